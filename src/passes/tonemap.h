// `tonemap` (DESIGN.md §4 step 7): exposure, then a filmic curve from scene-referred radiance
// to display-referred [0, 1], still linear (shaders/passes/tonemap.comp). The exposure is
// automatic exposure's (passes/auto_exposure.h) when the frame gives one, else the frame's
// fixed 2^exposureStops (FrameConstants::exposure).
#pragma once
#include <optional>

#include "graph/frame_graph.h"
#include "passes/auto_exposure.h"
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
  DisplayImage declare(graph::FrameGraph& graph, const FrameContext& frame, const HdrImage& hdr,
                       const std::optional<Exposure>& exposure);

 private:
  ComputePass pass_;
};

}  // namespace bounce
