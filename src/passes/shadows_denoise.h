// `shadows-denoise` (DESIGN.md §4): a reprojected running mean of the raw sun visibility with a
// neighbourhood clamp, upsampled to render resolution (shaders/passes/shadows_denoise.comp).
#pragma once
#include "graph/frame_graph.h"
#include "passes/frame_context.h"
#include "passes/gbuffer.h"
#include "passes/image_pass.h"
#include "passes/shadows_trace.h"

namespace bounce {

// The denoised sun visibility at render resolution.
struct Shadows {
  graph::ImageHandle visibility;  // shadows.visibility (current): rg16f, r = visibility
};

class ShadowsDenoisePass {
 public:
  ShadowsDenoisePass(vk::Context& context, const GpuScene& scene);
  Shadows declare(graph::FrameGraph& graph, const FrameContext& frame, const GBuffer& gbuffer,
                  const RawShadows& raw);

 private:
  ImageComputePass pass_;
};

}  // namespace bounce
