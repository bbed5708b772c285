// Visibility of a reservoir's sample x2 from a primary vertex x1: the shadow ray of
// gi-trace-spatial-validation-rays and of gi-restir-resolve's pixels beside occluders.
#ifndef BOUNCE_GI_EVOLVE_RESTIR_GI_VISIBILITY_GLSL
#define BOUNCE_GI_EVOLVE_RESTIR_GI_VISIBILITY_GLSL
#include "gi/evolve/restir/restir_gi_common.glsl"
#include "common/ray_offset.glsl"
#include "rt/trace.glsl"

// Whether x2 is visible from x1 (a sky sample: its direction escapes). Alpha-tested, like the
// rays that found the samples.
bool sampleVisible(PrimaryVertex x1, Reservoir r) {
  vec3 origin = offsetRayOrigin(x1.position, x1.geometricNormal);
  if (r.kind == RESTIR_GI_KIND_SKY)
    return traceVisibility(origin, normalize(r.samplePosition - x1.position), 0.0, 3.0e38, true);
  vec3 target = offsetRayOrigin(r.samplePosition, r.sampleNormal);
  return traceVisibility(origin, target - origin, 0.0, 1.0, true);
}

#endif
