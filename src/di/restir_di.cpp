#include "di/restir_di.h"

#include "core/error.h"

namespace bounce {

namespace {

gpu::DiConstants makeConstants(const DiSettings& s, VkDeviceAddress lights,
                               VkDeviceAddress lightGrid) {
  gpu::DiConstants c{};
  c.lights = lights;
  c.lightGrid = lightGrid;
  c.flags = 0;
  if (s.reuses()) c.flags |= gpu::DI_FLAG_TEMPORAL;
  if (s.reuses() && (s.spatialSamples > 0 || s.disocclusionSamples > 0))
    c.flags |= gpu::DI_FLAG_SPATIAL;
  if (s.unbiased) c.flags |= gpu::DI_FLAG_UNBIASED;
  if (s.candidateVisibility) c.flags |= gpu::DI_FLAG_CANDIDATE_VISIBILITY;
  c.lightCandidates = s.lightCandidates;
  c.temporalMaxM = s.temporalMaxM;
  c.depthTolerance = s.depthTolerance;
  c.normalTolerance = s.normalTolerance;
  c.spatialSamples = s.spatialSamples;
  c.disocclusionSamples = s.disocclusionSamples;
  c.disocclusionM = s.disocclusionM;
  c.spatialRadius = s.spatialRadius;
  c.seed = s.seed;
  return c;
}

}  // namespace

RestirDi::RestirDi(vk::Context& context, const GpuScene& gpuScene, const Scene& scene,
                   const DiSettings& settings)
    : settings_(settings), lights_(context, gpuScene, scene) {
  if (!settings.enabled()) fail("ReSTIR DI: built with --di off");
  validate(settings);
  if (lights_.localLightCount() == 0 && lights_.distantLightCount() == 0) return;
  if (lights_.localLightCount() >= settings.lightGridThreshold)
    grid_.emplace(context, gpuScene, settings, gpuScene.bounds());
  candidates_.emplace(context, gpuScene);
  shade_.emplace(context, gpuScene);
  const gpu::DiConstants c =
      makeConstants(settings, lights_.address(), grid_ ? grid_->address() : 0);
  constants_ = vk::uploadBuffer(context, std::as_bytes(std::span(&c, 1)),
                                VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "di.constants");
  if (settings.reuses()) {
    temporal_.emplace(context, gpuScene);
    if (c.flags & gpu::DI_FLAG_SPATIAL) spatial_.emplace(context, gpuScene);
  }
}

// The chain, top to bottom (see the header).
DirectLight RestirDi::declare(graph::FrameGraph& graph, const FrameContext& frame,
                              const GBuffer& gbuffer) {
  if (!hasLights()) fail("ReSTIR DI: the scene has no lights; the frame runs no DI pass");
  DiFrame f{frame, gbuffer, constants_.address()};
  if (grid_) f.lightGrid = grid_->declare(graph, f);
  graph::ImageHandle reservoirs = candidates_->declare(graph, f);
  if (temporal_) reservoirs = temporal_->declare(graph, f, reservoirs);
  if (spatial_) reservoirs = spatial_->declare(graph, f, reservoirs);
  return shade_->declare(graph, f, reservoirs);
}

}  // namespace bounce
