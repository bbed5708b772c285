// `tonemap` (DESIGN.md §4 step 7): exposure, then a filmic curve from scene-referred radiance
// to display-referred [0, 1], still linear (shaders/passes/tonemap.comp).
#pragma once
#include "graph/frame_graph.h"
#include "passes/composite.h"
#include "passes/frame_context.h"
#include "passes/image_pass.h"

namespace bounce {

struct DisplayImage {
  graph::ImageHandle color;  // tonemap.display: rgba16f, linear [0, 1]
};

class TonemapPass {
 public:
  TonemapPass(vk::Context& context, const GpuScene& scene);
  DisplayImage declare(graph::FrameGraph& graph, const FrameContext& frame, const HdrImage& hdr);

 private:
  ImageComputePass pass_;
};

}  // namespace bounce
