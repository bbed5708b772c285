// `svgf`: spatiotemporal variance-guided filtering (Schied et al., HPG 2017;
// research/gi10_lux_denoisers.md §2.3 (d) and §3.1; docs/denoise.md) of any noisy signal with a
// G-buffer, as a library unit that knows nothing of the GI technique that made the signal:
//
//   svgf-temporal   reprojected running mean of the (demodulated) colour and of the first two
//                   luminance moments, disocclusion tests on depth and normal; the temporal
//                   luminance variance where the history is long enough, and the list of the
//                   8x8 tiles where it is not
//   svgf-variance   on the listed tiles (an indirect dispatch), a 7x7 spatial estimate of the
//                   variance while the history is shorter than 4 frames
//   svgf-atrous-0..N  2 to 5 edge-avoiding à-trous iterations (the paper's 5x5 B3 kernel or
//                   RELAX's 3x3 Gaussian, steps 1, 2, 4, ...) with depth, normal and
//                   luminance-variance edge stops; iteration 0 (SvgfSettings::feedbackIteration)
//                   is the next frame's colour history; the last remodulates the albedo
//
// Three compute pipelines (shaders/denoise/svgf_{temporal,variance,atrous}.comp); the à-trous
// passes share one, with a descriptor set each. Every image is at the frame graph's render
// resolution. Resources: history svgf.surface, svgf.moments, svgf.illumination;
// svgf.accumulated, svgf.slope, svgf.filtered-moments, svgf.atrous-1..3; the buffer
// svgf.variance-tiles (formats: shared/svgf_io.h).
#pragma once
#include <cstdint>
#include <optional>
#include <string>

#include <glm/glm.hpp>

#include "denoise/denoise_inputs.h"
#include "graph/frame_graph.h"
#include "passes/image_pass.h"
#include "shared/svgf_io.h"
#include "tools/image_io.h"

namespace bounce {

// The scale of the à-trous luminance stop exp(-|l_p - l_q| / (sigma_l s)) (Schied eq. 5).
//   Centre: s = the centre's standard deviation (its variance 3x3-prefiltered), the paper's.
//           A bright outlier (a large variance) takes its dark neighbours in while they refuse
//           it, so on heavy-tailed noise the mean drops (sunroom's GI -5.6 %, DI -6 %).
//   Shared: s = sqrt(s_p s_q), the geometric mean of the centre's and the tap's: a tap weighs
//           the same from either side, so an outlier keeps its energy, and a pixel whose
//           variance is 0 (certain, as a shadow) takes no noisy light in. docs/denoise.md.
enum class SvgfLuminanceStop : uint32_t { Centre, Shared };

// The à-trous kernel (svgf_atrous.comp).
//   BSpline5x5:  the paper's 5x5 B3 spline (25 taps; per iteration, white noise's variance
//                13x lower).
//   Gaussian3x3: NRD RELAX's 3x3 sampled Gaussian (9 taps, 8x lower; research/
//                gi10_lux_denoisers.md §3.3), with 5 iterations about the reach of the B3 with
//                4 (31 against 30 pixels) for 45 taps against 100.
enum class SvgfKernel : uint32_t { BSpline5x5, Gaussian3x3 };

// The defaults are the paper's (Schied et al. 2017 §5) except where noted.
struct SvgfSettings {
  // Temporal blend weight of a new sample, colour and moments (paper: 0.2 both; Falcor's
  // default colour alpha is 0.05). Lower: a longer effective history (about 2 / alpha - 1
  // frames), smoother, slower to follow a change. In (0, 1].
  float colorAlpha = 0.2f;
  float momentsAlpha = 0.2f;
  // The history length is counted up to this many frames (Falcor: 32); it only steers
  // the blend weight max(alpha, 1 / length), so above 1 / alpha frames it changes nothing.
  float maxHistory = 32.0f;
  // Disocclusion: last frame's surface is this pixel's when its view depth differs by at most
  // depthTolerance x depth (plus twice the surface's slope per pixel) and the normals' cosine is
  // at least normalTolerance. Looser: less history lost on moving views, more ghosting.
  float depthTolerance = 0.05f;
  float normalTolerance = 0.9f;
  // Below this history length (frames) svgf-variance estimates the variance over 7x7 pixels
  // (paper: 4). 0: always temporal.
  uint32_t varianceHistoryFrames = 4;
  // À-trous iterations, steps 1, 2, 4, ... (paper: 5, a 62-pixel reach; Falcor: 4, 30 px). 2 to 5.
  uint32_t iterations = 5;
  // The iteration whose output is the next frame's colour history (svgf.illumination; paper:
  // 0, Schied §4.3; Falcor's "FeedbackTap": 1). Below iterations - 1: the last remodulates.
  uint32_t feedbackIteration = 0;
  // Edge stops (paper §4.2 eq. 3-5): sigma_z (depth, times the slope and the tap distance),
  // sigma_n (exponent of the normals' cosine), sigma_l (luminance, in standard deviations).
  // Larger: more blur across the edge kind.
  float phiDepth = 1.0f;
  float phiNormal = 128.0f;
  float phiLuminance = 4.0f;
  // Not the paper's (Centre): see SvgfLuminanceStop.
  SvgfLuminanceStop luminanceStop = SvgfLuminanceStop::Shared;
  SvgfKernel kernel = SvgfKernel::BSpline5x5;
  // The centre's variance is blurred by a 3x3 Gaussian before every à-trous iteration (the
  // paper's, Schied eq. 5), or false: before the first only (NRD RELAX), later iterations taking
  // the variance the previous one filtered (9 reads fewer per pixel and iteration).
  bool prefilterEveryIteration = true;

  // Falcor's SVGFPass defaults where they differ from the paper's: colour alpha 0.05 (a longer
  // history, about 39 frames), sigma_l 10 (a looser luminance stop), 4 iterations (a 30-pixel
  // reach, one pass less). Not Falcor's feedback tap 1: the history from the second iteration
  // measured worse on Evolve's GI (docs/decisions.md). What Evolve's GI, the DI denoiser and
  // the public API used until session 29; on the Cornell box HDR-FLIP 0.148-0.158 against the
  // paper's 0.162 (docs/denoise.md).
  static SvgfSettings falcor() {
    SvgfSettings s;
    s.colorAlpha = 0.05f;
    s.phiLuminance = 10.0f;
    s.iterations = 4;
    return s;
  }

  // Falcor's temporal settings and luminance stop with NRD RELAX's à-trous: the 3x3 kernel, the
  // variance prefiltered before the first iteration only, 4 iterations (a 15-pixel reach). What
  // Evolve's GI, Lux, the hybrid, the DI denoiser and the public API use: as good as falcor()
  // on every measure taken (HDR-FLIP within 0.001 on cornell, sunroom, foliage and a camera
  // path; flicker the same) at half its GPU time (docs/denoise.md, "RELAX's à-trous").
  static SvgfSettings relaxAtrous() {
    SvgfSettings s = falcor();
    s.kernel = SvgfKernel::Gaussian3x3;
    s.prefilterEveryIteration = false;
    return s;
  }
};

// Throws bounce::Error naming the field when a setting is out of its documented range.
void validate(const SvgfSettings& settings);

// svgf.surface's texel (RG32UI: the depth's bits, the normal octahedral as two snorm16; the
// shaders' packSurface in denoise/packed_surface.glsl), for declareAtrousStep's `surface` image,
// and what the shaders unpack from it (xyz normal as quantised, w depth): a test gives the CPU
// reference the unpacked surface, so that both see the same normal.
glm::uvec2 packSvgfSurface(const glm::vec4& normalDepth);
glm::vec4 unpackSvgfSurface(const glm::uvec2& texel);

// The debug view of a denoiser's packed `<name>.surface` (and `.previous`; SVGF's and ReBLUR's,
// both RG32UI): normal and depth unpacked, as the RGBA32F image it was before it was packed.
bool isSvgfSurfaceView(const graph::DebugView& view);
ImageRGBA32F decodeSvgfSurfaceView(const graph::DebugView& view);

// What SVGF filters (denoise/denoise_inputs.h; shared/svgf_io.h has the formats).
using SvgfInputs = DenoiseInputs;

class Svgf {
 public:
  // The distinct compute pipelines SVGF compiles (issue 21's permutation budget).
  static constexpr uint32_t kPipelineCount = 3;

  // `name` prefixes every pass (`<name>-temporal`, ...) and resource (`<name>.moments`, ...), so
  // that two instances can run in one frame (the GI's and ReSTIR DI's, di/di_denoise.h).
  Svgf(vk::Context& context, const GpuScene& scene, const SvgfSettings& settings = {},
       std::string name = "svgf");
  // Declares SVGF's passes on `graph`, ending in `output` (RGBA16F: rgb the denoised signal,
  // a its remaining luminance variance). `resolution`: the graph's render resolution.
  // Returns svgf.moments (current; RGBA32F: mu1, mu2, history length), which the hybrid
  // denoiser reads.
  graph::ImageHandle declare(graph::FrameGraph& graph, VkExtent2D resolution,
                             const SvgfInputs& inputs, graph::ImageHandle output);

  // declare() in two halves, for the hybrid denoiser, which classifies tiles between them.
  // The first declares svgf-temporal and svgf-variance, the second the à-trous iterations.
  struct Temporal {
    graph::ImageHandle filtered;  // svgf.filtered-moments: colour, variance
    graph::ImageHandle surface;   // svgf.surface (current)
    graph::ImageHandle slope;     // svgf.slope: the view depth's change per pixel
    graph::ImageHandle moments;   // svgf.moments (current)
    graph::ImageHandle
        illumination;  // svgf.illumination (current): the feedback iteration writes it
  };
  Temporal declareTemporal(graph::FrameGraph& graph, VkExtent2D resolution,
                           const SvgfInputs& inputs);
  // `tiles` (RGBA16F, one texel per 8x8 tile, SVGF_GROUP_SIZE): where its red is 0 the
  // iterations copy their input instead of filtering (the hybrid uses ReBLUR alone there).
  void declareSpatial(graph::FrameGraph& graph, VkExtent2D resolution, const SvgfInputs& inputs,
                      const Temporal& temporal, graph::ImageHandle output,
                      std::optional<graph::ImageHandle> tiles = std::nullopt);
  // One à-trous iteration alone (pass svgf-atrous-<iteration>), for tests against the CPU
  // reference (denoise/svgf_reference.h): `input` RGBA16F colour + variance, `surface` RG32UI
  // packed normal + depth (svgf.surface's format: packSvgfSurface), `slope` R32F the depth's
  // change per pixel (svgf.slope: svgfDepthSlopes); no albedo.
  void declareAtrousStep(graph::FrameGraph& graph, VkExtent2D resolution, graph::ImageHandle input,
                         graph::ImageHandle surface, graph::ImageHandle slope, uint32_t iteration,
                         graph::ImageHandle output);

  const SvgfSettings& settings() const { return settings_; }

 private:
  gpu::SvgfConstants constants(VkExtent2D resolution, const SvgfInputs& inputs) const;
  void declareAtrous(graph::FrameGraph& graph, const gpu::SvgfConstants& constants,
                     graph::ImageHandle input, graph::ImageHandle surface, graph::ImageHandle slope,
                     graph::ImageHandle albedo, uint32_t iteration, graph::ImageHandle output,
                     std::optional<graph::ImageHandle> tiles = std::nullopt);

  SvgfSettings settings_;
  std::string name_;
  ComputePass temporal_;
  ComputePass variance_;
  ComputePass atrous_;  // one descriptor set per iteration
};

}  // namespace bounce
