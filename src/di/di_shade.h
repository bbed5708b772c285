// `di-shade` (shaders/di/di_shade.comp): the final reservoir's sample with the full BRDF, W and
// one shadow ray: di.radiance, the direct light composite adds (through the DI denoiser when
// one is on, di/di_denoise.h); and di.reservoir-final, di-temporal's next history
// (DiFrame::finalReservoirs): di-temporal's reservoir, with W = 0 where it holds the sample
// shaded and the ray was blocked.
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
  // `reservoirs`: the chain's last (spatial's, or temporal's); `temporal`: di-temporal's (or,
  // without reuse, the same as `reservoirs`).
  DirectLight declare(graph::FrameGraph& graph, const DiFrame& f, graph::ImageHandle reservoirs,
                      graph::ImageHandle temporal);

 private:
  DiPass pass_;
};

}  // namespace bounce
