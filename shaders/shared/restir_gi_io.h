// ReSTIR GI (seed 000's diffuse GI chain; Ouyang et al. 2021, "ReSTIR GI: Path Resampling for
// Real-Time Path Tracing"): the constants block, push constants, reservoir encoding and the
// bindings of each pass (src/gi/evolve/restir/restir_gi.cpp declares them on the frame graph).
//
// GI resolution = render resolution / divisor (1 full, 2 half on desktop, 4 quarter on mobile).
// GI pixel g traces from the full-res pixel g * divisor + divisor / 2 (clamped), the
// "representative" pixel, whose GBuffer gives the primary vertex x1.
//
// A reservoir holds one sample, the path's 2nd vertex x2 seen from x1, in four images:
//   *.sample    RGBA32F  x2 (xyz; for a sky sample x1 + direction * RESTIR_GI_SKY_DISTANCE),
//                        W, the unbiased contribution weight (solid angle at x1, 1/sr)
//   *.radiance  RGBA32F  outgoing radiance at x2 towards x1 (rgb), M (confidence, samples seen)
//   *.origin    RGBA32F  x1, the primary vertex the sample belongs to (xyz), RESTIR_GI_KIND_* | age
//   << 2
//   *.normals   RGBA16F  octahedral shading normal at x1 (xy), geometric normal at x2 (zw)
// The target function is p_hat(x2) = luminance(radiance) * max(0, cos(n1, x2 - x1)), zero
// where x2 lies below x1's geometric surface; the estimate of gi.diffuse (irradiance / pi per
// unit albedo) is radiance * cos / pi * W.
#ifndef BOUNCE_SHARED_RESTIR_GI_IO_H
#define BOUNCE_SHARED_RESTIR_GI_IO_H
#include "shared/compat.h"

BOUNCE_BEGIN_SHARED

BOUNCE_CONST uint RESTIR_GI_KIND_NONE = 0u;     // no sample (sky pixel, invalid ray)
BOUNCE_CONST uint RESTIR_GI_KIND_SURFACE = 1u;  // x2 is a surface point
BOUNCE_CONST uint RESTIR_GI_KIND_SKY = 2u;      // the ray escaped: x2 is a direction

// Sky samples are stored as a point this far along their direction (scene units): far enough
// that moving x1 within the scene changes the direction negligibly, near enough for float.
BOUNCE_CONST float RESTIR_GI_SKY_DISTANCE = 1.0e5f;

// What the radiance at x2 includes besides its emission (RestirGiSettings::secondVertex).
BOUNCE_CONST uint RESTIR_GI_SECOND_VERTEX_NEE = 0u;    // + one NEE sample: one bounce only
BOUNCE_CONST uint RESTIR_GI_SECOND_VERTEX_PATH = 1u;   // + NEE + a path traced on from x2
BOUNCE_CONST uint RESTIR_GI_SECOND_VERTEX_CACHE = 2u;  // + NEE + the clipmap cache
// Specialization constant of gi-shade-diffuse-hits (PASS_SPEC_FIRST): the chain's second vertex,
// so that the driver drops the continued path's code (its own traversal) where it never runs;
// RESTIR_GI_SECOND_VERTEX_ANY (a pipeline created without it) reads RestirGiConstants.
BOUNCE_CONST uint GI_SPEC_SECOND_VERTEX = 1u;
BOUNCE_CONST uint RESTIR_GI_SECOND_VERTEX_ANY = 3u;

BOUNCE_CONST uint RESTIR_GI_FLAG_TEMPORAL = 1u;             // gi-restir-temporal merges history
BOUNCE_CONST uint RESTIR_GI_FLAG_DENOISE = 2u;              // gi-temporal-denoise runs
BOUNCE_CONST uint RESTIR_GI_FLAG_RESOLVE_REUSE = 4u;        // resolve averages neighbour reservoirs
BOUNCE_CONST uint RESTIR_GI_FLAG_SPATIAL = 8u;              // gi-restir-spatial-0/1 run
BOUNCE_CONST uint RESTIR_GI_FLAG_SPATIAL_VALIDATION = 16u;  // gi-trace-spatial-validation-rays
BOUNCE_CONST uint RESTIR_GI_FLAG_PATCH = 32u;               // gi-restir-patch-reservoir
BOUNCE_CONST uint RESTIR_GI_FLAG_VALIDATION = 64u;  // validation traces every validationPeriod
BOUNCE_CONST uint RESTIR_GI_FLAG_SPATIAL_DENOISE = 128u;         // gi-spatial-denoise
BOUNCE_CONST uint RESTIR_GI_FLAG_OCCLUDER_VISIBILITY = 256u;     // gi-trace-resolve-visibility
BOUNCE_CONST uint RESTIR_GI_FLAG_PRODUCER_NORMALISATION = 512u;  // 1/Z in spatial reuse
BOUNCE_CONST uint RESTIR_GI_FLAG_TEMPORAL_PRODUCERS = 2048u;     // 1/Z in temporal reuse
BOUNCE_CONST uint RESTIR_GI_FLAG_CANONICAL_RESOLVE = 1024u;      // resolve: home as canonical

// Constants of the whole chain, uploaded once (RestirGi's constructor).
struct RestirGiConstants {
  // A LightTables block (shared/lighting_io.h, src/lighting/gpu_light_tables.h) with the
  // scene's light tables for NEE from x2; its distant lights exclude the sun, which comes from
  // the frame constants (it moves).
  DeviceAddress lights;
  uvec2 giResolution;
  uint divisor;
  uint secondVertex;         // RESTIR_GI_SECOND_VERTEX_*
  uint flags;                // RESTIR_GI_FLAG_*
  uint maxPathBounces;       // PATH: scattering events after x2 (Russian roulette from the 3rd)
  float temporalMaxM;        // M cap of the history reservoir
  float planeTolerance;      // reprojection: |n1 . (x1' - x1)| / view depth
  float normalTolerance;     // reprojection: minimum n1 . n1'
  float maxJacobian;         // reconnection shifts with a larger Jacobian are rejected
  float denoiseMaxHistory;   // frames the temporal denoiser averages at most
  float denoiseClipSigma;    // colour clipping box: mean +- sigma * standard deviation
  float resolveRadius;       // resolve: neighbour reservoirs within this many GI pixels
  uint resolveSamples;       // resolve: reservoirs averaged per pixel (own one included)
  DeviceAddress cache;       // ClipmapCacheConstants (CACHE second vertex), else 0
  uint spatialSamples[2];    // gi-restir-spatial-0 / -1: neighbours per pixel
  float spatialRadius[2];    // their largest radius, GI pixels
  float spatialMinRadius;    // their smallest radius (the spiral's first sample), GI pixels
  float validityBlend;       // spatial occlusion validity: weight of this frame in the running mean
  uint validationPeriod;     // gi-prepare-diffuse-rays re-traces history every N frames (0 = never)
  float validationDistance;  // validation: hit moved by more than this x ray length -> M cut
  float validationRadiance;  // validation: relative radiance change of a neighbourhood -> M cut
  uint temporalHistorySamples;  // history reservoirs gi-restir-temporal may merge (1 to 5)
  uint spatialDenoiseRadius;    // gi-spatial-denoise: half-width of the blur, pixels
  float historyBrightening;  // temporal: neighbourhood candidates / their running mean above this
                             // (2 frames) -> M cut (0 = off)
  float fireflyRatio;  // temporal denoise: input clamped to this x its ring's brightest (0 = off)
  uint materialTextureSide;  // x2's textures are read at mips at most this wide (0 = full)
  // RESTIR_GI_BLUE_NOISE_SIDE^2 uints, row-major: two blue-noise rank maps (src/core/blue_noise.h)
  // packed as rankA | rankB << 16, for gi-prepare-diffuse-rays' ray directions
  DeviceAddress blueNoise;
  uint maxSampleAge;  // temporal: history samples older than this many frames are dropped (0 = off)
  float spatialWideMaxM;     // gi-restir-spatial-0 skips reservoirs with at least this M (0 = none)
  float movingTemporalMaxM;  // M cap of the history where the pixel moves movingPixels or more
  float movingPixels;        // render pixels per frame
};
BOUNCE_CHECK_SIZE(RestirGiConstants, 152);

// Side of the tiled blue-noise map (64: 4,096 distinct values per channel, 16 KiB).
BOUNCE_CONST uint RESTIR_GI_BLUE_NOISE_SIDE = 64u;
// Most neighbours one spatial pass merges (gi_restir_spatial.comp keeps them for 1/Z).
BOUNCE_CONST uint RESTIR_GI_MAX_SPATIAL_SAMPLES = 8u;

// Push constants of every ReSTIR GI pass.
struct RestirGiPassConstants {
  DeviceAddress frame;  // FrameConstants (shared/hybrid_frame_io.h)
  DeviceAddress gi;     // RestirGiConstants
  uint historyValid;    // 0 in the first frame and after a reset
  uint variant;         // which of a shared shader's passes (gi-restir-spatial-0 / -1)
  // Scales temporalMaxM: settleHistoryScale while the light settles after a reset or a
  // lighting cut (RestirGiSettings::settleFrames), else 1 (gi-temporal-denoise: < 1 = settling).
  float historyScale;
  uint pad0;
  // gi.ray-lists (GiRayListHeader x 2, then the entries): read by the passes that append to or
  // walk a ray list (below), 0 for the others.
  DeviceAddress rayLists;
};
BOUNCE_CHECK_SIZE(RestirGiPassConstants, 40);

// ---- Ray lists --------------------------------------------------------------------------------
// Two passes trace rays at few, scattered pixels: gi-trace-diffuse-nee-rays (the 2nd vertices
// with a light sample; by night on `city` 1 GI pixel in 20) and gi-trace-resolve-visibility
// (the pixels beside an occluder, 1 in 70). One thread per pixel left most lanes of a subgroup
// idle while one traversed (0.16-0.25 Grays/s against 1-4 for the dense ray passes, H100,
// docs/benchmarks.md), so the pass before each appends its pixels to a list and the tracing
// pass runs one thread per entry through vkCmdDispatchIndirect. gi.ray-lists holds both lists:
// two headers, then GI_RAY_LIST_NEE's entries (one per GI pixel at most), then
// GI_RAY_LIST_RESOLVE's (one per render pixel at most). An entry is a pixel, x | y << 16.
struct GiRayListHeader {
  uint count;
  uint groupsX;  // the tracing pass's vkCmdDispatchIndirect arguments
  uint groupsY;
  uint groupsZ;
};
BOUNCE_CHECK_SIZE(GiRayListHeader, 16);
BOUNCE_CONST uint GI_RAY_LIST_NEE = 0u;
BOUNCE_CONST uint GI_RAY_LIST_RESOLVE = 1u;
BOUNCE_CONST uint GI_RAY_LISTS_HEADER_BYTES = 32u;
// Threads per group of the passes that walk a list. With vkCmdDispatchIndirect's x at most
// GI_RAY_LIST_MAX_GROUPS (the smallest maxComputeWorkGroupCount Vulkan allows), a list of up
// to 128 x 65,535 = 8.4 M entries (a 3840x2160 frame has 8.3 M pixels) needs one thread each;
// longer lists are walked with a stride.
BOUNCE_CONST uint GI_RAY_LIST_GROUP_SIZE = 128u;
BOUNCE_CONST uint GI_RAY_LIST_MAX_GROUPS = 65535u;

BOUNCE_CONST uint RESTIR_GI_GROUP_SIZE = 8u;

// Set 1 bindings (storage images) per pass.
// gi-prepare-diffuse-rays
BOUNCE_CONST uint GI_PREPARE_BINDING_NORMALS = 0u;
BOUNCE_CONST uint GI_PREPARE_BINDING_DEPTH = 1u;
BOUNCE_CONST uint GI_PREPARE_BINDING_FLAGS = 2u;
// RGBA32F direction (xyz); w: 0 = no ray, 1 = a fresh candidate, >= 2: a validation ray that
// re-traces the history reservoir of GI pixel q = (w - 2) % width, (w - 2) / width
BOUNCE_CONST uint GI_PREPARE_BINDING_RAYS = 3u;
BOUNCE_CONST uint GI_PREPARE_BINDING_PREVIOUS_SAMPLE = 4u;   // gi.reservoir.sample (previous)
BOUNCE_CONST uint GI_PREPARE_BINDING_PREVIOUS_ORIGIN = 5u;   // gi.reservoir.origin (previous)
BOUNCE_CONST uint GI_PREPARE_BINDING_PREVIOUS_NORMALS = 6u;  // gi.reservoir.normals (previous)
BOUNCE_CONST uint GI_PREPARE_BINDING_VELOCITY = 7u;
BOUNCE_CONST uint GI_PREPARE_BINDING_COUNT = 8u;
BOUNCE_CONST float GI_RAY_FRESH = 1.0f;
BOUNCE_CONST float GI_RAY_VALIDATION = 2.0f;

// gi-trace-diffuse-rays: the closest hit of each GI pixel's ray, nothing more, so that the
// traversal runs with the registers it needs and no more (shading x2 in the same shader took
// 128 per thread: docs/benchmarks.md)
BOUNCE_CONST uint GI_TRACE_BINDING_NORMALS = 0u;
BOUNCE_CONST uint GI_TRACE_BINDING_DEPTH = 1u;
BOUNCE_CONST uint GI_TRACE_BINDING_RAYS = 2u;
// RGBA32UI instance (GI_HIT_NONE on a miss or without a ray), geometry, primitive, 0
BOUNCE_CONST uint GI_TRACE_BINDING_HIT_IDS = 3u;
BOUNCE_CONST uint GI_TRACE_BINDING_HIT_BARYCENTRICS = 4u;  // RG32F
BOUNCE_CONST uint GI_TRACE_BINDING_COUNT = 5u;
BOUNCE_CONST uint GI_HIT_NONE = 0xFFFFFFFFu;

// gi-shade-diffuse-hits: x2 at each hit (or the sky), its emission, the set-up of its NEE ray,
// the cache or a continued path
BOUNCE_CONST uint GI_SHADE_BINDING_NORMALS = 0u;
BOUNCE_CONST uint GI_SHADE_BINDING_DEPTH = 1u;
BOUNCE_CONST uint GI_SHADE_BINDING_RAYS = 2u;
BOUNCE_CONST uint GI_SHADE_BINDING_HIT_IDS = 3u;
BOUNCE_CONST uint GI_SHADE_BINDING_HIT_BARYCENTRICS = 4u;
BOUNCE_CONST uint GI_SHADE_BINDING_HIT = 5u;           // RGBA32F x2, RESTIR_GI_KIND_*
BOUNCE_CONST uint GI_SHADE_BINDING_HIT_NORMAL = 6u;    // RGBA16F oct geometric normal at x2
BOUNCE_CONST uint GI_SHADE_BINDING_HIT_RADIANCE = 7u;  // RGBA32F radiance at x2 without NEE
BOUNCE_CONST uint GI_SHADE_BINDING_NEE_RAY = 8u;       // RGBA32F direction (unnormalised), tMax
BOUNCE_CONST uint GI_SHADE_BINDING_NEE_RADIANCE = 9u;  // RGBA32F NEE radiance if unoccluded
// R16F the NEE visibility, 0 here (a GI pixel without a light sample stays at 0); the GI
// pixels with a light sample go to GI_RAY_LIST_NEE
BOUNCE_CONST uint GI_SHADE_BINDING_NEE_VISIBILITY = 10u;
BOUNCE_CONST uint GI_SHADE_BINDING_COUNT = 11u;

// gi-trace-diffuse-nee-rays: one thread per entry of GI_RAY_LIST_NEE
BOUNCE_CONST uint GI_NEE_BINDING_HIT = 0u;
BOUNCE_CONST uint GI_NEE_BINDING_HIT_NORMAL = 1u;
BOUNCE_CONST uint GI_NEE_BINDING_NEE_RAY = 2u;
BOUNCE_CONST uint GI_NEE_BINDING_VISIBILITY = 3u;  // R16F 1 = unoccluded
BOUNCE_CONST uint GI_NEE_BINDING_COUNT = 4u;

// gi-resolve-diffuse-rays (writes the candidate reservoirs)
BOUNCE_CONST uint GI_CANDIDATES_BINDING_NORMALS = 0u;
BOUNCE_CONST uint GI_CANDIDATES_BINDING_DEPTH = 1u;
BOUNCE_CONST uint GI_CANDIDATES_BINDING_RAYS = 2u;
BOUNCE_CONST uint GI_CANDIDATES_BINDING_HIT = 3u;
BOUNCE_CONST uint GI_CANDIDATES_BINDING_HIT_NORMAL = 4u;
BOUNCE_CONST uint GI_CANDIDATES_BINDING_HIT_RADIANCE = 5u;
BOUNCE_CONST uint GI_CANDIDATES_BINDING_NEE_RADIANCE = 6u;
BOUNCE_CONST uint GI_CANDIDATES_BINDING_VISIBILITY = 7u;
BOUNCE_CONST uint GI_CANDIDATES_BINDING_SAMPLE = 8u;
BOUNCE_CONST uint GI_CANDIDATES_BINDING_RADIANCE = 9u;
BOUNCE_CONST uint GI_CANDIDATES_BINDING_ORIGIN = 10u;
BOUNCE_CONST uint GI_CANDIDATES_BINDING_RESERVOIR_NORMALS = 11u;
BOUNCE_CONST uint GI_CANDIDATES_BINDING_ESTIMATE = 12u;  // RGBA16F the candidate's own estimate
BOUNCE_CONST uint GI_CANDIDATES_BINDING_PREVIOUS = 13u;  // 13-16 history reservoir (previous)
// RGBA16F *reservoir validity*: x in [0, 1], the geometric validity (1, or lower where a
// validation ray found the hit moved), y = 1 where the candidate is the validated history
// reservoir rather than a fresh sample (gi-restir-temporal then does not merge), z and w the
// luminance of the stored and of the re-traced radiance of a validated, unmoved sample (0
// elsewhere), which gi-restir-temporal and gi-temporal-denoise compare over a neighbourhood
// (restir_gi_common.glsl, radianceValidity)
BOUNCE_CONST uint GI_CANDIDATES_BINDING_VALIDITY = 17u;
BOUNCE_CONST uint GI_CANDIDATES_BINDING_COUNT = 18u;

// gi-restir-temporal: candidate (0-3), previous reservoir (4-7), current reservoir (8-11)
BOUNCE_CONST uint GI_TEMPORAL_BINDING_CANDIDATE = 0u;
BOUNCE_CONST uint GI_TEMPORAL_BINDING_PREVIOUS = 4u;
BOUNCE_CONST uint GI_TEMPORAL_BINDING_CURRENT = 8u;
BOUNCE_CONST uint GI_TEMPORAL_BINDING_NORMALS = 12u;
BOUNCE_CONST uint GI_TEMPORAL_BINDING_DEPTH = 13u;
BOUNCE_CONST uint GI_TEMPORAL_BINDING_VELOCITY = 14u;
BOUNCE_CONST uint GI_TEMPORAL_BINDING_ESTIMATE = 15u;  // RGBA16F the reservoir's own estimate
BOUNCE_CONST uint GI_TEMPORAL_BINDING_VALIDITY = 16u;  // gi.reservoir-validity
// last frame's spatial occlusion validity (R16F; read only with RESTIR_GI_FLAG_SPATIAL_VALIDATION)
BOUNCE_CONST uint GI_TEMPORAL_BINDING_OCCLUSION_VALIDITY = 17u;
// this frame's candidate estimates (gi.candidate-estimate) and the running mean of their
// neighbourhood sums (gi.candidate-mean, RG32F history: last frame's, this frame's; x the
// mean, y 1 where this frame's sum exceeded historyBrightening x the mean)
BOUNCE_CONST uint GI_TEMPORAL_BINDING_CANDIDATE_ESTIMATE = 18u;
BOUNCE_CONST uint GI_TEMPORAL_BINDING_PREVIOUS_CANDIDATE_MEAN = 19u;
BOUNCE_CONST uint GI_TEMPORAL_BINDING_CURRENT_CANDIDATE_MEAN = 20u;
BOUNCE_CONST uint GI_TEMPORAL_BINDING_COUNT = 21u;
// offsets within a reservoir's four images
BOUNCE_CONST uint GI_RESERVOIR_SAMPLE = 0u;
BOUNCE_CONST uint GI_RESERVOIR_RADIANCE = 1u;
BOUNCE_CONST uint GI_RESERVOIR_ORIGIN = 2u;
BOUNCE_CONST uint GI_RESERVOIR_NORMALS = 3u;

// gi-restir-resolve (GI resolution -> render resolution)
BOUNCE_CONST uint GI_RESOLVE_BINDING_RESERVOIR = 0u;  // 0-3
BOUNCE_CONST uint GI_RESOLVE_BINDING_NORMALS = 4u;
BOUNCE_CONST uint GI_RESOLVE_BINDING_DEPTH = 5u;
BOUNCE_CONST uint GI_RESOLVE_BINDING_FLAGS = 6u;
BOUNCE_CONST uint GI_RESOLVE_BINDING_OUTPUT = 7u;     // RGBA16F irradiance / pi per unit albedo
BOUNCE_CONST uint GI_RESOLVE_BINDING_OCCLUSION = 8u;  // gi.resolve-occlusion
BOUNCE_CONST uint GI_RESOLVE_BINDING_COUNT = 9u;

// gi-resolve-find-occluders (render resolution) and gi-trace-resolve-visibility (one thread
// per entry of GI_RAY_LIST_RESOLVE): which of gi-restir-resolve's samples are hidden from
// pixels beside an occluder. Same reservoir and GBuffer bindings as the resolve; they write
// gi.resolve-occlusion, R32UI: bit i (i < 4) = the resolve's i-th sample is hidden,
// RESOLVE_BESIDE_OCCLUDER = the pixel is beside an occluder (gi-spatial-denoise keeps it as is).
// The first writes every pixel (0, or RESOLVE_BESIDE_OCCLUDER and an entry in the list), the
// second the listed pixels' hidden samples.
BOUNCE_CONST uint GI_RESOLVE_VISIBILITY_BINDING_OUTPUT = 7u;
BOUNCE_CONST uint GI_RESOLVE_VISIBILITY_BINDING_COUNT = 8u;
BOUNCE_CONST uint RESOLVE_BESIDE_OCCLUDER = 16u;
// Most reservoirs gi-restir-resolve reads per pixel (RestirGiConstants::resolveSamples is
// clamped to it): gi-trace-resolve-visibility runs this many threads per listed pixel.
BOUNCE_CONST uint RESOLVE_MAX_SAMPLES = 4u;

// gi-restir-spatial-0 / -1 and gi-restir-patch-reservoir: a reservoir in, a reservoir out
BOUNCE_CONST uint GI_SPATIAL_BINDING_INPUT = 0u;   // 0-3
BOUNCE_CONST uint GI_SPATIAL_BINDING_OUTPUT = 4u;  // 4-7
BOUNCE_CONST uint GI_SPATIAL_BINDING_NORMALS = 8u;
BOUNCE_CONST uint GI_SPATIAL_BINDING_DEPTH = 9u;
BOUNCE_CONST uint GI_SPATIAL_BINDING_ESTIMATE = 10u;  // RGBA16F the output reservoir's estimate
BOUNCE_CONST uint GI_SPATIAL_BINDING_COUNT = 11u;

// gi-trace-spatial-validation-rays: groups of GI_VALIDATION_GROUP_SIDE^2 pixels whose rays it
// bins by direction (rt/ray_bins.glsl)
BOUNCE_CONST uint GI_VALIDATION_GROUP_SIDE = 16u;
BOUNCE_CONST uint GI_VALIDATION_BINDING_INPUT = 0u;  // 0-3, gi-restir-spatial-1's reservoir
BOUNCE_CONST uint GI_VALIDATION_BINDING_TEMPORAL_SAMPLE = 4u;  // gi.reservoir.sample (own)
BOUNCE_CONST uint GI_VALIDATION_BINDING_NORMALS = 5u;
BOUNCE_CONST uint GI_VALIDATION_BINDING_DEPTH = 6u;
BOUNCE_CONST uint GI_VALIDATION_BINDING_VELOCITY = 7u;
BOUNCE_CONST uint GI_VALIDATION_BINDING_VALIDITY_PREVIOUS = 8u;  // R16F history
BOUNCE_CONST uint GI_VALIDATION_BINDING_VALIDITY_CURRENT = 9u;   // R16F spatial occlusion validity
BOUNCE_CONST uint GI_VALIDATION_BINDING_SAMPLE_OUT = 10u;        // RGBA32F x2, W (0 when occluded)
BOUNCE_CONST uint GI_VALIDATION_BINDING_ESTIMATE = 11u;
BOUNCE_CONST uint GI_VALIDATION_BINDING_COUNT = 12u;

// gi-temporal-denoise
BOUNCE_CONST uint GI_DENOISE_BINDING_INPUT = 0u;
BOUNCE_CONST uint GI_DENOISE_BINDING_NORMALS = 1u;
BOUNCE_CONST uint GI_DENOISE_BINDING_DEPTH = 2u;
BOUNCE_CONST uint GI_DENOISE_BINDING_PREVIOUS_DEPTH = 3u;
BOUNCE_CONST uint GI_DENOISE_BINDING_FLAGS = 4u;
BOUNCE_CONST uint GI_DENOISE_BINDING_VELOCITY = 5u;
BOUNCE_CONST uint GI_DENOISE_BINDING_PREVIOUS = 6u;  // RGBA16F rgb, frames accumulated (a)
BOUNCE_CONST uint GI_DENOISE_BINDING_CURRENT = 7u;
BOUNCE_CONST uint GI_DENOISE_BINDING_OUTPUT = 8u;    // gi.diffuse
BOUNCE_CONST uint GI_DENOISE_BINDING_VALIDITY = 9u;  // gi.reservoir-validity (GI resolution)
// this frame's spatial occlusion validity (GI resolution; read only with
// RESTIR_GI_FLAG_SPATIAL_VALIDATION)
BOUNCE_CONST uint GI_DENOISE_BINDING_OCCLUSION_VALIDITY = 10u;
// The fast history (gi.denoised-fast: rgb, frames accumulated), whose neighbourhood clips the
// slow one.
BOUNCE_CONST uint GI_DENOISE_BINDING_PREVIOUS_FAST = 11u;
BOUNCE_CONST uint GI_DENOISE_BINDING_CURRENT_FAST = 12u;
BOUNCE_CONST uint GI_DENOISE_BINDING_COUNT = 13u;

// gi-spatial-denoise (render resolution)
BOUNCE_CONST uint GI_SPATIAL_DENOISE_BINDING_INPUT = 0u;  // gi-temporal-denoise's output
BOUNCE_CONST uint GI_SPATIAL_DENOISE_BINDING_NORMALS = 1u;
BOUNCE_CONST uint GI_SPATIAL_DENOISE_BINDING_DEPTH = 2u;
BOUNCE_CONST uint GI_SPATIAL_DENOISE_BINDING_FLAGS = 3u;
BOUNCE_CONST uint GI_SPATIAL_DENOISE_BINDING_OUTPUT = 4u;     // gi.diffuse
BOUNCE_CONST uint GI_SPATIAL_DENOISE_BINDING_OCCLUSION = 5u;  // gi.resolve-occlusion
BOUNCE_CONST uint GI_SPATIAL_DENOISE_BINDING_COUNT = 6u;
// RestirGiPassConstants::variant of its two passes: the blur across the rows, then down the
// columns.
BOUNCE_CONST uint GI_SPATIAL_DENOISE_ROWS = 0u;
BOUNCE_CONST uint GI_SPATIAL_DENOISE_COLUMNS = 1u;
BOUNCE_CONST uint GI_SPATIAL_DENOISE_MAX_RADIUS =
    4u;  // RestirGiSettings::spatialDenoiseRadius at most

BOUNCE_END_SHARED
#endif
