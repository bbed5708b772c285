#include "rt/cpu_trace.h"

#include <algorithm>
#include <bit>
#include <stdexcept>

#include "rt/wide_bvh.h"
#include "shared/ray_triangle.h"

namespace bounce::rt {
namespace {

// 1 + 2 * gamma(3) with gamma(n) = n u / (1 - n u), u = 2^-24 (Ize 2013, "Robust BVH ray
// traversal"): scaling the far slab distance by it keeps the float box test conservative.
constexpr float kRobustFarScale = 1.0000004f;
// Direction components smaller than this are replaced by it (with their sign) before
// inverting, so a slab distance is never 0 * inf = NaN.
constexpr float kMinDirection = 1e-20f;
// The end of a level's entries (never a valid stack entry).
constexpr uint32_t kNoEntry = 0xFFFFFFFFu;
constexpr uint32_t kEntryKindBits = gpu::BVH_STACK_INSTANCE | gpu::BVH_STACK_LEAF;

// A ray prepared for one space (world, or one instance's object space).
struct SpaceRay {
  glm::vec3 origin;
  glm::vec3 invDir;
  gpu::RayShear shear;
};

SpaceRay prepareRay(const glm::vec3& origin, const glm::vec3& direction) {
  SpaceRay r;
  r.origin = origin;
  for (int axis = 0; axis < 3; ++axis) {
    float d = direction[axis];
    if (std::abs(d) < kMinDirection) d = d < 0.0f ? -kMinDirection : kMinDirection;
    r.invDir[axis] = 1.0f / d;
  }
  r.shear = gpu::makeRayShear(direction);
  return r;
}

glm::vec3 transformPoint(const gpu::vec4 rows[3], const glm::vec3& p) {
  return {glm::dot(glm::vec3(rows[0]), p) + rows[0].w, glm::dot(glm::vec3(rows[1]), p) + rows[1].w,
          glm::dot(glm::vec3(rows[2]), p) + rows[2].w};
}

glm::vec3 transformVector(const gpu::vec4 rows[3], const glm::vec3& v) {
  return {glm::dot(glm::vec3(rows[0]), v), glm::dot(glm::vec3(rows[1]), v),
          glm::dot(glm::vec3(rows[2]), v)};
}

// A mirroring transform turns counter-clockwise triangles clockwise (glTF: the winding of a
// node with a negative determinant is reversed).
bool mirrors(const gpu::vec4 rows[3]) {
  return glm::dot(glm::vec3(rows[0]), glm::cross(glm::vec3(rows[1]), glm::vec3(rows[2]))) < 0.0f;
}

struct BoxHit {
  bool hit;
  float tNear;
};

// Slab test with the near plane picked by the sign of invDir, so an inverted (empty) box has
// tNear > tFar and is never entered.
BoxHit intersectBox(const SpaceRay& ray, const glm::vec3& lo, const glm::vec3& hi, float tMin,
                    float tMax) {
  float tNear = tMin, tFar = tMax;
  for (int axis = 0; axis < 3; ++axis) {
    const bool negative = ray.invDir[axis] < 0.0f;
    const float nearPlane = negative ? hi[axis] : lo[axis];
    const float farPlane = negative ? lo[axis] : hi[axis];
    tNear = std::max(tNear, (nearPlane - ray.origin[axis]) * ray.invDir[axis]);
    tFar = std::min(tFar, (farPlane - ray.origin[axis]) * ray.invDir[axis] * kRobustFarScale);
  }
  return {tNear <= tFar, tNear};
}

// The stack entry of a child slot that is a leaf or an interior node (shared/scene_layout.h).
uint32_t childEntry(bool inBlas, uint32_t index, uint32_t count) {
  if (count == 0) return index;
  return inBlas ? (gpu::BVH_STACK_LEAF | ((count - 1) << gpu::BVH_STACK_LEAF_COUNT_SHIFT) | index)
                : (index | gpu::BVH_STACK_INSTANCE);
}

// The children of a binary node (TLAS, or a binary BLAS) that the ray enters before tMax.
struct EnteredChildren {
  uint32_t nearer;   // the nearer entered child's entry, when any is entered
  uint32_t farther;  // the other one's, when both are
  bool any;
  bool both;
};

EnteredChildren enterBinaryNode(const gpu::GpuBvhNode& node, const SpaceRay& ray, float tMin,
                                float tMax, bool inBlas) {
  const BoxHit left = intersectBox(ray, node.leftMin, node.leftMax, tMin, tMax);
  const BoxHit right = intersectBox(ray, node.rightMin, node.rightMax, tMin, tMax);
  const uint32_t leftEntry = childEntry(inBlas, node.leftIndex, node.leftCount);
  const uint32_t rightEntry = childEntry(inBlas, node.rightIndex, node.rightCount);
  const bool leftNear = left.hit && (!right.hit || left.tNear <= right.tNear);
  return {leftNear ? leftEntry : rightEntry, leftNear ? rightEntry : leftEntry,
          left.hit || right.hit, left.hit && right.hit};
}

// An instance as its BLAS is traversed: the ray in object space (same t in both spaces, because
// the direction is not normalised) and what a hit records of the instance.
struct InstanceSpace {
  SpaceRay ray;
  uint32_t instance = 0;
  uint32_t geometryBase = 0;
  uint32_t blasRoot = 0;
  bool mirrored = false;
};

InstanceSpace enterInstance(std::span<const gpu::GpuInstance> instances, uint32_t index,
                            const Ray& ray) {
  const gpu::GpuInstance& instance = instances[index];
  return {prepareRay(transformPoint(instance.worldToObject, ray.origin),
                     transformVector(instance.worldToObject, ray.direction)),
          index, instance.geometryBase, instance.blasRoot, mirrors(instance.worldToObject)};
}

// Tests one triangle of the instance's BLAS; an accepted hit before tMax replaces result and
// becomes the new tMax. Returns whether it did.
bool hitTriangle(const gpu::GpuTriangle& tri, const InstanceSpace& space, float tMin, float& tMax,
                 const AlphaTest& alphaTest, TraceHit& result) {
  const gpu::TriangleHit h =
      gpu::intersectTriangle(space.ray.origin, space.ray.shear, tri.v0, tri.v1, tri.v2, tMin, tMax);
  if (!h.hit) return false;
  const uint32_t geometry = space.geometryBase + (tri.geometry & ~gpu::GPU_TRIANGLE_ALPHA_TESTED);
  if ((tri.geometry & gpu::GPU_TRIANGLE_ALPHA_TESTED) && alphaTest &&
      !alphaTest(space.instance, geometry, tri.primitive, h.b1, h.b2))
    return false;
  result = {true,          h.t,  space.instance, geometry,
            tri.primitive, h.b1, h.b2,           h.frontFacing != space.mirrored};
  tMax = h.t;
  return true;
}

}  // namespace

// The loop of shaders/rt/trace.glsl, step by step: interior nodes until a leaf, an instance or
// nothing is next; then BLAS leaves; then a level change.
template <bool kAnyHit>
TraceHit CpuTracer::traverse(const Ray& ray, float tMax, const AlphaTest& alphaTest) const {
  TraceHit result;
  const float tMin = ray.tMin;
  const SpaceRay worldRay = prepareRay(ray.origin, ray.direction);
  // The level being traversed: the world ray in the TLAS, the entered instance in a BLAS.
  InstanceSpace space{worldRay};

  uint32_t stack[gpu::BVH_STACK_SIZE];
  uint32_t stackSize = 0;
  bool inBlas = false;
  uint32_t blasStackBase = 0;
  uint32_t entry = 0;  // the TLAS root
  auto popWithinLevel = [&] {
    const uint32_t base = inBlas ? blasStackBase : 0;
    return stackSize > base ? stack[--stackSize] : kNoEntry;
  };

  while (true) {
    while ((entry & kEntryKindBits) == 0) {  // interior nodes
      const gpu::GpuBvhNode& node = inBlas ? arrays_.blasNodes[entry] : arrays_.tlasNodes[entry];
      const EnteredChildren c = enterBinaryNode(node, space.ray, tMin, tMax, inBlas);
      if (c.both) {
        if (stackSize == gpu::BVH_STACK_SIZE)
          throw std::logic_error("BVH traversal stack overflow: tree deeper than its contract");
        stack[stackSize++] = c.farther;
      }
      entry = c.any ? c.nearer : popWithinLevel();
    }
    while ((entry & kEntryKindBits) == gpu::BVH_STACK_LEAF) {  // BLAS leaves
      const uint32_t first = entry & gpu::BVH_STACK_LEAF_INDEX_MASK;
      const uint32_t count = ((entry & ~kEntryKindBits) >> gpu::BVH_STACK_LEAF_COUNT_SHIFT) + 1;
      for (uint32_t k = first; k < first + count; ++k)
        if (hitTriangle(arrays_.triangles[k], space, tMin, tMax, alphaTest, result) && kAnyHit)
          return result;
      entry = popWithinLevel();
    }
    if (entry == kNoEntry) {
      if (inBlas && stackSize == blasStackBase) {  // the instance is done: back to the world ray
        inBlas = false;
        space.ray = worldRay;
      }
      if (stackSize == 0) return result;
      entry = stack[--stackSize];
      continue;
    }
    if ((entry & kEntryKindBits) == 0) continue;  // a node popped after the leaves
    if (inBlas || (entry & kEntryKindBits) != gpu::BVH_STACK_INSTANCE)
      throw std::logic_error("BVH traversal: an instance entry inside a BLAS");
    space = enterInstance(arrays_.instances, entry & ~gpu::BVH_STACK_INSTANCE, ray);
    inBlas = true;
    blasStackBase = stackSize;
    entry = space.blasRoot;
  }
}

// ---- the wide BLAS layout (scene_bvh.h, "Wide BLAS traversal"; traceSceneWide in trace.glsl) --

template <bool kAnyHit>
TraceHit CpuTracer::traverseWide(const Ray& ray, float tMax, const AlphaTest& alphaTest) const {
  TraceHit result;
  const float tMin = ray.tMin;
  const SpaceRay worldRay = prepareRay(ray.origin, ray.direction);
  uint32_t stack[gpu::BVH_STACK_SIZE / 2];
  uint32_t stackSize = 0;
  auto pop = [&] { return stackSize > 0 ? stack[--stackSize] : kNoEntry; };
  uint32_t entry = 0;  // the TLAS root
  while (true) {
    while ((entry & gpu::BVH_STACK_INSTANCE) == 0) {  // TLAS interior nodes
      const EnteredChildren c =
          enterBinaryNode(arrays_.tlasNodes[entry], worldRay, tMin, tMax, false);
      if (c.both) {
        if (stackSize == gpu::BVH_STACK_SIZE / 2)
          throw std::logic_error("TLAS traversal stack overflow: tree deeper than its contract");
        stack[stackSize++] = c.farther;
      }
      entry = c.any ? c.nearer : pop();
    }
    if (entry == kNoEntry) return result;
    if (traverseWideBlas<kAnyHit>(entry & ~gpu::BVH_STACK_INSTANCE, ray, tMax, alphaTest, result))
      return result;
    entry = pop();
  }
}

template <bool kAnyHit>
bool CpuTracer::traverseWideBlas(uint32_t instanceIndex, const Ray& ray, float& tMax,
                                 const AlphaTest& alphaTest, TraceHit& result) const {
  const InstanceSpace space = enterInstance(arrays_.instances, instanceIndex, ray);
  const glm::vec3& invDir = space.ray.invDir;
  const uint32_t octant =
      (invDir.x < 0.0f ? 1u : 0u) | (invDir.y < 0.0f ? 2u : 0u) | (invDir.z < 0.0f ? 4u : 0u);
  const uint32_t octantInv = 7u ^ octant;
  constexpr uint32_t kHitBits = 0xFF000000u;

  glm::uvec2 stack[gpu::BVH_WIDE_STACK_SIZE];
  uint32_t stackSize = 0;
  glm::uvec2 group(space.blasRoot, 0x80000000u);
  while (true) {
    if ((group.y & kHitBits) == 0) {
      if (stackSize == 0) return false;
      group = stack[--stackSize];
    }
    const uint32_t bit = 31u - uint32_t(std::countl_zero(group.y));
    group.y &= ~(1u << bit);
    const uint32_t slot = (bit - 24u) ^ octantInv;
    const uint32_t nodeIndex =
        group.x + uint32_t(std::popcount(group.y & 0xFFu & ((1u << slot) - 1u)));
    if ((group.y & kHitBits) != 0) {
      if (stackSize == gpu::BVH_WIDE_STACK_SIZE)
        throw std::logic_error("wide BVH traversal stack overflow: tree deeper than its contract");
      stack[stackSize++] = group;
    }
    const gpu::GpuWideBvhNode& node = arrays_.blasWideNodes[nodeIndex];
    const uint32_t interiorMask = node.exponentsAndMask >> 24;
    uint32_t interiorHits = 0, triangleHits = 0;
    for (uint32_t s = 0; s < 8; ++s) {
      const uint32_t meta = wideByte(node.meta, s);
      if (meta == 0) continue;
      const Aabb box = decodeWideChildBox(node, s);
      if (!intersectBox(space.ray, box.min, box.max, ray.tMin, tMax).hit) continue;
      if (interiorMask & (1u << s))
        interiorHits |= 1u << (24u + (s ^ octantInv));
      else
        triangleHits |= (meta >> 5) << (meta & 31u);
    }
    group = glm::uvec2(node.childBase, interiorHits | interiorMask);
    while (triangleHits != 0) {
      const uint32_t k = node.triangleBase + uint32_t(std::countr_zero(triangleHits));
      triangleHits &= triangleHits - 1u;
      if (hitTriangle(arrays_.triangles[k], space, ray.tMin, tMax, alphaTest, result) && kAnyHit)
        return true;
    }
  }
}

TraceHit CpuTracer::closestHit(const Ray& ray, float tMax, const AlphaTest& alphaTest) const {
  if (arrays_.layout == BvhLayout::Wide) return traverseWide<false>(ray, tMax, alphaTest);
  return traverse<false>(ray, tMax, alphaTest);
}

bool CpuTracer::anyHit(const Ray& ray, float tMax, const AlphaTest& alphaTest) const {
  if (arrays_.layout == BvhLayout::Wide) return traverseWide<true>(ray, tMax, alphaTest).hit;
  return traverse<true>(ray, tMax, alphaTest).hit;
}

// ---- brute force ------------------------------------------------------------------------------

namespace {

// Mesh bounds in object space, computed from the Scene itself (not from any BVH).
Aabb meshBounds(const Mesh& mesh) {
  Aabb b;
  for (const Geometry& g : mesh.geometries)
    for (const glm::vec3& p : g.positions) b.extend(p);
  return b;
}

// World bounds of an instance, from the 8 transformed corners of its object-space box,
// inflated by a relative 1e-3 of its size (plus a tiny absolute term) so that the cull below can
// never reject a triangle the float triangle test would hit.
Aabb inflatedWorldBounds(const Aabb& object, const glm::mat4& objectToWorld) {
  Aabb world;
  if (object.empty()) return world;
  for (int corner = 0; corner < 8; ++corner) {
    glm::vec3 p{corner & 1 ? object.max.x : object.min.x, corner & 2 ? object.max.y : object.min.y,
                corner & 4 ? object.max.z : object.min.z};
    world.extend(glm::vec3(objectToWorld * glm::vec4(p, 1.0f)));
  }
  glm::vec3 margin = 1e-3f * (world.extent() + glm::vec3(glm::length(world.max - world.min))) +
                     glm::vec3(1e-6f) * (glm::abs(world.min) + glm::abs(world.max));
  world.min -= margin;
  world.max += margin;
  return world;
}

// Whether the segment (tMin, tMax) of the ray touches the box, in double precision.
bool segmentTouchesBox(const Ray& ray, float tMax, const Aabb& box) {
  if (box.empty()) return false;
  double enter = ray.tMin, exit = tMax;
  for (int axis = 0; axis < 3; ++axis) {
    double o = ray.origin[axis], d = ray.direction[axis];
    if (d == 0.0) {
      if (o < box.min[axis] || o > box.max[axis]) return false;
      continue;
    }
    double t0 = (box.min[axis] - o) / d, t1 = (box.max[axis] - o) / d;
    enter = std::max(enter, std::min(t0, t1));
    exit = std::min(exit, std::max(t0, t1));
  }
  return enter <= exit;
}

}  // namespace

BruteForceTracer::BruteForceTracer(const Scene& scene) : scene_(scene) {
  geometryBase_.resize(scene.meshes.size());
  for (size_t m = 1; m < scene.meshes.size(); ++m)
    geometryBase_[m] = geometryBase_[m - 1] + uint32_t(scene.meshes[m - 1].geometries.size());
  std::vector<Aabb> bounds(scene.meshes.size());
  for (size_t m = 0; m < scene.meshes.size(); ++m) bounds[m] = meshBounds(scene.meshes[m]);
  for (const Instance& instance : scene.instances) {
    gpu::GpuInstance transform{};
    setInstanceTransform(transform, instance.transform);
    instances_.push_back({transform, inflatedWorldBounds(bounds[instance.mesh], instance.transform),
                          glm::determinant(glm::mat3(instance.transform)) < 0.0f});
  }
}

// Every triangle of every instance whose (inflated) world box the ray segment touches, in object
// space. The ray is taken there exactly as the traversal does it (same inverse, same
// arithmetic), so both see bit-identical object-space rays and any disagreement is the BVH's.
template <bool kAnyHit>
TraceHit BruteForceTracer::trace(const Ray& ray, float tMax, const AlphaTest& alphaTest) const {
  TraceHit result;
  for (uint32_t i = 0; i < scene_.instances.size(); ++i) {
    const PreparedInstance& prepared = instances_[i];
    if (prepared.transform.flags & gpu::GPU_INSTANCE_HIDDEN) continue;  // scaled to nothing
    if (!segmentTouchesBox(ray, tMax, prepared.worldBounds)) continue;
    const Instance& instance = scene_.instances[i];
    const glm::vec3 origin = transformPoint(prepared.transform.worldToObject, ray.origin);
    const glm::vec3 direction = transformVector(prepared.transform.worldToObject, ray.direction);
    const gpu::RayShear shear = gpu::makeRayShear(direction);
    const Mesh& mesh = scene_.meshes[instance.mesh];
    for (uint32_t g = 0; g < mesh.geometries.size(); ++g) {
      const Geometry& geometry = mesh.geometries[g];
      const bool alphaTested =
          scene_.materials[geometry.material].alphaMode != AlphaMode::Opaque && alphaTest;
      const uint32_t globalGeometry = geometryBase_[instance.mesh] + g;
      for (uint32_t p = 0; p < geometry.triangleCount(); ++p) {
        const uint32_t* index = &geometry.indices[size_t(p) * 3];
        gpu::TriangleHit h = gpu::intersectTriangle(origin, shear, geometry.positions[index[0]],
                                                    geometry.positions[index[1]],
                                                    geometry.positions[index[2]], ray.tMin, tMax);
        if (!h.hit) continue;
        if (alphaTested && !alphaTest(i, globalGeometry, p, h.b1, h.b2)) continue;
        result = {true, h.t, i, globalGeometry, p, h.b1, h.b2, h.frontFacing != prepared.mirrored};
        if constexpr (kAnyHit) return result;
        tMax = h.t;
      }
    }
  }
  return result;
}

TraceHit BruteForceTracer::closestHit(const Ray& ray, float tMax,
                                      const AlphaTest& alphaTest) const {
  return trace<false>(ray, tMax, alphaTest);
}

bool BruteForceTracer::anyHit(const Ray& ray, float tMax, const AlphaTest& alphaTest) const {
  return trace<true>(ray, tMax, alphaTest).hit;
}

TraceHit closestHitBruteForce(const Scene& scene, const Ray& ray, float tMax,
                              const AlphaTest& alphaTest) {
  return BruteForceTracer(scene).closestHit(ray, tMax, alphaTest);
}

bool anyHitBruteForce(const Scene& scene, const Ray& ray, float tMax, const AlphaTest& alphaTest) {
  return BruteForceTracer(scene).anyHit(ray, tMax, alphaTest);
}

}  // namespace bounce::rt
