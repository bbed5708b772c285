#include "di/di_denoise.h"

#include "core/error.h"

namespace bounce {

namespace {

DenoiserKind libraryKind(DiDenoiser kind) {
  switch (kind) {
    case DiDenoiser::Svgf:
      return DenoiserKind::Svgf;
    case DiDenoiser::Reblur:
      return DenoiserKind::Reblur;
    case DiDenoiser::None:
      break;
  }
  fail("DI denoiser: none chosen");
}

}  // namespace

// SVGF with Falcor's settings, as Evolve's GI uses it (docs/denoise.md: they measured better
// than the paper's on Cornell); ReBLUR with NRD's defaults.
DiDenoise::DiDenoise(vk::Context& context, const GpuScene& scene, DiDenoiser kind)
    : denoiser_(context, scene, libraryKind(kind), LibraryDenoiserSettings{}, "di-denoise") {}

graph::ImageHandle DiDenoise::declare(graph::FrameGraph& graph, const DiFrame& f,
                                      const DirectLight& direct, bool dropHistory) {
  const graph::ImageHandle output =
      graph.createImage("di.denoised", {VK_FORMAT_R16G16B16A16_SFLOAT});
  const GBuffer& g = f.gbuffer;
  DenoiseInputs in{direct.radiance, g.depth.current, g.normals, g.velocity};
  in.albedo = direct.reflectance;
  in.octahedralNormals = true;
  in.dropHistory = dropHistory;
  denoiser_.declare(graph, f.frame.resolution, in, output);
  return output;
}

}  // namespace bounce
