// gi10-resolve-radiance-cache (§1.2 #15): each probe ray that landed in a hash-grid cell takes
// the cell's radiance, updated with this frame's samples (gi10-update-radiance-cache).
// One thread per probe ray.
#version 460
#include "gi/gi10/gi10_common.glsl"

layout(local_size_x = GI10_GROUP_SIZE) in;
layout(push_constant, scalar) uniform Push { Gi10PassConstants pc; };

void main() {
  Gi10Constants k = Gi10ConstantsRef(pc.gi10).v;
  uint rayIndex = gl_GlobalInvocationID.x;
  uint spawnIndex = rayIndex / GI10_PROBE_CELLS;
  if (spawnIndex >= k.spawnGrid.x * k.spawnGrid.y) return;
  if (Gi10SpawnRef(k.spawn).v[spawnIndex].x == GI10_NO_SPAWN) return;
  Gi10RaysRef rays = Gi10RaysRef(k.rays);
  uint cell = rays.v[rayIndex].cell;
  if (cell == GI10_NO_CELL) return;
  rays.v[rayIndex].radiance += Gi10CacheRef(k.cache).v[cell].radiance;
}
