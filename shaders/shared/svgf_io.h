// svgf-temporal, svgf-variance, svgf-atrous-N (src/denoise/svgf.h; docs/denoise.md): the push
// constants and image bindings (set 1) of the SVGF denoiser (Schied et al. 2017, "Spatiotemporal
// Variance-Guided Filtering"; research/gi10_lux_denoisers.md §3.1). Every pass runs at the
// signal's resolution, one thread per pixel.
//
// Images (the caller's):
//   noisy     RGBA16F  the signal to denoise (rgb; a ignored)
//   depth     R32F     linear view depth; 0, negative or non-finite: no surface (passed through)
//   normals   RGBA16F  world-space normal: xyz, or octahedral in xy (SVGF_FLAG_OCTAHEDRAL_NORMALS,
//                      Bounce's gbuffer.normals)
//   motion    RG16F    pixels moved since last frame (this frame's position minus last frame's)
//   albedo    RGBA16F  with SVGF_FLAG_ALBEDO: the signal is divided by it before filtering and
//                      multiplied back at the end (the filter sees irradiance, not texture)
// Images (SVGF's own):
//   svgf.surface       RG32UI   (history) x the view depth's bits (0: no surface), y the unit
//                               normal, octahedral, two snorm16 (denoise/packed_surface.glsl
//                               packSurface)
//   svgf.moments       RGBA32F  (history) x, y: running means of luminance and luminance^2,
//                               z: history length in frames (0: none)
//   svgf.accumulated   RGBA16F  svgf-temporal's running mean (rgb; demodulated)
//   svgf.filtered-moments RGBA16F svgf-variance's output: rgb colour, a luminance variance
//   svgf.illumination  RGBA16F  (history) svgf-atrous-0's output (SvgfSettings::
//                               feedbackIteration's), the colour history of the next frame
//                               (Schied §4.3: the first iteration is fed back; Falcor: the second)
//   svgf.atrous-N      RGBA16F  the other iterations' outputs but the last (rgb, a variance)
#ifndef BOUNCE_SHARED_SVGF_IO_H
#define BOUNCE_SHARED_SVGF_IO_H
#include "shared/compat.h"

BOUNCE_BEGIN_SHARED

// Push constants of all three shaders; SvgfSettings (src/denoise/svgf.h) documents each knob.
struct SvgfConstants {
  uvec2 resolution;
  uint flags;         // SVGF_FLAG_*
  uint historyValid;  // 0: the first frame or after a reset: no history is read
  float colorAlpha;   // temporal blend weight of the new colour (at least 1 / history length)
  float momentsAlpha;
  float depthTolerance;   // disocclusion: relative view-depth difference allowed
  float normalTolerance;  // disocclusion: cosine between the normals at least this
  float phiDepth;         // edge stops (Schied eq. 3-5): sigma_z, sigma_n, sigma_l
  float phiNormal;
  float phiLuminance;
  float maxHistory;             // frames, the cap on the history length
  uint varianceHistoryFrames;   // below: svgf-variance estimates the variance spatially (7x7)
  uint step;                    // svgf-atrous: the tap spacing 2^iteration in pixels
  uint iteration;               // svgf-atrous: 0 .. iterations - 1
  uint lastIteration;           // svgf-atrous: 1 on the last one (remodulation with the albedo)
  DeviceAddress varianceTiles;  // svgf-temporal, svgf-variance: svgf.variance-tiles
};
BOUNCE_CHECK_SIZE(SvgfConstants, 72);

// svgf.variance-tiles: svgf-temporal lists the 8x8 tiles (SVGF_GROUP_SIZE) holding a pixel whose
// history is shorter than varianceHistoryFrames (one uint each, x | y << 16, after this header)
// and writes svgf.filtered-moments itself everywhere else; svgf-variance runs on the listed
// tiles only, through an indirect dispatch of the header's first three words.
struct SvgfVarianceTilesHeader {
  uint groupsX;  // the tile count
  uint groupsY;  // 1
  uint groupsZ;  // 1
  uint unused;
};
BOUNCE_CHECK_SIZE(SvgfVarianceTilesHeader, 16);

BOUNCE_CONST uint SVGF_GROUP_SIZE = 8u;
BOUNCE_CONST uint SVGF_FLAG_OCTAHEDRAL_NORMALS = 1u;
BOUNCE_CONST uint SVGF_FLAG_ALBEDO = 2u;
// svgf-atrous-*: the hybrid's tile classes are bound (SVGF_ATROUS_BINDING_TILES); a workgroup
// whose tile does not need SVGF (red 0) copies its input.
BOUNCE_CONST uint SVGF_FLAG_TILES = 4u;
// svgf-atrous-*: the luminance stop's scale is shared by the centre and the tap (the geometric
// mean of their standard deviations, SvgfLuminanceStop::Shared) instead of the centre's alone.
BOUNCE_CONST uint SVGF_FLAG_SHARED_LUMINANCE_STOP = 8u;
// svgf-atrous-*: the 3x3 kernel (SvgfKernel::Gaussian3x3) instead of the 5x5 B3 spline.
BOUNCE_CONST uint SVGF_FLAG_KERNEL_3X3 = 16u;
// svgf-atrous-*: the centre's variance is 3x3-prefiltered on the first iteration only (RELAX);
// later ones take it as the previous iteration filtered it (SvgfSettings::prefilterEveryIteration).
BOUNCE_CONST uint SVGF_FLAG_PREFILTER_FIRST_ONLY = 32u;
// The variance (alpha) svgf-variance and the à-trous iterations but the last give a pixel
// without a surface, so that svgf-atrous's 3x3 variance prefilter skips it from the signal alone
// (without reading svgf.surface at 9 pixels); the last iteration writes 0 there.
BOUNCE_CONST float SVGF_NO_SURFACE_VARIANCE = -1.0;

// svgf-temporal
BOUNCE_CONST uint SVGF_TEMPORAL_BINDING_NOISY = 0u;
BOUNCE_CONST uint SVGF_TEMPORAL_BINDING_DEPTH = 1u;
BOUNCE_CONST uint SVGF_TEMPORAL_BINDING_NORMALS = 2u;
BOUNCE_CONST uint SVGF_TEMPORAL_BINDING_MOTION = 3u;
BOUNCE_CONST uint SVGF_TEMPORAL_BINDING_ALBEDO = 4u;
BOUNCE_CONST uint SVGF_TEMPORAL_BINDING_PREVIOUS_SURFACE = 5u;
BOUNCE_CONST uint SVGF_TEMPORAL_BINDING_PREVIOUS_MOMENTS = 6u;
BOUNCE_CONST uint SVGF_TEMPORAL_BINDING_PREVIOUS_ILLUMINATION = 7u;
BOUNCE_CONST uint SVGF_TEMPORAL_BINDING_SURFACE = 8u;       // svgf.surface (current)
BOUNCE_CONST uint SVGF_TEMPORAL_BINDING_MOMENTS = 9u;       // svgf.moments (current)
BOUNCE_CONST uint SVGF_TEMPORAL_BINDING_ACCUMULATED = 10u;  // svgf.accumulated
BOUNCE_CONST uint SVGF_TEMPORAL_BINDING_SLOPE = 11u;        // svgf.slope
BOUNCE_CONST uint SVGF_TEMPORAL_BINDING_FILTERED = 12u;     // svgf.filtered-moments
BOUNCE_CONST uint SVGF_TEMPORAL_BINDING_COUNT = 13u;

// svgf-variance
BOUNCE_CONST uint SVGF_VARIANCE_BINDING_ACCUMULATED = 0u;
BOUNCE_CONST uint SVGF_VARIANCE_BINDING_MOMENTS = 1u;
BOUNCE_CONST uint SVGF_VARIANCE_BINDING_SURFACE = 2u;
BOUNCE_CONST uint SVGF_VARIANCE_BINDING_OUTPUT = 3u;  // svgf.filtered-moments
BOUNCE_CONST uint SVGF_VARIANCE_BINDING_SLOPE = 4u;   // svgf.slope
BOUNCE_CONST uint SVGF_VARIANCE_BINDING_COUNT = 5u;

// svgf-atrous-N
BOUNCE_CONST uint SVGF_ATROUS_BINDING_INPUT = 0u;    // rgb colour, a variance
BOUNCE_CONST uint SVGF_ATROUS_BINDING_SURFACE = 1u;  // svgf.surface (current)
BOUNCE_CONST uint SVGF_ATROUS_BINDING_ALBEDO = 2u;   // read on the last iteration with the flag
BOUNCE_CONST uint SVGF_ATROUS_BINDING_OUTPUT = 3u;
BOUNCE_CONST uint SVGF_ATROUS_BINDING_TILES = 4u;  // hybrid.tiles with SVGF_FLAG_TILES
BOUNCE_CONST uint SVGF_ATROUS_BINDING_SLOPE = 5u;  // svgf.slope
BOUNCE_CONST uint SVGF_ATROUS_BINDING_COUNT = 6u;

// Rec. 709 luminance, the moments' and the edge stop's measure.
BOUNCE_CONST float SVGF_LUMINANCE_R = 0.2126f;
BOUNCE_CONST float SVGF_LUMINANCE_G = 0.7152f;
BOUNCE_CONST float SVGF_LUMINANCE_B = 0.0722f;
// The B3-spline kernel's 1-D weights at offsets 0, +-1, +-2 (Schied §4.2; Dammertz et al. 2010).
BOUNCE_CONST float SVGF_KERNEL_0 = 3.0f / 8.0f;
BOUNCE_CONST float SVGF_KERNEL_1 = 1.0f / 4.0f;
BOUNCE_CONST float SVGF_KERNEL_2 = 1.0f / 16.0f;
// SvgfKernel::Gaussian3x3: NRD RELAX's 3x3 à-trous kernel, a sampled Gaussian whose 1-D weights
// at offsets 0 and +-1 sum to 1 (research/gi10_lux_denoisers.md §3.3).
BOUNCE_CONST float SVGF_GAUSSIAN_0 = 0.44198f;
BOUNCE_CONST float SVGF_GAUSSIAN_1 = 0.27901f;

BOUNCE_END_SHARED

#endif
