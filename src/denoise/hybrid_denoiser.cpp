#include "denoise/hybrid_denoiser.h"

#include "core/error.h"

namespace bounce {

using graph::Access;

void validate(const HybridDenoiseSettings& s) {
  validate(s.svgf);
  validate(s.reblur);
  auto ordered = [](float lo, float hi) { return lo >= 0.0f && hi > lo && hi < 1e30f; };
  if (!ordered(s.historySpatial, s.historyTemporal))
    fail("hybrid denoiser: history thresholds spatial {} < temporal {} frames expected",
         s.historySpatial, s.historyTemporal);
  if (!ordered(s.motionTemporal, s.motionSpatial))
    fail("hybrid denoiser: motion thresholds temporal {} < spatial {} pixels expected",
         s.motionTemporal, s.motionSpatial);
  if (!ordered(s.varianceTemporal, s.varianceSpatial))
    fail("hybrid denoiser: variance thresholds temporal {} < spatial {} expected",
         s.varianceTemporal, s.varianceSpatial);
  if (s.bandRadius > 8) fail("hybrid denoiser: band radius {} must be 0 to 8", s.bandRadius);
}

HybridDenoiser::HybridDenoiser(vk::Context& context, const GpuScene& scene,
                               const HybridDenoiseSettings& settings)
    : settings_(settings),
      svgf_(context, scene, settings.svgf),
      reblur_(context, scene, settings.reblur),
      blend_(context, scene, "denoise/hybrid_blend", gpu::HYBRID_BLEND_BINDING_COUNT,
             sizeof(gpu::HybridBlendConstants)) {
  validate(settings_);
}

void HybridDenoiser::declare(graph::FrameGraph& graph, VkExtent2D resolution,
                             const DenoiseInputs& in, graph::ImageHandle output, bool debugWeight) {
  constexpr VkFormat kRgba16f = VK_FORMAT_R16G16B16A16_SFLOAT;
  graph::ImageHandle spatial = graph.createImage("hybrid.svgf", {kRgba16f});
  graph::ImageHandle temporal = graph.createImage("hybrid.reblur", {kRgba16f});
  graph::ImageHandle moments = svgf_.declare(graph, resolution, in, spatial);
  reblur_.declare(graph, resolution, in, temporal);

  const HybridDenoiseSettings& s = settings_;
  gpu::HybridBlendConstants c{};
  c.resolution = {resolution.width, resolution.height};
  c.historySpatial = s.historySpatial;
  c.historyTemporal = s.historyTemporal;
  c.motionTemporal = s.motionTemporal;
  c.motionSpatial = s.motionSpatial;
  c.varianceTemporal = s.varianceTemporal;
  c.varianceSpatial = s.varianceSpatial;
  c.bandRadius = s.bandRadius;
  c.debugWeight = debugWeight ? 1u : 0u;
  graph.addPass("hybrid-blend", graph::QueueKind::Compute)
      .read(spatial, Access::StorageRead, gpu::HYBRID_BLEND_BINDING_SVGF)
      .read(temporal, Access::StorageRead, gpu::HYBRID_BLEND_BINDING_REBLUR)
      .read(moments, Access::StorageRead, gpu::HYBRID_BLEND_BINDING_MOMENTS)
      .read(in.motion, Access::StorageRead, gpu::HYBRID_BLEND_BINDING_MOTION)
      .write(output, Access::StorageWrite, gpu::HYBRID_BLEND_BINDING_OUTPUT)
      .record([this, c](VkCommandBuffer cmd, const graph::PassResources& r) {
        blend_.bind(cmd, c, r);
        vk::ComputePipeline::dispatchCovering(cmd, c.resolution.x, c.resolution.y,
                                              gpu::REBLUR_GROUP_SIZE, gpu::REBLUR_GROUP_SIZE);
      });
}

}  // namespace bounce
