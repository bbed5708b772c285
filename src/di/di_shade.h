// `di-shade` (shaders/di/di_shade.comp): the final reservoir's sample with the full BRDF, W and
// one shadow ray: di.radiance, the direct light composite adds.
#pragma once
#include "di/di_pass.h"

namespace bounce {

struct DirectLight {
  graph::ImageHandle radiance;  // di.radiance: rgba16f, W/(m^2 sr) towards the camera
  graph::ImageHandle info;      // di.reservoir-info: rgba32f (light index or -1, M, W, visibility)
};

class DiShadePass {
 public:
  DiShadePass(vk::Context& context, const GpuScene& scene);
  DirectLight declare(graph::FrameGraph& graph, const DiFrame& f, graph::ImageHandle reservoirs);

 private:
  DiPass pass_;
};

}  // namespace bounce
