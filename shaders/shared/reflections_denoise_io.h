// reflections-denoise-temporal and reflections-denoise-spatial (docs/reflections.md): the push
// constants and image bindings (set 1) of the reflection denoiser. Both passes run at the traced
// resolution (render resolution / ReflectionSettings::divisor) and keep the format of
// reflections.traced (shared/specular_io.h): a demodulated signal in rgb, hit distance in w.
//
// Images, at the traced resolution:
//   reflections.temporal          RGBA16F  (history) the signal's running mean in rgb, the running
//                                          mean of hit distance in w; REFLECTION_NO_SAMPLE in w
//                                          where the pixel holds nothing
//   reflections.temporal-moments  RGBA32F  (history) x: running mean of the signal's squared
//                                          luminance (its per-sample variance is x - mean^2),
//                                          y: history length in frames (0: none), z: running
//                                          mean of the parallax hit / (surface distance + hit)
//                                          (a miss: 1), what the spatial footprint needs
//   reflections.temporal-surface  RGBA32F  (history) the surface the history belongs to: xy the
//                                          octahedral shading normal, z perceptual roughness
//                                          (negative: no surface), w plane offset dot(n, x) in
//                                          world units (32-bit: it grows with the distance from
//                                          the world's origin)
//   reflections.temporal-fast     RGBA16F  (history) the fast history: the signal's running mean
//                                          over at most fastHistoryFrames frames in rgb
//   reflections.denoised          RGBA16F  the spatial filter's output: what reflections-upsample
//                                          reads
#ifndef BOUNCE_SHARED_REFLECTIONS_DENOISE_IO_H
#define BOUNCE_SHARED_REFLECTIONS_DENOISE_IO_H
#include "shared/compat.h"

BOUNCE_BEGIN_SHARED

// Push constants of both passes; ReflectionDenoiseSettings (src/passes/reflections_denoise.h)
// documents each knob.
struct ReflectionDenoiseConstants {
  DeviceAddress frame;       // FrameConstants
  uvec2 tracedResolution;    // reflections.traced
  uint divisor;              // render resolution / traced resolution
  uint historyValid;         // 0: the first frame, after a reset or a lighting cut
  float maxTracedRoughness;  // above: no sample is ever traced (ReflectionSettings)
  float mirrorHistoryFrames;
  float glossyHistoryFrames;
  float glossyHistoryRoughness;
  float virtualRoughnessLimit;
  float planeTolerance;
  float normalTolerance;        // radians, for the widest lobes
  float mirrorNormalTolerance;  // radians, for a mirror
  float roughnessTolerance;
  float ghostSigma;
  float responsiveFrames;
  float spatialMaxRadius;  // traced pixels
  float spatialFootprintScale;
  uint flags;  // REFLECTION_DENOISE_FLAG_*
  float fastHistoryFrames;
  float lagSigma;
  float motionParallaxTolerance;  // 0: no test
  uint padding;
};
BOUNCE_CHECK_SIZE(ReflectionDenoiseConstants, 96);

// Tests only: the temporal pass replaces every REFLECTION_DENOISE_POISON_PERIOD-th traced sample
// by NaN or Inf before it sanitizes its input (ReflectionDenoiseSettings::poisonInput).
BOUNCE_CONST uint REFLECTION_DENOISE_FLAG_POISON_INPUT = 1u;
BOUNCE_CONST uint REFLECTION_DENOISE_POISON_PERIOD = 5u;

BOUNCE_CONST uint REFLECTIONS_DENOISE_TEMPORAL_BINDING_TRACED = 0u;
BOUNCE_CONST uint REFLECTIONS_DENOISE_TEMPORAL_BINDING_NORMALS = 1u;
BOUNCE_CONST uint REFLECTIONS_DENOISE_TEMPORAL_BINDING_DEPTH = 2u;
BOUNCE_CONST uint REFLECTIONS_DENOISE_TEMPORAL_BINDING_EMISSIVE = 3u;
BOUNCE_CONST uint REFLECTIONS_DENOISE_TEMPORAL_BINDING_FLAGS = 4u;
BOUNCE_CONST uint REFLECTIONS_DENOISE_TEMPORAL_BINDING_VELOCITY = 5u;
BOUNCE_CONST uint REFLECTIONS_DENOISE_TEMPORAL_BINDING_PREVIOUS = 6u;
BOUNCE_CONST uint REFLECTIONS_DENOISE_TEMPORAL_BINDING_PREVIOUS_MOMENTS = 7u;
BOUNCE_CONST uint REFLECTIONS_DENOISE_TEMPORAL_BINDING_PREVIOUS_SURFACE = 8u;
BOUNCE_CONST uint REFLECTIONS_DENOISE_TEMPORAL_BINDING_CURRENT = 9u;
BOUNCE_CONST uint REFLECTIONS_DENOISE_TEMPORAL_BINDING_CURRENT_MOMENTS = 10u;
BOUNCE_CONST uint REFLECTIONS_DENOISE_TEMPORAL_BINDING_CURRENT_SURFACE = 11u;
BOUNCE_CONST uint REFLECTIONS_DENOISE_TEMPORAL_BINDING_PREVIOUS_FAST = 12u;
BOUNCE_CONST uint REFLECTIONS_DENOISE_TEMPORAL_BINDING_CURRENT_FAST = 13u;
// reflections.candidate.sample and .origin: the traced rays before any reuse (their hit points and
// x1, shared/restir_gi_io.h's reservoir layout), whose depths the motion parallax test reads.
BOUNCE_CONST uint REFLECTIONS_DENOISE_TEMPORAL_BINDING_CANDIDATE_SAMPLE = 14u;
BOUNCE_CONST uint REFLECTIONS_DENOISE_TEMPORAL_BINDING_CANDIDATE_ORIGIN = 15u;
BOUNCE_CONST uint REFLECTIONS_DENOISE_TEMPORAL_BINDING_COUNT = 16u;

BOUNCE_CONST uint REFLECTIONS_DENOISE_SPATIAL_BINDING_TEMPORAL = 0u;
BOUNCE_CONST uint REFLECTIONS_DENOISE_SPATIAL_BINDING_MOMENTS = 1u;
BOUNCE_CONST uint REFLECTIONS_DENOISE_SPATIAL_BINDING_SURFACE = 2u;
BOUNCE_CONST uint REFLECTIONS_DENOISE_SPATIAL_BINDING_DEPTH = 3u;
BOUNCE_CONST uint REFLECTIONS_DENOISE_SPATIAL_BINDING_OUTPUT = 4u;
BOUNCE_CONST uint REFLECTIONS_DENOISE_SPATIAL_BINDING_COUNT = 5u;

BOUNCE_END_SHARED
#endif
