// `gi-temporal-denoise` (seed 000, DESIGN.md §4 step 5): a reprojected running mean of a noisy
// diffuse-GI signal with variance clipping against a fast history, its length guided by the
// signal's validity images (shaders/denoise/gi_temporal_denoise.comp).
#pragma once
#include <optional>

#include "graph/frame_graph.h"
#include "passes/frame_context.h"
#include "passes/gbuffer.h"
#include "passes/image_pass.h"
#include "shared/restir_gi_io.h"

namespace bounce {

struct GiTemporalDenoiseInputs {
  graph::ImageHandle noisy;     // rgba16f at render resolution: the signal to denoise
  graph::ImageHandle validity;  // rgba16f at GI resolution: how far each reservoir still holds
  // r16f at GI resolution: the spatial occlusion validity (current), where the producer has it.
  std::optional<graph::ImageHandle> occlusionValidity;
  // Any r16f image bound in its place when absent (the shader then ignores it).
  graph::ImageHandle placeholderR16f;
  // The producer's constants (RestirGiConstants: history length, clip sigma, firefly ratio);
  // historyValid is set here.
  gpu::RestirGiPassConstants constants{};
  bool dropHistory = false;  // a lighting cut: the history holds the old light
};

class GiTemporalDenoise {
 public:
  GiTemporalDenoise(vk::Context& context, const GpuScene& scene);
  // Writes `output` (rgba16f at render resolution); keeps the histories gi.denoised and
  // gi.denoised-fast.
  void declare(graph::FrameGraph& graph, const FrameContext& frame, const GBuffer& gbuffer,
               const GiTemporalDenoiseInputs& inputs, graph::ImageHandle output);

 private:
  ComputePass pass_;
};

}  // namespace bounce
