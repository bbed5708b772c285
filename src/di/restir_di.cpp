#include "di/restir_di.h"

#include <algorithm>

#include <glm/glm.hpp>

#include "core/error.h"

namespace bounce {

namespace {

gpu::DiConstants makeConstants(const DiSettings& s, const GpuLightTables& lights,
                               VkDeviceAddress lightGrid) {
  gpu::DiConstants c{};
  c.lights = lights.address();
  c.hitMap = lights.emissiveHitMap();
  c.lightGrid = lightGrid;
  // A BRDF ray can only meet emissive triangles: none, no ray. With the light grid the light
  // candidates' density, which the BRDF candidate's MIS weight needs, is unknown: no ray either
  // (di_generate_candidates.comp).
  c.brdfCandidates =
      lights.table().emissiveTriangles.empty() || lightGrid != 0 ? 0 : s.brdfCandidates;
  c.brdfCandidateMaxAlpha = s.brdfCandidateMaxRoughness * s.brdfCandidateMaxRoughness;
  c.flags = 0;
  if (s.reuses()) c.flags |= gpu::DI_FLAG_TEMPORAL;
  if (s.reuses() && (s.spatialSamples > 0 || s.disocclusionSamples > 0))
    c.flags |= gpu::DI_FLAG_SPATIAL;
  if (s.unbiased) c.flags |= gpu::DI_FLAG_UNBIASED;
  if (s.tracesCandidateVisibility(lightGrid != 0)) c.flags |= gpu::DI_FLAG_CANDIDATE_VISIBILITY;
  c.lightCandidates = s.lightCandidates;
  c.temporalMaxM = s.temporalMaxM;
  c.depthTolerance = s.depthTolerance;
  c.normalTolerance = s.normalTolerance;
  c.spatialSamples = s.spatialSamples;
  c.disocclusionSamples = s.disocclusionSamples;
  c.disocclusionM = s.disocclusionM;
  c.spatialRadius = s.spatialRadius;
  c.seed = s.seed;
  c.finalVisibilityMaxAge = s.unbiased ? 0u : s.finalVisibilityMaxAge;
  return c;
}

}  // namespace

RestirDi::RestirDi(vk::Context& context, const GpuScene& gpuScene, const Scene& scene,
                   const DiSettings& settings)
    : settings_(settings), lights_(context, gpuScene, scene, /*updatable=*/true) {
  if (!settings.enabled()) fail("ReSTIR DI: built with --di off");
  validate(settings);
  lightState_ = scene.lights;
  const glm::vec3 extent = gpuScene.bounds().empty() ? glm::vec3(1.0f) : gpuScene.bounds().extent();
  dropDistance_ = kDropMove * std::max({extent.x, extent.y, extent.z});
  if (lights_.localLightCount() == 0 && lights_.distantLightCount() == 0) return;
  // A reservoir keeps the light's index in 24 bits (shared/restir_di_io.h).
  if (lights_.localLightCount() >= gpu::DI_MAX_LIGHTS ||
      lights_.distantLightCount() >= gpu::DI_MAX_LIGHTS)
    fail("ReSTIR DI: {} local and {} distant lights: at most {} of each", lights_.localLightCount(),
         lights_.distantLightCount(), gpu::DI_MAX_LIGHTS - 1);
  if (lights_.localLightCount() >= settings.lightGridThreshold)
    grid_.emplace(context, gpuScene, settings, gpuScene.bounds());
  const gpu::DiConstants c = makeConstants(settings, lights_, grid_ ? grid_->address() : 0);
  const bool candidateRay = (c.flags & gpu::DI_FLAG_CANDIDATE_VISIBILITY) != 0;
  // With nothing between them, the candidates are drawn in di-temporal's pass (one surface
  // load, no di.candidate round trip).
  const bool fused = settings.reuses() && !candidateRay && settings.fuseCandidatesWithTemporal;
  if (!fused) candidates_.emplace(context, gpuScene, c.brdfCandidates > 0, candidateRay);
  shade_.emplace(context, gpuScene);
  constants_ = vk::uploadBuffer(context, std::as_bytes(std::span(&c, 1)),
                                VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "di.constants");
  if (settings.reuses()) {
    temporal_.emplace(context, gpuScene, fused, c.brdfCandidates > 0);
    if (c.flags & gpu::DI_FLAG_SPATIAL)
      spatial_.emplace(context, gpuScene, (c.flags & gpu::DI_FLAG_UNBIASED) != 0);
  }
  if (settings.denoiser != DiDenoiser::None) denoise_.emplace(context, gpuScene, settings.denoiser);
}

// Whether `lights`, against the state last set, changed enough to drop the history
// (kDropMove): `reservoirs` for di-temporal's (a light moved or brightened), else for
// the denoiser's (also dimmed, switched off or turned).
bool RestirDi::lightsChanged(std::span<const PunctualLight> lights, bool reservoirs) const {
  for (size_t i = 0; i < lights.size(); ++i) {
    const double before = punctualLightPower(lightState_[i]);
    const double after = punctualLightPower(lights[i]);
    if (after > kHistoryDropRise * before) return true;
    if (glm::distance(lights[i].position, lightState_[i].position) > dropDistance_) return true;
    if (reservoirs) continue;
    if (before > kHistoryDropRise * after) return true;
    // A spot turned by more than about 8 degrees.
    if (glm::dot(lights[i].direction, lightState_[i].direction) < 0.99f) return true;
  }
  return false;
}

bool RestirDi::emittersMoved(const std::vector<gpu::GpuEmissiveTriangle>& before) const {
  const std::vector<gpu::GpuEmissiveTriangle>& after = lights_.table().emissiveTriangles;
  for (size_t i = 0; i < before.size() && i < after.size(); ++i) {
    const glm::vec3 p0 = after[i].p0, q0 = before[i].p0;
    const glm::vec3 p2 = after[i].p0 + after[i].edge2, q2 = before[i].p0 + before[i].edge2;
    if (glm::distance(p0, q0) > dropDistance_ || glm::distance(p2, q2) > dropDistance_) return true;
  }
  return false;
}

void RestirDi::setLights(std::span<const PunctualLight> lights) {
  if (lights.size() != lightState_.size())
    fail("RestirDi::setLights: {} lights for a scene of {}", lights.size(), lightState_.size());
  if (lightsChanged(lights, /*reservoirs=*/true)) dropHistory_ = true;
  if (denoise_ && lightsChanged(lights, /*reservoirs=*/false)) dropDenoiseHistory_ = true;
  std::copy(lights.begin(), lights.end(), lightState_.begin());
  lights_.update(lightState_);
}

void RestirDi::instancesMoved() {
  if (lights_.table().emissiveTriangles.empty()) return;
  const std::vector<gpu::GpuEmissiveTriangle> before = lights_.table().emissiveTriangles;
  lights_.update(lightState_);
  if (emittersMoved(before)) dropHistory_ = dropDenoiseHistory_ = true;
}

uint32_t RestirDi::pipelineCount() const {
  if (!hasLights()) return 0;
  return (candidates_ ? candidates_->pipelineCount() : 0) + 1 + (grid_ ? 1 : 0) +
         (temporal_ ? 1 : 0) + (spatial_ ? 1 : 0) + (denoise_ ? denoise_->pipelineCount() : 0);
}

// The chain, top to bottom (see the header).
DirectLight RestirDi::declare(graph::FrameGraph& graph, const FrameContext& frame,
                              const GBuffer& gbuffer) {
  if (!hasLights()) fail("ReSTIR DI: the scene has no lights; the frame runs no DI pass");
  DiFrame f{frame, gbuffer, constants_.address()};
  f.lights = graph.importBuffer("di.lights", graph::ImportedBuffer::from(lights_.buffer()));
  f.dropHistory = dropHistory_;
  // The flag is cleared when the frame runs, not here: a frame may be declared and never run
  // (the pass names for --view).
  graph.addPass("di-lights-update", graph::QueueKind::Compute)
      .write(f.lights, graph::Access::TransferDst)
      .record([this](VkCommandBuffer cmd, const graph::PassResources&) {
        lights_.recordUpload(cmd);  // nothing when no light changed
        dropHistory_ = false;
        dropDenoiseHistory_ = false;
      });
  if (grid_) f.lightGrid = grid_->declare(graph, f);
  if (showLightGrid_) grid_->declareView(graph, f, *f.lightGrid);
  if (temporal_)
    f.finalReservoirs = graph.createHistoryImage("di.reservoir-final", {kDiReservoirFormat});
  std::optional<graph::ImageHandle> candidates;
  if (candidates_) candidates = candidates_->declare(graph, f);
  graph::ImageHandle reservoirs =
      temporal_ ? temporal_->declare(graph, f, candidates) : candidates.value();
  const graph::ImageHandle temporal = reservoirs;
  if (spatial_) reservoirs = spatial_->declare(graph, f, reservoirs);
  DirectLight direct = shade_->declare(graph, f, reservoirs, temporal);
  if (denoise_) direct.radiance = denoise_->declare(graph, f, direct, dropDenoiseHistory_);
  return direct;
}

}  // namespace bounce
