// Specular shading in the hybrid frame (docs/reflections.md): the push constants of `composite`
// and of the reflection passes, and the reflection passes' image bindings (set 1).
//
// Images:
//   reflections.traced  RGBA16F  at 1/ReflectionSettings::divisor: the reflection signal of one
//                                ray per pixel (rgb, see below), hit distance in w
//                                (REFLECTION_NO_SAMPLE: no ray, the pixel is sky or too rough
//                                to trace; REFLECTION_MISS_DISTANCE: the ray left the scene)
//   reflections         RGBA16F  the same signal at render resolution (reflections-upsample;
//                                mirrors' own rays from reflections-trace-mirrors), w = 1
//                                where set
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

// Push constants of reflections-trace, reflections-trace-mirrors and reflections-upsample
// (ReflectionSettings documents the thresholds; src/passes/reflections_trace.h).
struct ReflectionPassConstants {
  DeviceAddress frame;           // FrameConstants
  DeviceAddress specularAlbedo;  // the split-sum table
  DeviceAddress lights;          // LightTables (shared/lighting_io.h), without the sun
  DeviceAddress cache;           // the clipmap cache's constants; 0: no cache (--gi none)
  uvec2 tracedResolution;        // reflections.traced
  uint divisor;                  // render resolution / traced resolution
  float mirrorRoughness;         // below: the single mirror direction is traced
  float maxTracedRoughness;      // above: no ray (composite takes the diffuse light instead)
  uint materialTextureSide;      // textures at the hit read at mips at most this wide; 0 = full
  uint seed;                     // mixed into the random numbers (ReflectionSettings::seed)
  float hitRegularization;       // the hit's lobe for light samples >= this x the pixel's alpha
  // reflections-trace-mirrors: a mirror pixel traces its own ray unless the traced rays it is
  // upsampled from reflect within this angle's cosine of its own mirror direction
  float mirrorDirectionCosine;
  uint pad0;
};
BOUNCE_CHECK_SIZE(ReflectionPassConstants, 72);

BOUNCE_CONST float REFLECTION_NO_SAMPLE = -1.0f;     // reflections.traced w: no ray here
BOUNCE_CONST float REFLECTION_MISS_DISTANCE = 1e4f;  // reflections.traced w: the ray left
// A reprojection that moves a pixel by less than this many render pixels counts as a still view:
// the reflection passes' motion-only tests (ReflectionSettings and ReflectionDenoiseSettings::
// motionParallaxTolerance) leave it alone, so a static view's estimates are as without them.
BOUNCE_CONST float REFLECTION_STILL_PIXELS = 0.005f;

BOUNCE_CONST uint REFLECTIONS_TRACE_BINDING_NORMALS = 0u;
BOUNCE_CONST uint REFLECTIONS_TRACE_BINDING_DEPTH = 1u;
BOUNCE_CONST uint REFLECTIONS_TRACE_BINDING_EMISSIVE = 2u;
BOUNCE_CONST uint REFLECTIONS_TRACE_BINDING_FLAGS = 3u;
BOUNCE_CONST uint REFLECTIONS_TRACE_BINDING_TRACED = 4u;
// 5-8: reflections.candidate.{sample,radiance,origin,normals}, the traced sample as a reservoir
// of one candidate (shared/reflections_reuse_io.h), for the reuse passes
BOUNCE_CONST uint REFLECTIONS_TRACE_BINDING_CANDIDATE = 5u;
BOUNCE_CONST uint REFLECTIONS_TRACE_BINDING_COUNT = 9u;

BOUNCE_CONST uint REFLECTIONS_TRACE_MIRRORS_BINDING_NORMALS = 0u;
BOUNCE_CONST uint REFLECTIONS_TRACE_MIRRORS_BINDING_DEPTH = 1u;
BOUNCE_CONST uint REFLECTIONS_TRACE_MIRRORS_BINDING_EMISSIVE = 2u;
BOUNCE_CONST uint REFLECTIONS_TRACE_MIRRORS_BINDING_FLAGS = 3u;
BOUNCE_CONST uint REFLECTIONS_TRACE_MIRRORS_BINDING_REFLECTIONS = 4u;  // read-modify-write
BOUNCE_CONST uint REFLECTIONS_TRACE_MIRRORS_BINDING_TRACED = 5u;       // what the upsample read
BOUNCE_CONST uint REFLECTIONS_TRACE_MIRRORS_BINDING_COUNT = 6u;

BOUNCE_CONST uint REFLECTIONS_UPSAMPLE_BINDING_TRACED = 0u;
BOUNCE_CONST uint REFLECTIONS_UPSAMPLE_BINDING_NORMALS = 1u;
BOUNCE_CONST uint REFLECTIONS_UPSAMPLE_BINDING_DEPTH = 2u;
BOUNCE_CONST uint REFLECTIONS_UPSAMPLE_BINDING_FLAGS = 3u;
BOUNCE_CONST uint REFLECTIONS_UPSAMPLE_BINDING_OUTPUT = 4u;
BOUNCE_CONST uint REFLECTIONS_UPSAMPLE_BINDING_COUNT = 5u;

BOUNCE_END_SHARED
#endif
