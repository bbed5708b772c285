// `scene-update` (DESIGN.md §4): the frame's first pass. Uploads this frame's constants (camera,
// sun, sky, resolution) and the instance transforms and TLAS of objects that moved
// (GpuScene::setInstanceTransforms), and declares them on the graph so that every later pass
// reads them after the upload and the next frame's upload waits for this frame's readers.
#pragma once
#include "graph/frame_graph.h"
#include "passes/frame_context.h"
#include "rt/gpu_scene.h"
#include "vk/resources.h"

namespace bounce {

class SceneUpdatePass {
 public:
  SceneUpdatePass(vk::Context& context, GpuScene& scene);
  // `constants` must stay alive until the frame has been recorded.
  FrameContext declare(graph::FrameGraph& graph, const gpu::FrameConstants& constants,
                       bool lightingCut);
  VkDeviceAddress constantsAddress() const { return constantsBuffer_.address(); }

 private:
  GpuScene& scene_;
  vk::Buffer constantsBuffer_;
};

}  // namespace bounce
