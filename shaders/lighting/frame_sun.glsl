// The hybrid frame's sun as a light sample (the real-time passes take the sun from the frame
// constants, because it moves; the light tables leave it out): a direction uniformly in its
// cone, weighted like the reference's distant lights (shared/lighting_io.h: E 2 / (1 + cos
// half-angle)). Shared by ReSTIR GI's 2nd vertex and reflections-trace's hit.
#ifndef BOUNCE_LIGHTING_FRAME_SUN_GLSL
#define BOUNCE_LIGHTING_FRAME_SUN_GLSL
#include "lighting/lights.glsl"
#include "shared/hybrid_frame_io.h"

LightSample sampleFrameSun(FrameConstants f, vec2 u) {
  LightSample l = invalidLightSample();
  if (!any(greaterThan(f.sunIrradiance, vec3(0.0)))) return l;
  l.distant = true;
  l.direction = f.sunCosHalfAngle < 1.0 ? sampleCone(f.towardSun, f.sunCosHalfAngle, u) : f.towardSun;
  l.radianceOverPdf = f.sunIrradiance * (2.0 / (1.0 + f.sunCosHalfAngle));
  l.valid = true;
  return l;
}

#endif
