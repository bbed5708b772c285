// What scene-refit-tlas (shaders/rt/scene_refit_tlas.comp) reads: the TLAS to refit in place,
// the instances' current placement, the meshes' object-space boxes and the refit plan of
// src/rt/scene_bvh.h (TlasRefitPlan: interior nodes deepest level first, then the levels'
// starts).
#ifndef BOUNCE_SHARED_TLAS_REFIT_IO_H
#define BOUNCE_SHARED_TLAS_REFIT_IO_H
#include "shared/compat.h"

BOUNCE_BEGIN_SHARED

struct TlasRefitConstants {
  DeviceAddress tlasNodes;   // GpuBvhNode[], rewritten in place
  DeviceAddress instances;   // GpuInstance[]
  DeviceAddress meshBounds;  // vec4[2 * meshes]: min.xyz, max.xyz of mesh m at 2m, 2m + 1
  DeviceAddress plan;        // uint[]: the plan's nodes, then its levels + 1 level starts
  uint levels;
  uint levelStartOffset;  // where the level starts begin in `plan`
  uint pad0;
  uint pad1;
};

// One workgroup refits the whole tree, a level per step with a barrier between steps.
BOUNCE_CONST uint TLAS_REFIT_GROUP_SIZE = 256u;

BOUNCE_END_SHARED
#endif
