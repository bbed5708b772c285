// `hybrid`: SVGF (spatial) and ReBLUR (temporal) on the same signal, blended per pixel from the
// history length, the motion and the signal's relative variance (research/gi10_lux_denoisers.md
// §2.3 (f); docs/denoise.md has the rule's thresholds and how they were measured):
//
//   svgf-temporal, -variance              denoise/svgf.h, everywhere (they keep the histories)
//   reblur-pre-blur, -temporal, -history-fix  denoise/reblur.h, everywhere
//   hybrid-classify  each pixel's spatial weight w (the rule), and each 8x8 tile's class: SVGF,
//                    ReBLUR or both, from the weights over the tile and its band (hybrid.tiles)
//   svgf-atrous-*    only on the tiles that need SVGF (the others copy their input)
//   reblur-blur, -post-blur  only on the tiles that need ReBLUR; reblur-stabilize everywhere
//   hybrid-blend     per pixel, mix(reblur, svgf, w), w averaged over a band of pixels so no
//                    seam shows (shaders/denoise/hybrid_blend.comp)
//
// Ten compute pipelines: SVGF's 3, ReBLUR's 5, hybrid-classify's and hybrid-blend's.
#pragma once
#include <cstdint>

#include "denoise/denoise_inputs.h"
#include "denoise/reblur.h"
#include "denoise/svgf.h"

namespace bounce {

struct HybridDenoiseSettings {
  SvgfSettings svgf = SvgfSettings::relaxAtrous();
  ReblurSettings reblur;
  // The spatial weight w (1: SVGF alone, 0: ReBLUR alone) is the largest of three linear ramps:
  // history length in frames from historySpatial (w 1; SVGF's own threshold of a young history,
  // research §2.3 (f): 4) to historyTemporal (w 0; 8); |motion| in pixels from motionTemporal
  // (0; 2) to motionSpatial (1; 8); the signal's relative luminance variance sigma^2 / mu^2
  // (SVGF's temporal moments) from varianceTemporal (0) to varianceSpatial (1), measured on
  // Evolve's GI (docs/denoise.md).
  float historySpatial = 4.0f;
  float historyTemporal = 8.0f;
  float motionTemporal = 2.0f;
  float motionSpatial = 8.0f;
  float varianceTemporal = 0.5f;
  float varianceSpatial = 2.0f;
  // w is averaged over (2 bandRadius + 1)^2 pixels: the band over which one filter hands over
  // to the other. 0: per pixel (seams where the inputs jump, e.g. at a disocclusion's border).
  uint32_t bandRadius = 2;
  // SVGF's à-trous iterations and ReBLUR's blurs filter only the 8x8 tiles whose output the
  // blend reads (hybrid-classify's classes) and copy elsewhere. false: both filter every tile
  // (the output is the same where both are read; for measuring what the tiles save).
  bool skipTiles = true;
};

void validate(const HybridDenoiseSettings& settings);

class HybridDenoiser {
 public:
  static constexpr uint32_t kPipelineCount = Svgf::kPipelineCount + Reblur::kPipelineCount + 2;

  HybridDenoiser(vk::Context& context, const GpuScene& scene,
                 const HybridDenoiseSettings& settings = {});
  // Declares SVGF, ReBLUR, hybrid-classify and hybrid-blend, ending in `output` (RGBA16F: rgb the
  // denoised signal, a the spatial weight w). debugWeight: write w as grey instead (a debug
  // picture).
  void declare(graph::FrameGraph& graph, VkExtent2D resolution, const DenoiseInputs& inputs,
               graph::ImageHandle output, bool debugWeight = false);

  const HybridDenoiseSettings& settings() const { return settings_; }

 private:
  HybridDenoiseSettings settings_;
  Svgf svgf_;
  Reblur reblur_;
  ComputePass classify_;
  ComputePass blend_;
};

}  // namespace bounce
