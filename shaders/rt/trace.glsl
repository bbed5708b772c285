// Software ray tracing over the two-level BVH (shaders/shared/scene_layout.h): one tracing
// interface for every consumer (STYLE.md "What we take" 8):
//   TraceHit traceClosest(origin, direction, tMin, tMax, alphaTest)
//   bool     traceVisibility(origin, direction, tMin, tMax, alphaTest)  // true = unoccluded
// The node layout and the traversal contract are written down in src/rt/scene_bvh.h; in short,
// one stack serves the TLAS and the BLAS: entering an instance transforms the ray into object
// space and remembers the stack height, and the world ray comes back when the stack drops to
// that height. src/rt/cpu_trace.cpp mirrors this loop step by step.
#ifndef BOUNCE_RT_TRACE_GLSL
#define BOUNCE_RT_TRACE_GLSL
#include "rt/alpha_test.glsl"
#include "rt/scene.glsl"
#include "shared/ray_triangle.h"

struct TraceHit {
  float t;
  uint instance;  // BVH_INVALID on a miss
  uint geometry;  // global geometry index
  uint primitive;
  vec2 barycentrics;
  bool frontFacing;
};

bool traceHitFound(TraceHit h) { return h.instance != BVH_INVALID; }

// The end of a level's entries (never a valid stack entry).
const uint NO_ENTRY = 0xFFFFFFFFu;
const uint STACK_KIND_BITS = BVH_STACK_INSTANCE | BVH_STACK_LEAF;

// Reciprocal with components below 1e-20 in magnitude replaced by +-1e-20 (sign of the
// component, -0 counting as +), so the slab test never computes 0 * inf.
vec3 safeReciprocal(vec3 d) {
  const float tiny = 1e-20;
  return 1.0 / vec3(abs(d.x) < tiny ? (d.x < 0.0 ? -tiny : tiny) : d.x,
                    abs(d.y) < tiny ? (d.y < 0.0 ? -tiny : tiny) : d.y,
                    abs(d.z) < tiny ? (d.z < 0.0 ? -tiny : tiny) : d.z);
}

// Per-ray slab set-up: near/far planes are picked by the sign of the reciprocal direction,
// which makes the inverted box of an empty child miss without a special case.
struct BoxRay {
  vec3 origin;
  vec3 invDir;
  bvec3 negative;
};

BoxRay makeBoxRay(vec3 origin, vec3 dir) {
  BoxRay r;
  r.origin = origin;
  r.invDir = safeReciprocal(dir);
  r.negative = lessThan(r.invDir, vec3(0.0));
  return r;
}

// Entry distance of the ray into the box, or +inf when it misses (tMin, tMax). The exit
// distance is widened by 1 + 2 gamma(3) so a hit the watertight triangle test finds is never
// culled by rounding (Ize 2013, "Robust BVH Ray Traversal"). The plane distances are written
// (plane - origin) * invDir and kept `precise`: the cheaper plane * invDir - origin * invDir,
// once fused into an FMA, wrongly rejects rays aimed at the edges of small boxes far from the
// origin (src/rt/cpu_trace.cpp uses the same form).
float intersectBox(vec3 boxMin, vec3 boxMax, BoxRay r, float tMin, float tMax) {
  vec3 nearPlane = mix(boxMin, boxMax, r.negative);
  vec3 farPlane = mix(boxMax, boxMin, r.negative);
  precise vec3 tNear = (nearPlane - r.origin) * r.invDir;
  precise vec3 tFar = (farPlane - r.origin) * r.invDir;
  float enter = max(max(tNear.x, tNear.y), max(tNear.z, tMin));
  float exit = min(min(tFar.x, tFar.y), min(tFar.z, tMax)) * 1.0000004;
  return enter <= exit ? enter : 1.0 / 0.0;
}

// State of the traversal at one level (world space for the TLAS, object space in a BLAS).
struct LevelRay {
  vec3 origin;
  vec3 dir;
  BoxRay box;
  RayShear shear;
};

LevelRay makeLevelRay(vec3 origin, vec3 dir) {
  LevelRay r;
  r.origin = origin;
  r.dir = dir;
  r.box = makeBoxRay(origin, dir);
  r.shear = makeRayShear(dir);
  return r;
}

// The stack entry of a child slot that is a leaf or an interior node (shared/scene_layout.h).
uint childEntry(bool inBlas, uint index, uint count) {
  if (count == 0u) return index;
  return inBlas ? (BVH_STACK_LEAF | ((count - 1u) << BVH_STACK_LEAF_COUNT_SHIFT) | index)
                : (index | BVH_STACK_INSTANCE);
}

// The children of a binary node (TLAS, or a binary BLAS) that the ray enters before tMax.
struct EnteredChildren {
  uint nearer;   // the nearer entered child's entry, when any is entered
  uint farther;  // the other one's, when both are
  bool any;
  bool both;
};

EnteredChildren enterBinaryNode(GpuBvhNode node, BoxRay ray, float tMin, float tMax,
                                bool inBlas) {
  float tLeft = intersectBox(node.leftMin, node.leftMax, ray, tMin, tMax);
  float tRight = intersectBox(node.rightMin, node.rightMax, ray, tMin, tMax);
  bool hitLeft = tLeft <= tMax;
  bool hitRight = tRight <= tMax;
  uint leftEntry = childEntry(inBlas, node.leftIndex, node.leftCount);
  uint rightEntry = childEntry(inBlas, node.rightIndex, node.rightCount);
  bool leftNear = hitLeft && (!hitRight || tLeft <= tRight);
  EnteredChildren c;
  c.nearer = leftNear ? leftEntry : rightEntry;
  c.farther = leftNear ? rightEntry : leftEntry;
  c.any = hitLeft || hitRight;
  c.both = hitLeft && hitRight;
  return c;
}

// An instance as its BLAS is traversed: the ray in object space (not renormalised, so t means
// the same in both spaces) and what a hit records of the instance.
struct InstanceSpace {
  LevelRay ray;
  uint instance;
  uint geometryBase;
  uint blasRoot;
  bool mirrored;  // a mirroring transform turns the triangles' winding around
};

InstanceSpace enterInstance(uint instance, vec3 worldOrigin, vec3 worldDir) {
  // GpuInstance's worldToObject rows and its indices: quarters 3..6 of its 112 bytes.
  QuadArray instances = QuadArray(scene.instances);
  vec4 worldToObject[3] = vec4[3](instances.v[7u * instance + 3u], instances.v[7u * instance + 4u],
                                  instances.v[7u * instance + 5u]);
  uvec4 indices = floatBitsToUint(instances.v[7u * instance + 6u]);
  InstanceSpace s;
  s.ray = makeLevelRay(transformPoint(worldToObject, worldOrigin),
                       transformVector(worldToObject, worldDir));
  s.instance = instance;
  s.blasRoot = indices.x;
  s.geometryBase = indices.y;
  s.mirrored =
      dot(worldToObject[0].xyz, cross(worldToObject[1].xyz, worldToObject[2].xyz)) < 0.0;
  return s;
}

// Tests triangle i of the instance's BLAS; an accepted hit nearer than best.t replaces best.
// Returns whether it did.
bool hitTriangle(uint i, InstanceSpace space, float tMin, bool alphaTest, inout TraceHit best) {
  GpuTriangle tri = loadTriangle(QuadArray(scene.triangles), i);
  TriangleHit h = intersectTriangle(space.ray.origin, space.ray.shear, tri.v0, tri.v1, tri.v2,
                                    tMin, best.t);
  // Most tests miss: leave before the geometry index and the alpha test (one expression for
  // both cost 1.5-2.5 % of shadow-ray time on an H200; docs/benchmarks.md, session 19).
  if (!h.hit) return false;
  uint geometry = space.geometryBase + (tri.geometry & ~GPU_TRIANGLE_ALPHA_TESTED);
  if (alphaTest && (tri.geometry & GPU_TRIANGLE_ALPHA_TESTED) != 0u &&
      !alphaAccepts(geometry, tri.primitive, vec2(h.b1, h.b2)))
    return false;
  best.t = h.t;
  best.instance = space.instance;
  best.geometry = geometry;
  best.primitive = tri.primitive;
  best.barycentrics = vec2(h.b1, h.b2);
  best.frontFacing = h.frontFacing != space.mirrored;
  return true;
}

// The shared traversal (src/rt/cpu_trace.cpp mirrors it). anyHit: stop at the first accepted
// hit. BLAS leaves go through the stack like nodes, so the loop runs as two inner loops, nodes
// then leaves (Aila and Laine 2009, "while-while"): the lanes of a warp fetch nodes together and
// test triangles together instead of taking turns (measured against testing a node's leaves as
// soon as it is fetched: docs/decisions.md).
TraceHit noHit(float tMax) {
  TraceHit best;
  best.t = tMax;
  best.instance = BVH_INVALID;
  best.geometry = BVH_INVALID;
  best.primitive = BVH_INVALID;
  best.barycentrics = vec2(0.0);
  best.frontFacing = false;
  return best;
}

TraceHit traceSceneBinary(vec3 worldOrigin, vec3 worldDir, float tMin, float tMax, bool alphaTest,
                          bool anyHit) {
  TraceHit best = noHit(tMax);
  if (scene.instanceCount == 0u) return best;

  uint stack[BVH_STACK_SIZE];
  int sp = 0;
  // The level being traversed: the world ray in the TLAS, the entered instance in a BLAS (its
  // other fields are first read after enterInstance has set them).
  InstanceSpace space;
  space.ray = makeLevelRay(worldOrigin, worldDir);
  QuadArray nodes = QuadArray(scene.tlasNodes);
  bool inBlas = false;
  int blasStackBase = 0;
  uint next = 0u;  // the TLAS root

  while (true) {
    // Interior nodes, until the next entry is a leaf, an instance or nothing.
    while ((next & STACK_KIND_BITS) == 0u) {
      EnteredChildren c =
          enterBinaryNode(loadBvhNode(nodes, next), space.ray.box, tMin, best.t, inBlas);
      if (c.both) stack[sp++] = c.farther;
      next = c.any ? c.nearer : (sp > (inBlas ? blasStackBase : 0) ? stack[--sp] : NO_ENTRY);
    }
    // BLAS leaves, until the next entry is not one.
    while ((next & STACK_KIND_BITS) == BVH_STACK_LEAF) {
      uint first = next & BVH_STACK_LEAF_INDEX_MASK;
      uint count = ((next & ~STACK_KIND_BITS) >> BVH_STACK_LEAF_COUNT_SHIFT) + 1u;
      for (uint i = first; i < first + count; ++i)
        if (hitTriangle(i, space, tMin, alphaTest, best) && anyHit) return best;
      next = sp > blasStackBase ? stack[--sp] : NO_ENTRY;
    }
    if (next == NO_ENTRY) {
      if (inBlas && sp == blasStackBase) {  // the instance is done: back to the world ray
        inBlas = false;
        space.ray = makeLevelRay(worldOrigin, worldDir);
        nodes = QuadArray(scene.tlasNodes);
      }
      if (sp == 0) break;
      next = stack[--sp];
      continue;
    }
    if (!inBlas && (next & BVH_STACK_INSTANCE) != 0u) {  // continue in the instance's BLAS
      space = enterInstance(next & ~BVH_STACK_INSTANCE, worldOrigin, worldDir);
      nodes = QuadArray(scene.blasNodes);
      blasStackBase = sp;
      inBlas = true;
      next = space.blasRoot;
    }
  }
  return best;
}

// ---- the wide compressed BLAS (BVH_LAYOUT_WIDE; src/rt/scene_bvh.h, "Wide BLAS traversal") ----

uint wideByte(uvec2 bytes, uint slot) {
  return (((slot & 4u) != 0u ? bytes.y : bytes.x) >> ((slot & 3u) * 8u)) & 0xFFu;
}

// A child's quantised box decoded on the node's grid: origin + q * 2^e, where q * 2^e is exact,
// so the one rounding of the sum gives the planes the builder checked to contain the child's
// exact box (src/rt/wide_bvh.cpp); then the same conservative slab test as the binary layout.
float intersectWideChild(GpuWideBvhNode node, vec3 scale, uint slot, BoxRay r, float tMin,
                         float tMax) {
  vec3 qLo = vec3(wideByte(node.quantLoX, slot), wideByte(node.quantLoY, slot),
                  wideByte(node.quantLoZ, slot));
  vec3 qHi = vec3(wideByte(node.quantHiX, slot), wideByte(node.quantHiY, slot),
                  wideByte(node.quantHiZ, slot));
  precise vec3 lo = node.origin + qLo * scale;
  precise vec3 hi = node.origin + qHi * scale;
  return intersectBox(lo, hi, r, tMin, tMax);
}

// Runs one instance's wide BLAS to completion (Ylitie, Karras and Laine 2017, §4): node groups
// (child base, hit bits 24..31 | interior mask) on a stack of their own; children visited in
// octant order (highest hit bit first), triangles of a node tested right after it. Returns true
// when anyHit found a hit (then in best).
bool traceBlasWide(uint instance, vec3 worldOrigin, vec3 worldDir, float tMin, bool alphaTest,
                   bool anyHit, inout TraceHit best) {
  InstanceSpace space = enterInstance(instance, worldOrigin, worldDir);
  bvec3 negative = space.ray.box.negative;
  uint octant = (negative.x ? 1u : 0u) | (negative.y ? 2u : 0u) | (negative.z ? 4u : 0u);
  uint octantInv = 7u ^ octant;
  QuadArray nodes = QuadArray(scene.blasNodes);

  uvec2 stack[BVH_WIDE_STACK_SIZE];
  int sp = 0;
  uvec2 group = uvec2(space.blasRoot, 0x80000000u);
  while (true) {
    if ((group.y & 0xFF000000u) == 0u) {
      if (sp == 0) return false;
      group = stack[--sp];
    }
    uint bit = uint(findMSB(group.y));
    group.y &= ~(1u << bit);
    uint slot = (bit - 24u) ^ octantInv;
    uint nodeIndex = group.x + bitCount(group.y & 0xFFu & ((1u << slot) - 1u));
    if ((group.y & 0xFF000000u) != 0u) stack[sp++] = group;

    GpuWideBvhNode node = loadWideBvhNode(nodes, nodeIndex);
    uint interiorMask = node.exponentsAndMask >> 24;
    vec3 scale = vec3(uintBitsToFloat((node.exponentsAndMask & 0xFFu) << 23),
                      uintBitsToFloat(((node.exponentsAndMask >> 8) & 0xFFu) << 23),
                      uintBitsToFloat(((node.exponentsAndMask >> 16) & 0xFFu) << 23));
    uint interiorHits = 0u;
    uint triangleHits = 0u;
    for (uint s = 0u; s < 8u; ++s) {
      uint meta = wideByte(node.meta, s);
      if (meta == 0u) continue;
      if (intersectWideChild(node, scale, s, space.ray.box, tMin, best.t) > best.t) continue;
      if ((interiorMask & (1u << s)) != 0u)
        interiorHits |= 1u << (24u + (s ^ octantInv));
      else
        triangleHits |= (meta >> 5) << (meta & 31u);
    }
    group = uvec2(node.childBase, interiorHits | interiorMask);

    while (triangleHits != 0u) {
      uint i = node.triangleBase + uint(findLSB(triangleHits));
      triangleHits &= triangleHits - 1u;
      if (hitTriangle(i, space, tMin, alphaTest, best) && anyHit) return true;
    }
  }
  return false;
}

// The 2-wide TLAS loop of traceSceneBinary with instance entries only; each instance's wide
// BLAS runs to completion before the next TLAS entry is popped.
TraceHit traceSceneWide(vec3 worldOrigin, vec3 worldDir, float tMin, float tMax, bool alphaTest,
                        bool anyHit) {
  TraceHit best = noHit(tMax);
  if (scene.instanceCount == 0u) return best;
  uint stack[BVH_STACK_SIZE / 2];
  int sp = 0;
  BoxRay ray = makeBoxRay(worldOrigin, worldDir);
  QuadArray nodes = QuadArray(scene.tlasNodes);
  uint next = 0u;  // the TLAS root
  while (true) {
    while ((next & BVH_STACK_INSTANCE) == 0u) {
      EnteredChildren c = enterBinaryNode(loadBvhNode(nodes, next), ray, tMin, best.t, false);
      if (c.both) stack[sp++] = c.farther;
      next = c.any ? c.nearer : (sp > 0 ? stack[--sp] : NO_ENTRY);
    }
    if (next == NO_ENTRY) break;
    if (traceBlasWide(next & ~BVH_STACK_INSTANCE, worldOrigin, worldDir, tMin, alphaTest, anyHit,
                      best))
      return best;
    next = sp > 0 ? stack[--sp] : NO_ENTRY;
  }
  return best;
}

// The scene's layout, set when the pipeline is created (BVH_SPEC_BLAS_LAYOUT), so the other loop
// is compiled out; else GpuSceneRefs::blasLayout, one uniform branch per ray, none per node
// (docs/ray-tracing.md, "Choosing the layout").
layout(constant_id = BVH_SPEC_BLAS_LAYOUT) const uint SPEC_BLAS_LAYOUT = BVH_LAYOUT_ANY;

TraceHit traceScene(vec3 worldOrigin, vec3 worldDir, float tMin, float tMax, bool alphaTest,
                    bool anyHit) {
  uint blasLayout = SPEC_BLAS_LAYOUT == BVH_LAYOUT_ANY ? scene.blasLayout : SPEC_BLAS_LAYOUT;
  if (blasLayout == BVH_LAYOUT_WIDE)
    return traceSceneWide(worldOrigin, worldDir, tMin, tMax, alphaTest, anyHit);
  return traceSceneBinary(worldOrigin, worldDir, tMin, tMax, alphaTest, anyHit);
}

layout(buffer_reference, scalar, buffer_reference_align = 4) buffer RayCounter { uint rays; };

// Counts one ray when the scene asks for it (GpuSceneRefs::rayCounting, a uniform branch that
// costs nothing when off). The lanes tracing together add their count with one atomic: one per
// ray would serialise millions of atomics on one address.
void countRay() {
  if (scene.rayCounting == 0u) return;
  uint lanes = subgroupBallotBitCount(subgroupBallot(true));
  if (subgroupElect()) atomicAdd(RayCounter(scene.rayCounter).rays, lanes);
}

TraceHit traceClosest(vec3 origin, vec3 dir, float tMin, float tMax, bool alphaTest) {
  countRay();
  return traceScene(origin, dir, tMin, tMax, alphaTest, false);
}

// The first accepted hit found on (tMin, tMax), not necessarily the closest.
TraceHit traceAnyHit(vec3 origin, vec3 dir, float tMin, float tMax, bool alphaTest) {
  countRay();
  return traceScene(origin, dir, tMin, tMax, alphaTest, true);
}

// True when nothing blocks the segment (tMin, tMax) of the ray.
bool traceVisibility(vec3 origin, vec3 dir, float tMin, float tMax, bool alphaTest) {
  return !traceHitFound(traceAnyHit(origin, dir, tMin, tMax, alphaTest));
}

#endif
