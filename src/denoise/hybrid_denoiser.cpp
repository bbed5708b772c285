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
      classify_(context, scene, "denoise/hybrid_classify", gpu::HYBRID_CLASSIFY_BINDING_COUNT,
                sizeof(gpu::HybridBlendConstants)),
      blend_(context, scene, "denoise/hybrid_blend", gpu::HYBRID_BLEND_BINDING_COUNT,
             sizeof(gpu::HybridBlendConstants)) {
  validate(settings_);
}

void HybridDenoiser::declare(graph::FrameGraph& graph, VkExtent2D resolution,
                             const DenoiseInputs& in, graph::ImageHandle output, bool debugWeight) {
  constexpr VkFormat kRgba16f = VK_FORMAT_R16G16B16A16_SFLOAT;
  graph::ImageHandle spatial = graph.createImage("hybrid.svgf", {kRgba16f});
  graph::ImageHandle temporal = graph.createImage("hybrid.reblur", {kRgba16f});
  graph::ImageHandle weight = graph.createImage("hybrid.weight", {kRgba16f});
  graph::ImageHandle tiles = graph.createImage(
      "hybrid.tiles", {kRgba16f, graph::ImageSize::dividedRes(gpu::HYBRID_TILE_SIZE)});
  const Svgf::Temporal svgf = svgf_.declareTemporal(graph, resolution, in);
  const Reblur::Temporal reblur = reblur_.declareTemporal(graph, resolution, in);

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
  auto dispatch = [](VkCommandBuffer cmd, const gpu::HybridBlendConstants& k) {
    vk::ComputePipeline::dispatchCovering(cmd, k.resolution.x, k.resolution.y,
                                          gpu::HYBRID_TILE_SIZE, gpu::HYBRID_TILE_SIZE);
  };
  graph.addPass("hybrid-classify", graph::QueueKind::Compute)
      .read(reblur.fixed, Access::StorageRead, gpu::HYBRID_CLASSIFY_BINDING_REBLUR)
      .read(svgf.moments, Access::StorageRead, gpu::HYBRID_CLASSIFY_BINDING_MOMENTS)
      .read(in.motion, Access::StorageRead, gpu::HYBRID_CLASSIFY_BINDING_MOTION)
      .write(weight, Access::StorageWrite, gpu::HYBRID_CLASSIFY_BINDING_WEIGHT)
      .write(tiles, Access::StorageWrite, gpu::HYBRID_CLASSIFY_BINDING_TILES)
      .record([this, c, dispatch](VkCommandBuffer cmd, const graph::PassResources& r) {
        classify_.bind(cmd, c, r);
        dispatch(cmd, c);
      });

  // Both spatial halves dispatch every tile; the tiles whose output the blend will not read
  // copy their input instead of filtering.
  const std::optional<graph::ImageHandle> skip =
      s.skipTiles ? std::optional<graph::ImageHandle>(tiles) : std::nullopt;
  svgf_.declareSpatial(graph, resolution, in, svgf, spatial, skip);
  reblur_.declareSpatial(graph, resolution, in, reblur, temporal, skip);

  graph.addPass("hybrid-blend", graph::QueueKind::Compute)
      .read(spatial, Access::StorageRead, gpu::HYBRID_BLEND_BINDING_SVGF)
      .read(temporal, Access::StorageRead, gpu::HYBRID_BLEND_BINDING_REBLUR)
      .read(weight, Access::StorageRead, gpu::HYBRID_BLEND_BINDING_WEIGHT)
      .write(output, Access::StorageWrite, gpu::HYBRID_BLEND_BINDING_OUTPUT)
      .record([this, c, dispatch](VkCommandBuffer cmd, const graph::PassResources& r) {
        blend_.bind(cmd, c, r);
        dispatch(cmd, c);
      });
}

}  // namespace bounce
