// ReSTIR DI (Bitterli et al. 2020, "Spatiotemporal reservoir resampling for real-time ray tracing
// with dynamic direct lighting"; defaults after RTXDI, research/gi10_lux_denoisers.md §2.3(a)):
// the constants block, push constants, reservoir encoding and the bindings of the four passes
// (src/di/restir_di.cpp chains them on the frame graph). Every image is at render resolution.
//
// The lights are those of the scene's light tables (shared/lighting_io.h, the GI's NEE tables):
// local lights (emissive triangles and KHR point/spot lights, alias table) and the KHR
// directional lights; the sun is not among them (its own soft-shadow pass lights it), nor are
// the large emitters the tables leave to rays (src/lighting/gpu_light_tables.h).
//
// A sample is (light, u): `light` indexes the local lights (alias-table entry) or, with
// DI_LIGHT_DISTANT set, the distant lights; u in [0, 1)^2 is the light's own primary sample:
// the point uniformTriangleBarycentrics(u) on a triangle, the direction sampleCone(u) in a
// directional light's cone, unused for a point or spot light. Every light's measure is thus
// uniform over u, the same for every pixel, so reuse between pixels needs no Jacobian, and the
// integrand of a sample (DiLight.contribution, di_common.glsl) is f cos L G x |dy/du|.
// The target function is p_hat = luminance(contribution) without visibility (RTXDI's choice:
// visibility enters through the initial and final visibility rays).
//
// Reservoir (one RGBA32UI texel, 16 bytes): x light (DI_NO_LIGHT: none; the index in the low
// 24 bits, DI_LIGHT_DISTANT, and in bits 24-30 the frames since di-shade's final shadow ray
// found the sample visible from this pixel, DI_VISIBILITY_UNKNOWN where it never did), y u as
// two unorm16, z W (float bits; the unbiased contribution weight, 1/pdf in u-space x
// selection), w M (float bits; the confidence, candidates' reservoirs have M = 1).
#ifndef BOUNCE_SHARED_RESTIR_DI_IO_H
#define BOUNCE_SHARED_RESTIR_DI_IO_H
#include "shared/compat.h"

BOUNCE_BEGIN_SHARED

BOUNCE_CONST uint DI_NO_LIGHT = 0xFFFFFFFFu;
BOUNCE_CONST uint DI_LIGHT_DISTANT = 0x80000000u;  // bit of a distant light's index
BOUNCE_CONST uint DI_MAX_LIGHTS = 0x01000000u;     // local and distant lights each below this
BOUNCE_CONST uint DI_VISIBLE_AGE_SHIFT = 24u;      // the reservoir's visibility age, 7 bits
BOUNCE_CONST uint DI_VISIBLE_AGE_MASK = 0x7F000000u;
BOUNCE_CONST uint DI_VISIBILITY_UNKNOWN = 127u;

BOUNCE_CONST uint DI_FLAG_TEMPORAL = 1u;  // di-temporal merges the reprojected history
BOUNCE_CONST uint DI_FLAG_SPATIAL = 2u;   // di-spatial merges neighbours
BOUNCE_CONST uint DI_FLAG_UNBIASED = 4u;  // di-spatial traces the neighbours' visibility (1/Z)
BOUNCE_CONST uint DI_FLAG_CANDIDATE_VISIBILITY = 8u;  // the chosen candidate's shadow ray

// Constants of the whole chain, uploaded once (RestirDi's constructor; DiSettings documents
// each field's unit and trade-off).
struct DiConstants {
  DeviceAddress lights;         // LightTables (shared/lighting_io.h): the GI's tables, sun left out
  DeviceAddress hitMap;         // uint[]: emissive hit -> light index (light_table.h)
  uint flags;                   // DI_FLAG_*
  uint lightCandidates;         // light candidates per pixel per frame
  uint brdfCandidates;          // BRDF-sampled candidates per pixel per frame (0 or 1)
  float brdfCandidateMaxAlpha;  // ... only where the GGX alpha is at most this
  float temporalMaxM;           // M cap of the history reservoir
  float depthTolerance;         // reuse: |depth - depth'| / depth at most this
  float normalTolerance;        // reuse: n . n' at least this
  uint spatialSamples;          // di-spatial: neighbours per pixel
  uint disocclusionSamples;     // ... where the temporal reservoir's M is below disocclusionM
  float disocclusionM;
  float spatialRadius;      // pixels
  uint seed;                // mixed into every random number of the chain
  DeviceAddress lightGrid;  // DiLightGrid (shared/di_light_grid_io.h); 0: no grid
  // di-shade takes a sample's visibility as its final shadow ray found it (visible) up to this
  // many frames ago instead of tracing again; 0: always traces
  uint finalVisibilityMaxAge;
  uint pad0;
};
BOUNCE_CHECK_SIZE(DiConstants, 80);

// Push constants of every DI pass.
struct DiPassConstants {
  DeviceAddress frame;  // FrameConstants
  DeviceAddress di;     // DiConstants
  uint historyValid;    // di-temporal: 0 in the first frame, after a reset or a lighting cut
  uint pad0;
};
BOUNCE_CHECK_SIZE(DiPassConstants, 24);

BOUNCE_CONST uint DI_GROUP_SIZE = 8u;

// Set 1 bindings (storage images), per pass. The GBuffer inputs come first in each.
BOUNCE_CONST uint DI_BINDING_BASE_COLOR = 0u;
BOUNCE_CONST uint DI_BINDING_NORMALS = 1u;
BOUNCE_CONST uint DI_BINDING_DEPTH = 2u;
BOUNCE_CONST uint DI_BINDING_EMISSIVE = 3u;  // roughness in w
BOUNCE_CONST uint DI_BINDING_FLAGS = 4u;
BOUNCE_CONST uint DI_GBUFFER_BINDING_COUNT = 5u;

// di-generate-candidates, and di-trace-candidate-visibility after it (which reads and writes
// the same reservoirs)
BOUNCE_CONST uint DI_CANDIDATES_BINDING_RESERVOIR = 5u;  // out: di.candidate
BOUNCE_CONST uint DI_CANDIDATES_BINDING_COUNT = 6u;
// Specialization constant of di-generate-candidates (PASS_SPEC_FIRST, shared/scene_layout.h):
// 0 when no pixel takes a BRDF candidate (DiConstants::brdfCandidates 0), so that the driver
// drops that candidate's traversal and the pass runs with fewer registers; 1 when some may;
// DI_SPEC_ANY (a pipeline created without it) reads DiConstants.
BOUNCE_CONST uint DI_SPEC_BRDF_CANDIDATE = 1u;
BOUNCE_CONST uint DI_SPEC_ANY = 2u;
// Specialization constant of di-spatial (PASS_SPEC_FIRST): 1 with the ray-traced bias
// correction (DI_FLAG_UNBIASED), 0 without, so that the driver drops its traversal (whose stack
// spilled to local memory with the neighbours' arrays); DI_SPEC_ANY reads DiConstants.
BOUNCE_CONST uint DI_SPEC_SPATIAL_TRACED_CORRECTION = 1u;
// di-trace-candidate-visibility's groups: tiles of this many pixels squared, whose rays it bins
// by direction (rt/ray_bins.glsl)
BOUNCE_CONST uint DI_VISIBILITY_GROUP_SIDE = 16u;

// di-temporal, and di-candidates-temporal (the candidates drawn in the same pass: every binding
// but the candidate's, which comes last so that the fused pass's bindings stay contiguous)
BOUNCE_CONST uint DI_TEMPORAL_BINDING_VELOCITY = 5u;          // gbuffer.velocity
BOUNCE_CONST uint DI_TEMPORAL_BINDING_PREVIOUS = 6u;          // di.reservoir-final (previous)
BOUNCE_CONST uint DI_TEMPORAL_BINDING_PREVIOUS_SURFACE = 7u;  // di.reservoir-surface (previous)
BOUNCE_CONST uint DI_TEMPORAL_BINDING_CURRENT = 8u;           // out: di.reservoir
BOUNCE_CONST uint DI_TEMPORAL_BINDING_CURRENT_SURFACE = 9u;   // di.reservoir-surface (current)
BOUNCE_CONST uint DI_CANDIDATES_TEMPORAL_BINDING_COUNT = 10u;
BOUNCE_CONST uint DI_TEMPORAL_BINDING_CANDIDATE = 10u;  // di.candidate (di-temporal only)
BOUNCE_CONST uint DI_TEMPORAL_BINDING_COUNT = 11u;

// di-light-grid-view (the debug view di.grid-cells, only when requested)
BOUNCE_CONST uint DI_GRID_VIEW_BINDING_OUTPUT = 5u;  // out: di.grid-cells
BOUNCE_CONST uint DI_GRID_VIEW_BINDING_COUNT = 6u;

// di-spatial
BOUNCE_CONST uint DI_SPATIAL_BINDING_INPUT = 5u;   // di.reservoir
BOUNCE_CONST uint DI_SPATIAL_BINDING_OUTPUT = 6u;  // di.spatial
BOUNCE_CONST uint DI_SPATIAL_BINDING_COUNT = 7u;

// di-shade
BOUNCE_CONST uint DI_SHADE_BINDING_RESERVOIR = 5u;  // the chain's last reservoir
BOUNCE_CONST uint DI_SHADE_BINDING_RADIANCE = 6u;   // out: di.radiance
BOUNCE_CONST uint DI_SHADE_BINDING_INFO = 7u;       // out: di.reservoir-info
// out: di.reflectance, the split-sum directional albedo (diffuse + specular lobes) that the DI
// denoiser demodulates by (di/di_denoise.h)
BOUNCE_CONST uint DI_SHADE_BINDING_REFLECTANCE = 8u;
// out: di.reservoir-final, di-temporal's history next frame: di-temporal's reservoir, with W = 0
// where its sample is the one shaded and the final shadow ray was blocked
BOUNCE_CONST uint DI_SHADE_BINDING_FINAL_RESERVOIR = 9u;
BOUNCE_CONST uint DI_SHADE_BINDING_TEMPORAL_RESERVOIR = 10u;  // di.reservoir (di-temporal's)
BOUNCE_CONST uint DI_SHADE_BINDING_COUNT = 11u;

BOUNCE_END_SHARED
#endif
