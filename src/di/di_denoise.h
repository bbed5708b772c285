// `di-denoise-*`: the DI signal denoised (docs/di.md, "The denoiser"). One of the library
// denoisers (denoise/library_denoiser.h: SVGF or ReBLUR, docs/denoise.md), instantiated with its
// passes and resources named `di-denoise-*` and `di-denoise.*` (di-denoise-temporal,
// di-denoise-variance, di-denoise-atrous-0..4 for SVGF), on di-shade's di.radiance demodulated
// by di.reflectance, the surface's split-sum directional albedo of both lobes: the filter
// averages incident light, and the last pass multiplies the albedo back (RTXDI and NRD
// denoise demodulated DI the same way, research/gi10_lux_denoisers.md §2.3). Output
// di.denoised, which composite adds instead of di.radiance.
#pragma once
#include "denoise/library_denoiser.h"
#include "di/di_settings.h"
#include "di/di_shade.h"

namespace bounce {

class DiDenoise {
 public:
  // `kind` must not be DiDenoiser::None.
  DiDenoise(vk::Context& context, const GpuScene& scene, DiDenoiser kind);

  // The denoised direct light (di.denoised, rgba16f). `dropHistory`: this frame starts the
  // denoiser's history afresh (a light changed; RestirDi decides).
  graph::ImageHandle declare(graph::FrameGraph& graph, const DiFrame& f, const DirectLight& direct,
                             bool dropHistory);

  uint32_t pipelineCount() const { return denoiser_.pipelineCount(); }

 private:
  LibraryDenoiser denoiser_;
};

}  // namespace bounce
