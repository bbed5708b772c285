// scene-refit-blas: after scene-deform posed the deforming meshes' vertices, copies the posed
// positions into their triangles and refits their BLAS boxes, tree kept. One workgroup per mesh
// walks its plan's levels from the deepest up (as scene-refit-tlas does for the TLAS); the
// barriers sit in uniform control flow (lavapipe 22.3 ends invocations at a barrier in divergent
// flow: docs/testing.md). A refit never moves a triangle between leaves, so a pose far from the
// one the tree was built for traces slower, never wrongly (docs/ray-tracing.md, "Deforming
// meshes").
#version 460
#include "shared/deform_io.h"
#include "shared/scene_layout.h"

layout(local_size_x = BLAS_REFIT_GROUP_SIZE) in;
layout(push_constant, scalar) uniform Push { BlasRefitConstants pc; };
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer Meshes {
  GpuRefitBlas v[];
};
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer Uints { uint v[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer Geometries {
  GpuGeometry v[];
};
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer Positions {
  vec3 v[];
};
layout(buffer_reference, scalar, buffer_reference_align = 4) coherent buffer Triangles {
  GpuTriangle v[];
};
layout(buffer_reference, scalar, buffer_reference_align = 4) coherent buffer Nodes {
  GpuBvhNode v[];
};
layout(buffer_reference, scalar, buffer_reference_align = 4) coherent buffer WideNodes {
  GpuWideBvhNode v[];
};
layout(buffer_reference, scalar, buffer_reference_align = 4) coherent buffer Boxes { vec4 v[]; };

struct Box {
  vec3 lo;
  vec3 hi;
};

const Box kEmptyBox = Box(vec3(1e30), vec3(-1e30));

Box join(Box a, Box b) { return Box(min(a.lo, b.lo), max(a.hi, b.hi)); }

// ---- the posed triangles ----------------------------------------------------------------------

void poseTriangle(GpuRefitBlas mesh, uint slot) {
  Triangles triangles = Triangles(pc.triangles);
  GpuTriangle tri = triangles.v[slot];
  GpuGeometry g = Geometries(pc.geometries).v[mesh.geometryBase + (tri.geometry & 0x7FFFFFFFu)];
  uint base = g.firstIndex + 3u * tri.primitive;
  Uints indices = Uints(pc.indices);
  Positions positions = Positions(pc.positions);
  triangles.v[slot].v0 = positions.v[g.vertexOffset + indices.v[base]];
  triangles.v[slot].v1 = positions.v[g.vertexOffset + indices.v[base + 1u]];
  triangles.v[slot].v2 = positions.v[g.vertexOffset + indices.v[base + 2u]];
}

// The box of triangles[first .. first + count): exact, as the builder's (min and max only).
Box leafBox(uint first, uint count) {
  Box box = kEmptyBox;
  Triangles triangles = Triangles(pc.triangles);
  for (uint k = first; k < first + count; ++k) {
    GpuTriangle t = triangles.v[k];
    box.lo = min(box.lo, min(t.v0, min(t.v1, t.v2)));
    box.hi = max(box.hi, max(t.v0, max(t.v1, t.v2)));
  }
  return box;
}

// ---- the 2-wide layout ------------------------------------------------------------------------

Box binaryChildBox(uint index, uint count) {
  if (count > 0u) return leafBox(index, count);
  if (index == BVH_INVALID) return kEmptyBox;
  GpuBvhNode child = Nodes(pc.blasNodes).v[index];
  return Box(min(child.leftMin, child.rightMin), max(child.leftMax, child.rightMax));
}

void refitBinaryNode(uint node) {
  Nodes nodes = Nodes(pc.blasNodes);
  Box left = binaryChildBox(nodes.v[node].leftIndex, nodes.v[node].leftCount);
  Box right = binaryChildBox(nodes.v[node].rightIndex, nodes.v[node].rightCount);
  nodes.v[node].leftMin = left.lo;
  nodes.v[node].leftMax = left.hi;
  nodes.v[node].rightMin = right.lo;
  nodes.v[node].rightMax = right.hi;
}

Box binaryNodeBox(uint node) { return binaryChildBox(node, 0u); }

// ---- the 8-wide compressed layout (the quantisation of src/rt/wide_bvh.cpp) ---------------------

uint wideByte(uvec2 bytes, uint slot) {
  return (((slot & 4u) != 0u ? bytes.y : bytes.x) >> ((slot & 3u) * 8u)) & 0xFFu;
}

void setWideByte(inout uvec2 bytes, uint slot, uint value) {
  uint shift = (slot & 3u) * 8u;
  if ((slot & 4u) != 0u)
    bytes.y |= value << shift;
  else
    bytes.x |= value << shift;
}

float decodePlane(float origin, uint q, float scale) {
  precise float plane = origin + float(q) * scale;
  return plane;
}

// The smallest power-of-two step 2^e whose 255 steps from lo reach hi in float.
int gridExponent(float lo, float hi) {
  int e = -126;
  float extent = hi - lo;
  if (extent > 0.0) {
    int exponent;
    frexp(extent / 255.0, exponent);
    e = max(e, exponent - 1);
  }
  while (e < 127 && decodePlane(lo, 255u, ldexp(1.0, e)) < hi) ++e;
  while (e > -126 && decodePlane(lo, 255u, ldexp(1.0, e - 1)) >= hi) --e;
  return e;
}

Box wideSlotBox(GpuWideBvhNode n, uint slot) {
  uint meta = wideByte(n.meta, slot);
  uint interiorMask = n.exponentsAndMask >> 24;
  if ((interiorMask & (1u << slot)) != 0u) {
    uint child = n.childBase + bitCount(interiorMask & ((1u << slot) - 1u));
    Boxes boxes = Boxes(pc.wideBoxes);
    return Box(boxes.v[2u * child].xyz, boxes.v[2u * child + 1u].xyz);
  }
  return leafBox(n.triangleBase + (meta & 0x1Fu), bitCount(meta >> 5));
}

void refitWideNode(uint node) {
  WideNodes nodes = WideNodes(pc.blasNodes);
  GpuWideBvhNode n = nodes.v[node];
  Box slotBox[8];
  Box box = kEmptyBox;
  for (uint slot = 0u; slot < 8u; ++slot) {
    slotBox[slot] = wideByte(n.meta, slot) == 0u ? kEmptyBox : wideSlotBox(n, slot);
    box = join(box, slotBox[slot]);
  }
  vec3 scale;
  uint exponents = n.exponentsAndMask & 0xFF000000u;
  for (int axis = 0; axis < 3; ++axis) {
    int e = gridExponent(box.lo[axis], box.hi[axis]);
    scale[axis] = ldexp(1.0, e);
    exponents |= uint(e + int(BVH_WIDE_EXPONENT_BIAS)) << (8 * axis);
  }
  uvec2 lo[3] = uvec2[3](uvec2(0u), uvec2(0u), uvec2(0u));
  uvec2 hi[3] = uvec2[3](uvec2(0u), uvec2(0u), uvec2(0u));
  for (uint slot = 0u; slot < 8u; ++slot) {
    if (wideByte(n.meta, slot) == 0u) continue;
    for (int axis = 0; axis < 3; ++axis) {
      float o = box.lo[axis], s = scale[axis];
      uint qlo = uint(clamp(floor((slotBox[slot].lo[axis] - o) / s), 0.0, 255.0));
      uint qhi = uint(clamp(ceil((slotBox[slot].hi[axis] - o) / s), 0.0, 255.0));
      while (qlo > 0u && decodePlane(o, qlo, s) > slotBox[slot].lo[axis]) --qlo;
      while (qhi < 255u && decodePlane(o, qhi, s) < slotBox[slot].hi[axis]) ++qhi;
      setWideByte(lo[axis], slot, qlo);
      setWideByte(hi[axis], slot, qhi);
    }
  }
  nodes.v[node].origin = box.lo;
  nodes.v[node].exponentsAndMask = exponents;
  nodes.v[node].quantLoX = lo[0];
  nodes.v[node].quantLoY = lo[1];
  nodes.v[node].quantLoZ = lo[2];
  nodes.v[node].quantHiX = hi[0];
  nodes.v[node].quantHiY = hi[1];
  nodes.v[node].quantHiZ = hi[2];
  Boxes boxes = Boxes(pc.wideBoxes);
  boxes.v[2u * node] = vec4(box.lo, 0.0);
  boxes.v[2u * node + 1u] = vec4(box.hi, 0.0);
}

// -------------------------------------------------------------------------------------------------

void main() {
  GpuRefitBlas mesh = Meshes(pc.meshes).v[gl_WorkGroupID.x];
  for (uint k = gl_LocalInvocationIndex; k < mesh.triangleCount; k += BLAS_REFIT_GROUP_SIZE)
    poseTriangle(mesh, mesh.triangleFirst + k);
  memoryBarrierBuffer();
  barrier();
  Uints plan = Uints(pc.plan);
  for (uint level = 0u; level < mesh.levels; ++level) {
    uint begin = mesh.planFirst + plan.v[mesh.levelStart + level];
    uint end = mesh.planFirst + plan.v[mesh.levelStart + level + 1u];
    for (uint k = begin + gl_LocalInvocationIndex; k < end; k += BLAS_REFIT_GROUP_SIZE) {
      if (pc.blasLayout == BVH_LAYOUT_WIDE)
        refitWideNode(plan.v[k]);
      else
        refitBinaryNode(plan.v[k]);
    }
    memoryBarrierBuffer();
    barrier();
  }
  if (gl_LocalInvocationIndex != 0u) return;
  Box root;
  if (pc.blasLayout == BVH_LAYOUT_WIDE) {
    Boxes boxes = Boxes(pc.wideBoxes);
    root = Box(boxes.v[2u * mesh.root].xyz, boxes.v[2u * mesh.root + 1u].xyz);
  } else {
    root = binaryNodeBox(mesh.root);
  }
  Boxes meshBounds = Boxes(pc.meshBounds);
  meshBounds.v[2u * mesh.mesh] = vec4(root.lo, 0.0);
  meshBounds.v[2u * mesh.mesh + 1u] = vec4(root.hi, 0.0);
}
