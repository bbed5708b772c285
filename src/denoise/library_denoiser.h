// One of the library denoisers (svgf, reblur, hybrid; docs/denoise.md) chosen at run time, for
// the callers that pick one by name: the GI techniques (`--denoiser`) and the public API
// (include/bounce/denoiser.h). Each knows nothing of the technique that made the signal.
#pragma once
#include <memory>
#include <string>

#include "denoise/denoise_inputs.h"
#include "denoise/hybrid_denoiser.h"
#include "denoise/reblur.h"
#include "denoise/svgf.h"

namespace bounce {

enum class DenoiserKind : uint32_t { Svgf = 0, Reblur = 1, Hybrid = 2 };

const char* denoiserName(DenoiserKind kind);  // "svgf", "reblur", "hybrid"

// Every kind's settings; only the chosen kind's are read (the hybrid's carry their own SVGF and
// ReBLUR settings).
struct LibraryDenoiserSettings {
  SvgfSettings svgf = SvgfSettings::relaxAtrous();
  ReblurSettings reblur;
  HybridDenoiseSettings hybrid;
};

class LibraryDenoiser {
 public:
  // `name`: the prefix of the chosen denoiser's passes and resources (Svgf's and Reblur's
  // `name`); empty: the kind's own ("svgf", "reblur"). The hybrid has no other names.
  LibraryDenoiser(vk::Context& context, const GpuScene& scene, DenoiserKind kind,
                  const LibraryDenoiserSettings& settings = {}, const std::string& name = {});
  ~LibraryDenoiser();

  // Declares the denoiser's passes, ending in `output` (RGBA16F, rgb the denoised signal).
  void declare(graph::FrameGraph& graph, VkExtent2D resolution, const DenoiseInputs& inputs,
               graph::ImageHandle output);

  DenoiserKind kind() const { return kind_; }
  uint32_t pipelineCount() const;

 private:
  DenoiserKind kind_;
  std::unique_ptr<Svgf> svgf_;
  std::unique_ptr<Reblur> reblur_;
  std::unique_ptr<HybridDenoiser> hybrid_;
};

}  // namespace bounce
