// ReSTIR-style reuse of the glossy reflection samples (docs/reflections.md, "Reuse"): the push
// constants and image bindings of reflections-temporal, reflections-spatial and
// reflections-resolve (src/passes/reflections_{temporal,spatial,resolve}.{h,cpp}).
//
// A reflection reservoir uses ReSTIR GI's encoding (shared/restir_gi_io.h, four images at the
// traced resolution) with one sample: the reflection ray's hit x2 seen from the primary vertex
// x1 (RESTIR_GI_KIND_SURFACE), or the sky (RESTIR_GI_KIND_SKY, a direction stored as a point
// RESTIR_GI_SKY_DISTANCE away), the radiance arriving at x1 from it (not demodulated), W (its
// unbiased contribution weight, 1/sr at x1; a fresh sample's is 1 / its visible-normal GGX pdf)
// and M:
//   reflections.candidate.*  written by reflections-trace (M = 1; M = 0 where nothing is traced)
//   reflections.reservoir.*  reflections-temporal's output, history (fed back next frame)
//   reflections.spatial.*    reflections-spatial's output (not fed back: no visibility test)
// plus reflections.reservoir.lobe (RG32F history): x the perceptual roughness at x1, for the
// temporal roughness test (negative: no reservoir), y the chosen sample's target p_hat at x1
// (reflections-temporal's confidence under motion).
//
// Target function at a receiving pixel (x1, shading normal n, view v, GGX alpha):
//   p_hat(l) = luminance(L) D(h) Vis(l, v) (n.l)     (the Fresnel-free GGX BRDF x cos x L)
// zero below x1's geometric or shading surface. reflections-resolve writes
//   L D Vis (n.l) W / (scale + bias)
// in reflections.traced's format (shared/specular_io.h): for a fresh sample W = 1 / pdf and this
// is exactly reflections-trace's L G2/G1(v) / (scale + bias).
#ifndef BOUNCE_SHARED_REFLECTIONS_REUSE_IO_H
#define BOUNCE_SHARED_REFLECTIONS_REUSE_IO_H
#include "shared/compat.h"

BOUNCE_BEGIN_SHARED

// Push constants of the three reuse passes (ReflectionSettings documents the knobs).
struct ReflectionReuseConstants {
  DeviceAddress frame;            // FrameConstants
  DeviceAddress specularAlbedo;   // the split-sum table
  uvec2 tracedResolution;         // reflections.traced
  uint divisor;                   // render resolution / traced resolution
  uint historyValid;              // 0: the first frame, after a reset, a resize or a lighting cut
  float reuseMinRoughness;        // below: no reuse, the traced signal passes unchanged
  float maxTracedRoughness;       // above: nothing traced
  float temporalMaxM;             // M cap of the history reservoir (0: no temporal reuse)
  float spatialRadius;            // traced pixels at roughness 1; scaled by the roughness
  uint spatialSamples;            // neighbours per pixel (0: no spatial reuse)
  uint seed;                      // ReflectionSettings::seed
  float motionParallaxTolerance;  // ReflectionSettings::motionParallaxTolerance (0: no test)
  uint padding;
};
BOUNCE_CHECK_SIZE(ReflectionReuseConstants, 64);

// Reuse tests between primary vertices (the same meaning as ReSTIR GI's, RestirGiSettings):
// x1' counts as x1's surface within this distance from x1's tangent plane per unit view depth,
BOUNCE_CONST float REFLECTION_REUSE_PLANE_TOLERANCE = 0.02f;
// with shading normals whose cosine is at least this (ReSTIR GI's 0.9: the test keeps reuse on
// one surface; a neighbour's turned lobe needs no tighter test, since the target is evaluated
// with this pixel's own normal and view and the 1/Z normalisation counts only neighbours whose
// lobe could have produced the sample),
BOUNCE_CONST float REFLECTION_REUSE_NORMAL_TOLERANCE = 0.9f;
// and perceptual roughnesses within this much of each other (a lobe of another width is another
// target; texture-varying roughness).
BOUNCE_CONST float REFLECTION_REUSE_ROUGHNESS_TOLERANCE = 0.1f;
// Reconnection shifts with a larger Jacobian are rejected, as in ReSTIR GI (grazing and
// near-contact geometry: fireflies).
BOUNCE_CONST float REFLECTION_REUSE_MAX_JACOBIAN = 10.0f;
// reflections-temporal's check that a history sample is still there: a ray towards it must hit
// within this fraction of its distance (a moving object's sample fails, a static one passes).
BOUNCE_CONST float REFLECTION_REUSE_VALIDATION_TOLERANCE = 0.02f;
// The smallest spatial radius, traced pixels: the spiral's first ring reaches the 8 neighbours.
BOUNCE_CONST float REFLECTION_REUSE_MIN_RADIUS = 1.5f;
// Most neighbours reflections-spatial merges (it keeps them for the 1/Z normalisation).
BOUNCE_CONST uint REFLECTION_REUSE_MAX_SPATIAL_SAMPLES = 8u;

// Offsets within a reservoir's four images: GI_RESERVOIR_SAMPLE .. GI_RESERVOIR_NORMALS
// (shared/restir_gi_io.h).

// reflections-temporal: candidate (0-3), previous reservoir (4-7), current reservoir (8-11)
BOUNCE_CONST uint REFLECTIONS_TEMPORAL_BINDING_CANDIDATE = 0u;
BOUNCE_CONST uint REFLECTIONS_TEMPORAL_BINDING_PREVIOUS = 4u;
BOUNCE_CONST uint REFLECTIONS_TEMPORAL_BINDING_CURRENT = 8u;
BOUNCE_CONST uint REFLECTIONS_TEMPORAL_BINDING_NORMALS = 12u;
BOUNCE_CONST uint REFLECTIONS_TEMPORAL_BINDING_DEPTH = 13u;
BOUNCE_CONST uint REFLECTIONS_TEMPORAL_BINDING_EMISSIVE = 14u;
BOUNCE_CONST uint REFLECTIONS_TEMPORAL_BINDING_VELOCITY = 15u;
BOUNCE_CONST uint REFLECTIONS_TEMPORAL_BINDING_PREVIOUS_LOBE = 16u;
BOUNCE_CONST uint REFLECTIONS_TEMPORAL_BINDING_CURRENT_LOBE = 17u;
BOUNCE_CONST uint REFLECTIONS_TEMPORAL_BINDING_COUNT = 18u;

// reflections-spatial: reservoir in (0-3), reservoir out (4-7)
BOUNCE_CONST uint REFLECTIONS_SPATIAL_BINDING_INPUT = 0u;
BOUNCE_CONST uint REFLECTIONS_SPATIAL_BINDING_OUTPUT = 4u;
BOUNCE_CONST uint REFLECTIONS_SPATIAL_BINDING_NORMALS = 8u;
BOUNCE_CONST uint REFLECTIONS_SPATIAL_BINDING_DEPTH = 9u;
BOUNCE_CONST uint REFLECTIONS_SPATIAL_BINDING_EMISSIVE = 10u;
BOUNCE_CONST uint REFLECTIONS_SPATIAL_BINDING_COUNT = 11u;

// reflections-resolve: reservoir (0-3), the trace's signal, the resolved signal
BOUNCE_CONST uint REFLECTIONS_RESOLVE_BINDING_RESERVOIR = 0u;
BOUNCE_CONST uint REFLECTIONS_RESOLVE_BINDING_NORMALS = 4u;
BOUNCE_CONST uint REFLECTIONS_RESOLVE_BINDING_DEPTH = 5u;
BOUNCE_CONST uint REFLECTIONS_RESOLVE_BINDING_EMISSIVE = 6u;
BOUNCE_CONST uint REFLECTIONS_RESOLVE_BINDING_TRACED = 7u;    // reflections.traced
BOUNCE_CONST uint REFLECTIONS_RESOLVE_BINDING_RESOLVED = 8u;  // reflections.resolved, same format
BOUNCE_CONST uint REFLECTIONS_RESOLVE_BINDING_COUNT = 9u;

BOUNCE_END_SHARED
#endif
