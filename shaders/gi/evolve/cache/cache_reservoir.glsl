// The reservoir of a cache entry (ReSTIR GI, Ouyang et al. 2021, temporal resampling): target
// function = luminance of the radiance a sample brought. L * W of the kept sample estimates
// the integral of radiance over the entry's direction bin.
#ifndef BOUNCE_GI_EVOLVE_CACHE_RESERVOIR_GLSL
#define BOUNCE_GI_EVOLVE_CACHE_RESERVOIR_GLSL
#include "gi/evolve/cache/cache_common.glsl"

void reservoirUpdateW(inout ClipmapEntry r) {
  float target = clipmapLuminance(r.radiance);
  r.W = target > 0.0 && r.M > 0.0 ? r.weightSum / (r.M * target) : 0.0;
}

// Merges one new candidate (drawn with density `pdf`) into the entry's history, whose M is
// first clamped to `historyCap` so the entry keeps adapting. u: uniform in [0, 1).
void reservoirMerge(inout ClipmapEntry r, vec3 radiance, vec3 direction, vec3 origin,
                    float hitDistance, float pdf, float historyCap, float u) {
  if (r.M > historyCap) {
    r.weightSum *= historyCap / r.M;
    r.M = historyCap;
  }
  float weight = clipmapLuminance(radiance) / pdf;
  r.weightSum += weight;
  r.M += 1.0;
  if (u * r.weightSum < weight) {
    r.radiance = radiance;
    r.direction = direction;
    r.origin = origin;
    r.hitDistance = hitDistance;
  }
  reservoirUpdateW(r);
}

// A validation ray re-traced the kept sample and found `radiance` now. The sample keeps its
// contribution weight, so the entry follows the change at once; a large change also cuts the
// history to `keptM` candidates so that new candidates take over quickly (ReSTIR GI §4.3).
void reservoirValidate(inout ClipmapEntry r, vec3 radiance, float keptM) {
  float before = clipmapLuminance(r.radiance);
  float after = clipmapLuminance(radiance);
  r.radiance = radiance;
  if (abs(after - before) > 0.25 * max(before, after)) r.M = min(r.M, keptM);
  r.weightSum = r.W * r.M * after;
}

#endif
