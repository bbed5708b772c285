#include "di/di_denoise.h"

#include <cstdlib>
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
static LibraryDenoiserSettings tmpSettings() {
  LibraryDenoiserSettings s;
  if (const char* e = std::getenv("TMP_PHIL")) s.svgf.phiLuminance = std::atof(e);
  if (const char* e = std::getenv("TMP_ALPHA")) s.svgf.colorAlpha = s.svgf.momentsAlpha = std::atof(e);
  if (const char* e = std::getenv("TMP_MALPHA")) s.svgf.momentsAlpha = std::atof(e);
  if (const char* e = std::getenv("TMP_ITER")) s.svgf.iterations = std::atoi(e);
  return s;
}
DiDenoise::DiDenoise(vk::Context& context, const GpuScene& scene, DiDenoiser kind)
    : denoiser_(context, scene, libraryKind(kind), tmpSettings(), "di-denoise") {}

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
