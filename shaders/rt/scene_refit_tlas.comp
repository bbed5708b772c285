// scene-refit-tlas: rewrites the TLAS's boxes for the instances' current placement, its tree
// kept (src/rt/scene_bvh.h, refitTlas: the CPU reference, same arithmetic). One workgroup walks
// the plan's levels from the deepest up; the barrier between levels sits in uniform control
// flow (lavapipe 22.3 ends invocations at a barrier in divergent flow: docs/testing.md).
#version 460
#include "shared/scene_layout.h"
#include "shared/tlas_refit_io.h"

layout(local_size_x = TLAS_REFIT_GROUP_SIZE) in;
layout(push_constant, scalar) uniform Push { TlasRefitConstants pc; };
layout(buffer_reference, scalar, buffer_reference_align = 4) coherent buffer TlasNodes {
  GpuBvhNode v[];
};
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer Instances {
  GpuInstance v[];
};
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer MeshBounds {
  vec4 v[];
};
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer Plan { uint v[]; };

struct Box {
  vec3 lo;
  vec3 hi;
};

const Box kEmptyBox = Box(vec3(1e30), vec3(-1e30));

// instanceWorldBounds of src/rt/scene_bvh.cpp (Arvo 1990), with its padding for the rounding
// of the object-space ray. `precise` keeps the same unfused arithmetic as the CPU's.
Box instanceBox(uint instance) {
  GpuInstance inst = Instances(pc.instances).v[instance];
  if ((inst.flags & GPU_INSTANCE_HIDDEN) != 0u) return kEmptyBox;
  precise vec3 lo = MeshBounds(pc.meshBounds).v[2u * inst.mesh].xyz;
  precise vec3 hi = MeshBounds(pc.meshBounds).v[2u * inst.mesh + 1u].xyz;
  precise vec3 center = 0.5 * (lo + hi);
  precise vec3 halfExtent = 0.5 * (hi - lo);
  Box box;
  for (int r = 0; r < 3; ++r) {
    vec4 row = inst.objectToWorld[r];
    precise float worldCenter = row.x * center.x + row.y * center.y + row.z * center.z + row.w;
    precise float worldHalfExtent =
        abs(row.x) * halfExtent.x + abs(row.y) * halfExtent.y + abs(row.z) * halfExtent.z;
    precise float pad = 1e-5 * (abs(worldCenter) + worldHalfExtent);
    box.lo[r] = worldCenter - worldHalfExtent - pad;
    box.hi[r] = worldCenter + worldHalfExtent + pad;
  }
  return box;
}

// A child slot's box: a leaf's instance box, an interior child's two boxes joined.
Box childBox(uint index, uint count) {
  if (count > 0u) return instanceBox(index);
  if (index == BVH_INVALID) return kEmptyBox;
  GpuBvhNode child = TlasNodes(pc.tlasNodes).v[index];
  return Box(min(child.leftMin, child.rightMin), max(child.leftMax, child.rightMax));
}

void refitNode(uint node) {
  TlasNodes nodes = TlasNodes(pc.tlasNodes);
  Box left = childBox(nodes.v[node].leftIndex, nodes.v[node].leftCount);
  Box right = childBox(nodes.v[node].rightIndex, nodes.v[node].rightCount);
  nodes.v[node].leftMin = left.lo;
  nodes.v[node].leftMax = left.hi;
  nodes.v[node].rightMin = right.lo;
  nodes.v[node].rightMax = right.hi;
}

void main() {
  Plan plan = Plan(pc.plan);
  for (uint level = 0u; level < pc.levels; ++level) {
    uint begin = plan.v[pc.levelStartOffset + level];
    uint end = plan.v[pc.levelStartOffset + level + 1u];
    for (uint k = begin + gl_LocalInvocationIndex; k < end; k += TLAS_REFIT_GROUP_SIZE)
      refitNode(plan.v[k]);
    memoryBarrierBuffer();
    barrier();
  }
}
