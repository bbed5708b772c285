// The parallax of a reflection ray, which reflections-temporal and reflections-denoise-temporal
// compare under motion (ReflectionSettings and ReflectionDenoiseSettings::
// motionParallaxTolerance): hit distance / (camera distance of the reflecting point + hit
// distance), 1 for a miss. Screen motion under a camera move goes with one over depth, so this,
// not the hit distance, is what a reflection's motion and its history's comparison need.
#ifndef BOUNCE_PASSES_REFLECTION_PARALLAX_GLSL
#define BOUNCE_PASSES_REFLECTION_PARALLAX_GLSL
#include "gi/evolve/restir/restir_gi_common.glsl"
#include "shared/specular_io.h"

float rayParallax(float surfaceDistance, float hitDistance) {
  return hitDistance >= REFLECTION_MISS_DISTANCE ? 1.0 : hitDistance / max(surfaceDistance + hitDistance, 1e-6);
}

// A traced ray's parallax from its candidate reservoir's images (reflections.candidate.sample:
// xyz the hit point x2; .origin: xyz x1, w the kind), seen from its own x1 by a camera at
// `camera`; negative where the pixel traced no ray.
float candidateParallax(vec3 camera, vec4 sampleW, vec4 originKind) {
  uint kind = reservoirKind(originKind.w);
  if (kind == RESTIR_GI_KIND_NONE) return -1.0;
  if (kind == RESTIR_GI_KIND_SKY) return 1.0;
  return rayParallax(distance(originKind.xyz, camera), distance(sampleW.xyz, originKind.xyz));
}

#endif
