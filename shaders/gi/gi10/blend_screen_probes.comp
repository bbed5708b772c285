// gi10-blend-screen-probes (§1.2 #16, §1.3 "blend"): each new probe's cells take their ray's
// radiance. With GI10_FLAG_HYSTERESIS (Gi10Settings::probeHysteresis, off by default) a cell is
// held back against the reprojected radiance where it brightens by more than 2x:
// blend = clamp(max(lA - lB - min(lA, lB), 0) / max(lA, lB), 0, 0.95)^2 (lA new luma, lB old),
// Capsaicin's "shadow-preserving biased hysteresis", which damps fireflies and takes darkening
// at once; on one noisy ray per cell that tends to the darker samples (docs/gi/gi10.md).
// One group per spawn tile, one thread per cell.
#version 460
#include "gi/gi10/gi10_common.glsl"

layout(local_size_x = GI10_GROUP_SIZE) in;
layout(push_constant, scalar) uniform Push { Gi10PassConstants pc; };

void main() {
  Gi10Constants k = Gi10ConstantsRef(pc.gi10).v;
  uint spawnIndex = gl_WorkGroupID.y * k.spawnGrid.x + gl_WorkGroupID.x;
  uvec2 spawnPixel = Gi10SpawnRef(k.spawn).v[spawnIndex];
  if (spawnPixel.x == GI10_NO_SPAWN) return;
  uint cell = gl_LocalInvocationIndex;
  uvec2 tile = spawnPixel / GI10_PROBE_SIZE;
  uint tileIndex = tile.y * k.probeGrid.x + tile.x;
  Gi10Ray ray = Gi10RaysRef(k.rays).v[spawnIndex * GI10_PROBE_CELLS + cell];
  vec3 radiance = ray.radiance;
  Gi10RadianceRef probeRadiance = Gi10RadianceRef(k.radiance);
  uint flags = Gi10ProbesRef(k.probes).v[tileIndex].flags;
  if ((k.flags & GI10_FLAG_HYSTERESIS) != 0u && (flags & GI10_PROBE_HISTORY) != 0u) {
    vec3 old = gi10UnpackCell(probeRadiance.v[tileIndex * GI10_PROBE_CELLS + cell]).rgb;
    float lA = gi10Luma(radiance), lB = gi10Luma(old);
    float m = max(lA, lB);
    float blend = m > 0.0 ? clamp(max(lA - lB - min(lA, lB), 0.0) / m, 0.0, 0.95) : 0.0;
    radiance = mix(radiance, old, blend * blend);
  }
  probeRadiance.v[tileIndex * GI10_PROBE_CELLS + cell] = gi10PackCell(radiance, ray.hitDistance);
}
