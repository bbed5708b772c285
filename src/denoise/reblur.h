// `reblur`: a ReBLUR-style diffuse denoiser (NRD REBLUR_DIFFUSE as the pattern;
// research/gi10_lux_denoisers.md §2.3 (e), §3.2; docs/denoise.md) of any noisy signal with a
// G-buffer, as a library unit that knows nothing of the GI technique that made the signal:
//
//   reblur-pre-blur     8 Poisson taps in a 30-pixel disk (at 1440p, scaled with the height)
//                       on the noisy signal (plane and normal weights), writes reblur.surface
//   reblur-temporal     reprojected slow (30 frames) and fast (6 frames) running means, the
//                       next frame's histories
//   reblur-history-fix  rebuilds histories shorter than 3 frames from a sparse 5x5 kernel
//                       (stride 14 px); clamps the slow history to the fast one's neighbourhood
//                       (+-2 sigma) and shortens it where it moved (anti-lag)
//   reblur-blur         8 Poisson taps, radius 30 / (1 + history length), at least 1
//   reblur-post-blur    the same at twice the radius
//   reblur-stabilize    a 63-frame stabilised history clamped to the fast one's neighbourhood
//                       (+-2 sigma, anti-lag); remodulates the albedo
//
// Five compute pipelines (shaders/denoise/reblur_{pre_blur,temporal,history_fix,blur,
// stabilize}.comp); the blur and the post-blur share one, with a descriptor set each. Every
// image is at the frame graph's render resolution (formats: shared/reblur_io.h).
#pragma once
#include <cstdint>
#include <optional>
#include <string>

#include "denoise/denoise_inputs.h"
#include "graph/frame_graph.h"
#include "passes/image_pass.h"
#include "shared/reblur_io.h"

namespace bounce {

// The defaults are NRD's REBLUR_DIFFUSE (research/gi10_lux_denoisers.md §3.2) except where noted.
struct ReblurSettings {
  // The image height at which the radii and the history fix's stride below are given in
  // pixels: at another height they scale with it (height / radiusReferenceHeight), so that a
  // blur covers the same part of the view at every resolution. NRD gives its radii for 1440p
  // ("30 is a baseline for 1440p", its ReblurSettings). 0: the radii are pixels at every size.
  // At 64x48 NRD's 30 px would span half the view (docs/denoise.md, the sunroom ablation).
  float radiusReferenceHeight = 1440.0f;
  // reblur-pre-blur's disk radius in pixels at the reference height (NRD
  // diffusePrepassBlurRadius 30), never below minBlurRadius once scaled. 0: no pre-blur (the pass
  // still runs, as a copy). Larger: less noise enters the history, more detail lost (NRD shrinks
  // it near contacts with the hit distance, which Bounce's signal does not carry).
  float preBlurRadius = 30.0f;
  // reblur-blur's radius at the reference height for a history of 0 frames (NRD maxBlurRadius
  // 30), divided by 1 + history length, never below minBlurRadius (NRD 1, in pixels at every
  // size); reblur-post-blur's is twice that.
  float maxBlurRadius = 30.0f;
  float minBlurRadius = 1.0f;
  // Slow and fast history lengths in frames (NRD maxAccumulatedFrameNum 30, at most 63;
  // maxFastAccumulatedFrameNum 6). Longer slow: smoother, slower without anti-lag; the fast one
  // only bounds the slow one (the clamps), so longer fast: less anti-lag, more lag.
  float maxAccumulatedFrames = 30.0f;
  float maxFastAccumulatedFrames = 6.0f;
  // Histories shorter than this many frames are rebuilt spatially (NRD historyFixFrameNum 3),
  // from taps this many pixels apart at a history of 1 frame (NRD 14; at the reference height,
  // scaled as the radii, at least 1 pixel). 0 frames: off.
  float historyFixFrames = 3.0f;
  float historyFixStride = 14.0f;
  // The clamps of the slow and stabilised histories: the fast history's 3x3 mean +- this many
  // standard deviations (NRD fastHistoryClampingSigmaScale 2; seed 002's 3 sigma is a TAA clamp).
  // Smaller: less lag and ghosting, more noise and bias on skewed noise.
  float sigmaScale = 2.0f;
  // Anti-lag: where a clamp moved a history by d standard deviations, its length is divided by
  // 1 + antilagSensitivity x d (NRD's sensitivity 3). 0: clamp only, keep the length.
  float antilagSensitivity = 3.0f;
  // Anti-firefly: reblur-history-fix clamps a pixel's luminance to the mean +- antiFireflySigma
  // standard deviations of its neighbours on the same surface in a 9x9 window less its 3x3
  // centre (NRD's REBLUR default: on, radius 4 px, 2 sigma). 0: off, Bounce's default: on the
  // 1-frame sunroom GI, 2 sigma moved the mean 1.2 % further down and raised the squared error
  // for 2 % less error at depth edges (docs/denoise.md, "Anti-firefly").
  float antiFireflySigma = 0.0f;
  // reblur-stabilize's history length in frames (NRD maxStabilizedFrameNum 63). 1: off.
  float maxStabilizedFrames = 63.0f;
  // Disocclusion and the blurs' plane test: view depth within depthTolerance x depth (plus the
  // surface's slope times the distance), normals' cosine at least normalTolerance; the blurs
  // weigh a tap by max(0, n.n_q)^normalPower. As SVGF's (SvgfSettings).
  float depthTolerance = 0.05f;
  float normalTolerance = 0.9f;
  float normalPower = 128.0f;
};

// Throws bounce::Error naming the field when a setting is out of its documented range.
void validate(const ReblurSettings& settings);

class Reblur {
 public:
  // The distinct compute pipelines ReBLUR compiles (issue 21's permutation budget).
  static constexpr uint32_t kPipelineCount = 5;

  // `name` prefixes every pass (`<name>-temporal`, ...) and resource (`<name>.stable`, ...), so
  // that two instances can run in one frame (the GI's and ReSTIR DI's, di/di_denoise.h).
  Reblur(vk::Context& context, const GpuScene& scene, const ReblurSettings& settings = {},
         std::string name = "reblur");
  // Declares ReBLUR's passes on `graph`, ending in `output` (RGBA16F: rgb the denoised signal,
  // a the slow history's length in frames after anti-lag). `resolution`: the graph's render
  // resolution.
  void declare(graph::FrameGraph& graph, VkExtent2D resolution, const DenoiseInputs& inputs,
               graph::ImageHandle output);

  // declare() in two halves, for the hybrid denoiser, which classifies tiles between them: the
  // first declares reblur-pre-blur, -temporal and -history-fix; the second the blurs and
  // reblur-stabilize.
  struct Temporal {
    graph::ImageHandle fixed;        // reblur.fixed: rgb, a the history length after anti-lag
    graph::ImageHandle fastMoments;  // reblur.fast-moments: the fast history's 3x3 statistics
    graph::HistoryImage surface;
    graph::ImageHandle slope;      // reblur.slope: the view depth's change per pixel
    graph::ImageHandle footprint;  // reblur.footprint: reblur-temporal's disocclusion tests
  };
  Temporal declareTemporal(graph::FrameGraph& graph, VkExtent2D resolution,
                           const DenoiseInputs& inputs);
  // `tiles` (RGBA16F, one texel per 8x8 tile, REBLUR_GROUP_SIZE): where its green is 0 the
  // blurs copy their input instead of filtering (the hybrid uses SVGF alone there);
  // reblur-stabilize runs everywhere (it keeps reblur.stable).
  void declareSpatial(graph::FrameGraph& graph, VkExtent2D resolution, const DenoiseInputs& inputs,
                      const Temporal& temporal, graph::ImageHandle output,
                      std::optional<graph::ImageHandle> tiles = std::nullopt);

  const ReblurSettings& settings() const { return settings_; }

 private:
  gpu::ReblurConstants constants(VkExtent2D resolution, const DenoiseInputs& inputs) const;
  // A length in pixels at radiusReferenceHeight, at this resolution, at least `floor`.
  float scaled(float pixels, VkExtent2D resolution, float floor) const;

  ReblurSettings settings_;
  std::string name_;
  ComputePass preBlur_;
  ComputePass temporal_;
  ComputePass historyFix_;
  ComputePass blur_;  // reblur-blur and reblur-post-blur: a descriptor set each
  ComputePass stabilize_;
  uint32_t frame_ = 0;  // rotates the blurs' taps
};

}  // namespace bounce
