#include "denoise/library_denoiser.h"

#include "core/error.h"

namespace bounce {

const char* denoiserName(DenoiserKind kind) {
  switch (kind) {
    case DenoiserKind::Svgf:
      return "svgf";
    case DenoiserKind::Reblur:
      return "reblur";
    case DenoiserKind::Hybrid:
      return "hybrid";
  }
  return "?";
}

LibraryDenoiser::LibraryDenoiser(vk::Context& context, const GpuScene& scene, DenoiserKind kind,
                                 const LibraryDenoiserSettings& settings, const std::string& name)
    : kind_(kind) {
  const std::string prefix = name.empty() ? denoiserName(kind) : name;
  switch (kind) {
    case DenoiserKind::Svgf:
      svgf_ = std::make_unique<Svgf>(context, scene, settings.svgf, prefix);
      break;
    case DenoiserKind::Reblur:
      reblur_ = std::make_unique<Reblur>(context, scene, settings.reblur, prefix);
      break;
    case DenoiserKind::Hybrid:
      if (!name.empty()) fail("the hybrid denoiser's passes cannot be renamed ({})", name);
      hybrid_ = std::make_unique<HybridDenoiser>(context, scene, settings.hybrid);
      break;
  }
}

LibraryDenoiser::~LibraryDenoiser() = default;

void LibraryDenoiser::declare(graph::FrameGraph& graph, VkExtent2D resolution,
                              const DenoiseInputs& inputs, graph::ImageHandle output) {
  if (svgf_) svgf_->declare(graph, resolution, inputs, output);
  if (reblur_) reblur_->declare(graph, resolution, inputs, output);
  if (hybrid_) hybrid_->declare(graph, resolution, inputs, output);
}

uint32_t LibraryDenoiser::pipelineCount() const {
  return svgf_     ? Svgf::kPipelineCount
         : reblur_ ? Reblur::kPipelineCount
                   : HybridDenoiser::kPipelineCount;
}

}  // namespace bounce
