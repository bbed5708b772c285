// Ray binning within a workgroup (issue 22, "ray coherence"): a pass that traces one ray per
// pixel of a tile first sorts the tile's rays by direction, so that the lanes of a subgroup
// trace rays that leave for about the same part of the sphere from about the same place. They
// then walk the same nodes in the same order instead of a subgroup's worth of different paths
// through the tree. Each ray is still traced for its own pixel and gives the same answer, so
// the image does not change; only which invocation traces which ray does.
//
// The tile is the workgroup: RAY_BIN_GROUP_SIDE x RAY_BIN_GROUP_SIDE invocations, a ray or none
// each. A counting sort in shared memory over RAY_BIN_CELLS x RAY_BIN_CELLS cells of the
// octahedral map of directions, plus one last bin for invocations without a ray, which so end
// up together in the last subgroups (those then have nothing to trace).
#ifndef BOUNCE_RT_RAY_BINS_GLSL
#define BOUNCE_RT_RAY_BINS_GLSL

const uint RAY_BIN_GROUP_SIDE = 16u;  // the including pass's local size is this squared
const uint RAY_BIN_GROUP_THREADS = RAY_BIN_GROUP_SIDE * RAY_BIN_GROUP_SIDE;
const uint RAY_BIN_CELLS = 4u;
const uint RAY_BIN_NONE = RAY_BIN_CELLS * RAY_BIN_CELLS;
const uint RAY_BIN_COUNT = RAY_BIN_NONE + 1u;

shared uint rayBinStart[RAY_BIN_COUNT];
shared uint rayBinOrder[RAY_BIN_GROUP_THREADS];

// The cell of the octahedral map (Engelhardt and Dachsbacher 2008) holding `direction`.
uint rayBin(bool hasRay, vec3 direction) {
  if (!hasRay) return RAY_BIN_NONE;
  vec3 d = direction / max(abs(direction.x) + abs(direction.y) + abs(direction.z), 1e-20);
  vec2 p = d.z >= 0.0 ? d.xy : (1.0 - abs(d.yx)) * vec2(d.x >= 0.0 ? 1.0 : -1.0, d.y >= 0.0 ? 1.0 : -1.0);
  uvec2 cell = uvec2(clamp((p * 0.5 + 0.5) * float(RAY_BIN_CELLS), vec2(0.0), vec2(RAY_BIN_CELLS - 1u)));
  return cell.y * RAY_BIN_CELLS + cell.x;
}

// Every invocation of the group must call this (it has barriers), with its own ray. Returns
// the local invocation index (gl_LocalInvocationIndex) whose ray this invocation is to trace:
// the group's rays in the order of their bins.
uint binnedInvocation(bool hasRay, vec3 direction) {
  uint local = gl_LocalInvocationIndex;
  if (local < RAY_BIN_COUNT) rayBinStart[local] = 0u;
  barrier();
  uint bin = rayBin(hasRay, direction);
  uint rank = atomicAdd(rayBinStart[bin], 1u);
  barrier();
  if (local == 0u) {  // counts to starts (17 values: one invocation is quickest)
    uint start = 0u;
    for (uint b = 0u; b < RAY_BIN_COUNT; ++b) {
      uint count = rayBinStart[b];
      rayBinStart[b] = start;
      start += count;
    }
  }
  barrier();
  rayBinOrder[rayBinStart[bin] + rank] = local;
  barrier();
  return rayBinOrder[local];
}

#endif
