// `gi-spatial-denoise` (seed 000, desktop preset): one edge-aware blur of a diffuse-GI signal
// at render resolution, taps only on this pixel's surface; pixels beside an occluder keep their
// value (shaders/denoise/gi_spatial_denoise.comp). Separable: two passes,
// `gi-spatial-denoise-rows` across the rows, then `gi-spatial-denoise` down the columns.
#pragma once
#include <optional>

#include "graph/frame_graph.h"
#include "passes/frame_context.h"
#include "passes/gbuffer.h"
#include "passes/image_pass.h"
#include "shared/restir_gi_io.h"

namespace bounce {

struct GiSpatialDenoiseInputs {
  graph::ImageHandle noisy;  // rgba16f at render resolution
  // r32ui at render resolution: RESOLVE_BESIDE_OCCLUDER per pixel (gi.resolve-occlusion),
  // where the producer has it; else the shader ignores the binding (the GBuffer flags fill it).
  std::optional<graph::ImageHandle> occlusion;
  // The producer's constants (RestirGiConstants: spatialDenoiseRadius, surface tolerances).
  gpu::RestirGiPassConstants constants{};
};

class GiSpatialDenoise {
 public:
  GiSpatialDenoise(vk::Context& context, const GpuScene& scene);
  // Writes `output` (rgba16f at render resolution).
  void declare(graph::FrameGraph& graph, const FrameContext& frame, const GBuffer& gbuffer,
               const GiSpatialDenoiseInputs& inputs, graph::ImageHandle output);

 private:
  void declareDirection(graph::FrameGraph& graph, const FrameContext& frame, const GBuffer& gbuffer,
                        const GiSpatialDenoiseInputs& in, graph::ImageHandle input,
                        graph::ImageHandle output, uint32_t direction, const char* name);

  // One pipeline, a descriptor set per direction (dispatch 0: rows, 1: columns).
  ComputePass pass_;
};

}  // namespace bounce
