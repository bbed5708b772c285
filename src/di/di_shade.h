// `di-shade` (shaders/di/di_shade.comp): the final reservoir's sample with the full BRDF, W and
// one shadow ray: di.radiance, the direct light composite adds (through the DI denoiser when
// one is on, di/di_denoise.h).
#pragma once
#include "di/di_pass.h"

namespace bounce {

struct DirectLight {
  graph::ImageHandle radiance;  // di.radiance: rgba16f, W/(m^2 sr) towards the camera
  graph::ImageHandle info;      // di.reservoir-info: rgba32f (light index or -1, M, W, visibility)
  // di.reflectance: rgba16f, the surface's directional albedo of both lobes (split sum; 1 where
  // there is no surface): what the DI denoiser demodulates by
  graph::ImageHandle reflectance;
};

class DiShadePass {
 public:
  DiShadePass(vk::Context& context, const GpuScene& scene);
  DirectLight declare(graph::FrameGraph& graph, const DiFrame& f, graph::ImageHandle reservoirs);

 private:
  DiPass pass_;
};

}  // namespace bounce
