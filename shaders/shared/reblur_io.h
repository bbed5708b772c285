// reblur-pre-blur, reblur-temporal, reblur-history-fix, reblur-blur, reblur-post-blur,
// reblur-stabilize (src/denoise/reblur.h; docs/denoise.md) and hybrid-blend
// (src/denoise/hybrid_denoiser.h): push constants and image bindings (set 1) of the ReBLUR-style
// diffuse denoiser (NRD REBLUR_DIFFUSE as the pattern; research/gi10_lux_denoisers.md §2.3 (e),
// §3.2) and of the hybrid that blends it with SVGF (§2.3 (f)). Every pass runs at the signal's
// resolution, one thread per pixel.
//
// Images (the caller's): noisy, depth, normals, motion, albedo as SVGF's (shared/svgf_io.h).
// Images (ReBLUR's own):
//   reblur.surface      RG32UI   (history) view depth bits (0: no surface), unit normal octahedral
//                                as two snorm16 (denoise/packed_surface.glsl)
//   reblur.slope        R32F     reblur-pre-blur's view-depth change per pixel (every later pass's
//                                plane test; written once instead of read from 4 neighbours each)
//   reblur.pre-blurred  RGBA16F  reblur-pre-blur's output (rgb; demodulated)
//   reblur.fast         RGBA16F  (history) rgb the fast history (few frames), a its length
//   reblur.accumulated  RGBA16F  (history) reblur-temporal's slow history: rgb, a its length in
//                                frames; next frame's slow history (unblurred: docs/denoise.md)
//   reblur.footprint    R8UI     reblur-temporal's disocclusion tests: which of the 4 last-frame
//                                pixels around the reprojected position hold this surface
//   reblur.fixed        RGBA16F  reblur-history-fix's output: rgb, a the (anti-lagged) length
//   reblur.fast-moments RGBA32UI reblur-history-fix's 3x3 mean and deviation of reblur.fast
//   reblur.blurred      RGBA16F  reblur-blur's output: rgb, a the length
//   reblur.post-blurred RGBA16F  reblur-post-blur's output: rgb, a the length
//   reblur.stable       RGBA16F  (history) reblur-stabilize's output: rgb, a its frame count
#ifndef BOUNCE_SHARED_REBLUR_IO_H
#define BOUNCE_SHARED_REBLUR_IO_H
#include "shared/compat.h"

BOUNCE_BEGIN_SHARED

// Push constants of every ReBLUR shader; ReblurSettings (src/denoise/reblur.h) documents each.
struct ReblurConstants {
  uvec2 resolution;
  uint flags;         // REBLUR_FLAG_*
  uint historyValid;  // 0: the first frame or after a reset: no history is read
  uint frame;         // frame index: rotates the Poisson taps
  float blurRadius;   // reblur-pre-blur: its radius; reblur-blur / -post-blur: the radius at
                      // history length 0 (it shrinks with the history)
  float minBlurRadius;
  float depthTolerance;   // disocclusion and the blurs' plane test: relative view-depth difference
  float normalTolerance;  // disocclusion: cosine between normals at least this
  float normalPower;      // the blurs' normal weight: max(0, n.n_q)^normalPower
  float maxAccumulatedFrames;
  float maxFastAccumulatedFrames;
  float historyFixFrames;    // below this history length reblur-history-fix rebuilds the pixel
  float historyFixStride;    // pixels between its 5x5 taps at history 0
  float sigmaScale;          // clamps: mean +- sigmaScale standard deviations of the fast history
  float antilagSensitivity;  // how fast a clamped history is shortened (0: no anti-lag)
  float maxStabilizedFrames;
  float
      antiFireflySigma;  // reblur-history-fix's anti-firefly clamp in standard deviations (0: off)
};
BOUNCE_CHECK_SIZE(ReblurConstants, 72);

BOUNCE_CONST uint REBLUR_GROUP_SIZE = 8u;
BOUNCE_CONST uint REBLUR_FLAG_OCTAHEDRAL_NORMALS = 1u;
BOUNCE_CONST uint REBLUR_FLAG_ALBEDO = 2u;
BOUNCE_CONST uint REBLUR_FLAG_POST_BLUR = 4u;  // reblur-blur's shader run as reblur-post-blur
// reblur-blur / -post-blur: the hybrid's tile classes are bound (REBLUR_BLUR_BINDING_TILES); a
// workgroup whose tile does not need ReBLUR (green 0) copies its input.
BOUNCE_CONST uint REBLUR_FLAG_TILES = 8u;

// reblur-pre-blur
BOUNCE_CONST uint REBLUR_PRE_BLUR_BINDING_NOISY = 0u;
BOUNCE_CONST uint REBLUR_PRE_BLUR_BINDING_DEPTH = 1u;
BOUNCE_CONST uint REBLUR_PRE_BLUR_BINDING_NORMALS = 2u;
BOUNCE_CONST uint REBLUR_PRE_BLUR_BINDING_ALBEDO = 3u;
BOUNCE_CONST uint REBLUR_PRE_BLUR_BINDING_SURFACE = 4u;  // reblur.surface (current), written
BOUNCE_CONST uint REBLUR_PRE_BLUR_BINDING_OUTPUT = 5u;   // reblur.pre-blurred
BOUNCE_CONST uint REBLUR_PRE_BLUR_BINDING_SLOPE = 6u;    // reblur.slope (R32F), written
BOUNCE_CONST uint REBLUR_PRE_BLUR_BINDING_COUNT = 7u;

// reblur-temporal
BOUNCE_CONST uint REBLUR_TEMPORAL_BINDING_INPUT = 0u;  // reblur.pre-blurred
BOUNCE_CONST uint REBLUR_TEMPORAL_BINDING_SURFACE = 1u;
BOUNCE_CONST uint REBLUR_TEMPORAL_BINDING_MOTION = 2u;
BOUNCE_CONST uint REBLUR_TEMPORAL_BINDING_PREVIOUS_SURFACE = 3u;
BOUNCE_CONST uint REBLUR_TEMPORAL_BINDING_PREVIOUS_HISTORY = 4u;  // reblur.accumulated (previous)
BOUNCE_CONST uint REBLUR_TEMPORAL_BINDING_PREVIOUS_FAST = 5u;
BOUNCE_CONST uint REBLUR_TEMPORAL_BINDING_FAST = 6u;         // reblur.fast (current)
BOUNCE_CONST uint REBLUR_TEMPORAL_BINDING_ACCUMULATED = 7u;  // reblur.accumulated (current)
BOUNCE_CONST uint REBLUR_TEMPORAL_BINDING_SLOPE = 8u;        // reblur.slope
// reblur.footprint (R8UI, written): bit i set where last-frame pixel p0 + (i & 1, i >> 1) of the
// bilinear footprint holds this pixel's surface (reblur_common.glsl bilinearFootprint)
BOUNCE_CONST uint REBLUR_TEMPORAL_BINDING_FOOTPRINT = 9u;
BOUNCE_CONST uint REBLUR_TEMPORAL_BINDING_COUNT = 10u;

// reblur-history-fix
BOUNCE_CONST uint REBLUR_HISTORY_FIX_BINDING_INPUT = 0u;  // reblur.accumulated
BOUNCE_CONST uint REBLUR_HISTORY_FIX_BINDING_FAST = 1u;
BOUNCE_CONST uint REBLUR_HISTORY_FIX_BINDING_SURFACE = 2u;
BOUNCE_CONST uint REBLUR_HISTORY_FIX_BINDING_OUTPUT = 3u;  // reblur.fixed
BOUNCE_CONST uint REBLUR_HISTORY_FIX_BINDING_SLOPE = 4u;
// reblur.fast-moments (RGBA32UI, written): the fast history's 3x3 same-surface mean and standard
// deviation, as halves: x mean.rg, y (mean.b, sigma.r), z sigma.gb; w 1 where the pixel has a
// surface (0 elsewhere, all of it). reblur-stabilize clamps to it and reads its surface flag.
BOUNCE_CONST uint REBLUR_HISTORY_FIX_BINDING_FAST_MOMENTS = 5u;
BOUNCE_CONST uint REBLUR_HISTORY_FIX_BINDING_COUNT = 6u;

// reblur-blur and reblur-post-blur (one shader)
BOUNCE_CONST uint REBLUR_BLUR_BINDING_INPUT = 0u;
BOUNCE_CONST uint REBLUR_BLUR_BINDING_SURFACE = 1u;
BOUNCE_CONST uint REBLUR_BLUR_BINDING_OUTPUT = 2u;
BOUNCE_CONST uint REBLUR_BLUR_BINDING_TILES = 3u;  // hybrid.tiles with REBLUR_FLAG_TILES
BOUNCE_CONST uint REBLUR_BLUR_BINDING_SLOPE = 4u;
BOUNCE_CONST uint REBLUR_BLUR_BINDING_COUNT = 5u;

// reblur-stabilize
BOUNCE_CONST uint REBLUR_STABILIZE_BINDING_INPUT = 0u;         // reblur.post-blurred
BOUNCE_CONST uint REBLUR_STABILIZE_BINDING_FAST_MOMENTS = 1u;  // reblur.fast-moments
BOUNCE_CONST uint REBLUR_STABILIZE_BINDING_MOTION = 2u;
BOUNCE_CONST uint REBLUR_STABILIZE_BINDING_FOOTPRINT = 3u;  // reblur.footprint
BOUNCE_CONST uint REBLUR_STABILIZE_BINDING_PREVIOUS_STABLE = 4u;
BOUNCE_CONST uint REBLUR_STABILIZE_BINDING_ALBEDO = 5u;
BOUNCE_CONST uint REBLUR_STABILIZE_BINDING_STABLE = 6u;  // reblur.stable (current)
BOUNCE_CONST uint REBLUR_STABILIZE_BINDING_OUTPUT = 7u;
BOUNCE_CONST uint REBLUR_STABILIZE_BINDING_COUNT = 8u;

// The 8 Poisson-disk taps of the blurs (unit disk; NRD's pre-pass, blur and post-blur each take
// 8), rotated per pixel and frame.
BOUNCE_CONST uint REBLUR_POISSON_TAPS = 8u;

// hybrid-blend (src/denoise/hybrid_denoiser.h)
struct HybridBlendConstants {
  uvec2 resolution;
  float historySpatial;    // history length (frames) at or below which SVGF alone is used
  float historyTemporal;   // at or above which ReBLUR may be used alone
  float motionTemporal;    // |motion| (pixels) at or below which ReBLUR may be used alone
  float motionSpatial;     // at or above which SVGF alone is used
  float varianceTemporal;  // relative luminance variance at or below which ReBLUR may be alone
  float varianceSpatial;   // at or above which SVGF alone is used
  uint bandRadius;         // the spatial weight is averaged over (2 r + 1)^2 pixels
  uint debugWeight;        // 1: output the spatial weight instead of the blend
};
BOUNCE_CHECK_SIZE(HybridBlendConstants, 40);

BOUNCE_CONST uint HYBRID_BLEND_BINDING_SVGF = 0u;    // rgb SVGF's output
BOUNCE_CONST uint HYBRID_BLEND_BINDING_REBLUR = 1u;  // rgb ReBLUR's output
BOUNCE_CONST uint HYBRID_BLEND_BINDING_WEIGHT = 2u;  // hybrid.weight: r each pixel's own w
BOUNCE_CONST uint HYBRID_BLEND_BINDING_OUTPUT = 3u;
BOUNCE_CONST uint HYBRID_BLEND_BINDING_COUNT = 4u;

// hybrid-classify (its constants HybridBlendConstants): each pixel's spatial weight w, and for
// each 8x8 tile (REBLUR_GROUP_SIZE, the blurs' and the à-trous' workgroup) which filter the
// blend will read there, over the tile and its band (bandRadius): red 1 where some w > 0
// (SVGF), green 1 where some w < 1 (ReBLUR).
BOUNCE_CONST uint HYBRID_CLASSIFY_BINDING_REBLUR = 0u;   // reblur.fixed: a the history length
BOUNCE_CONST uint HYBRID_CLASSIFY_BINDING_MOMENTS = 1u;  // svgf.moments: x mu1, y mu2
BOUNCE_CONST uint HYBRID_CLASSIFY_BINDING_MOTION = 2u;
BOUNCE_CONST uint HYBRID_CLASSIFY_BINDING_WEIGHT = 3u;  // hybrid.weight (RGBA16F, r w)
BOUNCE_CONST uint HYBRID_CLASSIFY_BINDING_TILES = 4u;   // hybrid.tiles (RGBA16F, 1/8 size)
BOUNCE_CONST uint HYBRID_CLASSIFY_BINDING_COUNT = 5u;
BOUNCE_CONST uint HYBRID_TILE_SIZE = 8u;

BOUNCE_END_SHARED

#endif
