// Specular shading in the hybrid frame (docs/reflections.md): the push constants of `composite`
// and of the reflection passes, and the reflection passes' image bindings (set 1).
//
// Images:
//   reflections.traced  RGBA16F  at 1/ReflectionSettings::divisor: the reflection signal of one
//                                ray per pixel (rgb, see below), hit distance in w (0: no ray,
//                                the pixel is sky or too rough to trace; a miss: 1e4 m)
//   reflections         RGBA16F  the same signal at render resolution (reflections-upsample)
//
// The reflection signal is demodulated: the radiance L arriving along a direction l drawn from
// the GGX lobe's visible normals, times the sample's Fresnel-free weight G2(l, v) / G1(v)
// (common/brdf.glsl: ggxReflectionWeight), divided by that weight's mean over the lobe (the
// split-sum table's scale + bias). Its expectation is the lobe-weighted mean of incident
// radiance, a value on the scale of radiance that filters well; composite multiplies it by
// specularReflectance (lighting/specular_albedo.glsl) to get reflected radiance.
#ifndef BOUNCE_SHARED_SPECULAR_IO_H
#define BOUNCE_SHARED_SPECULAR_IO_H
#include "shared/compat.h"

BOUNCE_BEGIN_SHARED

// Push constants of `composite`.
struct CompositeConstants {
  DeviceAddress frame;           // FrameConstants
  DeviceAddress specularAlbedo;  // the split-sum table (shared/specular_albedo_io.h)
  // Pixels whose perceptual roughness is at most this read their specular light from the
  // `reflections` image; rougher ones, and every pixel when it is negative (no reflection pass),
  // take it from the diffuse GI's irradiance / pi, the cosine-weighted mean of incident light.
  float reflectionMaxRoughness;
  uint pad0;
};
BOUNCE_CHECK_SIZE(CompositeConstants, 24);

BOUNCE_END_SHARED
#endif
