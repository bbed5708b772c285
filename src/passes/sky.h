// `sky` (DESIGN.md §4): the radiance of the sky where no surface is seen (the scene's constant
// sky or the daylight model driven by the sun), zero over surfaces (shaders/passes/sky.comp).
#pragma once
#include "graph/frame_graph.h"
#include "passes/frame_context.h"
#include "passes/gbuffer.h"
#include "passes/image_pass.h"

namespace bounce {

struct SkyImage {
  graph::ImageHandle radiance;  // sky.radiance: rgba16f, W/(m^2 sr)
};

class SkyPass {
 public:
  SkyPass(vk::Context& context, const GpuScene& scene);
  SkyImage declare(graph::FrameGraph& graph, const FrameContext& frame, const GBuffer& gbuffer);

 private:
  ImageComputePass pass_;
};

}  // namespace bounce
