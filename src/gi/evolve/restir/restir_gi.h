// Evolve's ReSTIR GI chain (seed 000; DESIGN.md §4 step 5): `--gi evolve`. By stage:
//
//   (cache-*)    the clipmap cache's update (ClipmapCache::declareUpdate), when the 2nd vertex
//                continues into the cache (RestirGiSecondVertex::Cache)
//   candidates   gi-prepare-diffuse-rays, gi-trace-diffuse-rays, gi-shade-diffuse-hits,
//                gi-trace-diffuse-nee-rays,
//                gi-resolve-diffuse-rays (candidates.h)
//   temporal     gi-restir-temporal (temporal.h)
//   spatial      gi-restir-spatial-0/-1, gi-trace-spatial-validation-rays,
//                gi-restir-patch-reservoir (spatial.h)
//   resolve      gi-trace-resolve-visibility, gi-restir-resolve (resolve.h)
//   denoise      GiDenoiser::Evolve: gi-temporal-denoise (when enabled), gi-spatial-denoise
//                (desktop preset) (denoise/gi_temporal_denoise.h, denoise/gi_spatial_denoise.h);
//                GiDenoiser::Svgf, Reblur, Hybrid: the library denoiser's passes
//                (denoise/library_denoiser.h)
//
// Resources (frame graph): gi.rays, gi.hit, gi.hit-normal, gi.hit-radiance, gi.nee-ray,
// gi.nee-radiance, gi.nee-visibility, gi.candidate.{sample,radiance,origin,normals},
// gi.candidate-estimate, gi.reservoir-validity, history gi.reservoir.{sample,radiance,origin,
// normals}, gi.reservoir-estimate, gi.spatial-{0,1}.{...}, gi.spatial-{0,1}-estimate,
// gi.validated.sample, gi.validated-estimate, history gi.spatial-occlusion-validity,
// gi.patched.{...}, gi.patched-estimate, gi.resolve-occlusion, gi.resolved, history gi.denoised,
// gi.temporal-denoised. Formats: shared/restir_gi_io.h. Every pass and resource is a debug view
// by name (`bounce render --gi evolve --view ...`; a pass shows its estimate image).
#pragma once
#include <array>
#include <memory>
#include <optional>

#include "denoise/gi_spatial_denoise.h"
#include "denoise/gi_temporal_denoise.h"
#include "denoise/library_denoiser.h"
#include "gi/diffuse_gi.h"
#include "gi/evolve/cache/clipmap_cache.h"
#include "gi/evolve/restir/candidates.h"
#include "gi/evolve/restir/resolve.h"
#include "gi/evolve/restir/restir_gi_pass.h"
#include "gi/evolve/restir/restir_gi_settings.h"
#include "gi/evolve/restir/spatial.h"
#include "gi/evolve/restir/temporal.h"
#include "lighting/gpu_light_tables.h"
#include "shared/restir_gi_io.h"
#include "vk/resources.h"

namespace bounce {

// The chain's constants for `settings` (shared with Lux's chain, src/gi/lux/lux_gi.h, which reuses
// the temporal, spatial and resolve stages): `cache` 0 without the clipmap cache, `blueNoise` the
// direction map or 0, `evolveDenoise` whether gi-temporal-denoise runs.
gpu::RestirGiConstants restirGiConstants(const RestirGiSettings& settings, VkExtent2D giResolution,
                                         VkDeviceAddress lights, VkDeviceAddress cache,
                                         VkDeviceAddress blueNoise, bool evolveDenoise);

class RestirGi final : public DiffuseGi {
 public:
  // `cache`: the clipmap cache's settings, used when settings.secondVertex is Cache;
  // `resolution`: the frame's render resolution.
  RestirGi(vk::Context& context, GpuScene& gpuScene, const Scene& scene,
           const RestirGiSettings& settings, const ClipmapCacheSettings& cache,
           VkExtent2D resolution);
  DiffuseGiOutput declare(graph::FrameGraph& graph, const GiInputs& inputs) override;
  // The clipmap cache (CACHE second vertex) has state outside the frame graph.
  void afterFrame() override;
  std::vector<GiStatistic> statistics() const override;
  void resetHistory() override;
  void lightingCut() override;
  // With RestirGiSecondVertex::Cache; nullptr otherwise.
  const ClipmapCache* clipmapCache() const override { return cache_.get(); }

 private:
  gpu::RestirGiConstants makeConstants() const;
  RestirFrame beginFrame(const GiInputs& inputs);
  // Whether gi-temporal-denoise runs (GiDenoiser::Evolve with temporalDenoise).
  bool evolveDenoise() const;
  void declareDenoise(graph::FrameGraph& graph, const RestirFrame& f, const Candidates& candidates,
                      const ResolvedGi& resolved,
                      const std::optional<graph::HistoryImage>& occlusionValidity,
                      graph::ImageHandle output);

  RestirGiSettings settings_;
  // Frames of settling still to come (RestirGiSettings::settleFrames).
  uint32_t settleFramesLeft_ = 0;
  // Set by lightingCut(), cleared after the next frame (afterFrame): that frame drops the
  // histories whose values hold the old light (reservoirs, candidate mean, denoiser), keeping
  // the geometric ones (the spatial occlusion validity) and the cache (which refreshes instead).
  bool lightCutPending_ = false;
  // The light tables for NEE at the 2nd vertex (and in the cache, which shares them).
  GpuLightTables lights_;
  std::unique_ptr<ClipmapCache> cache_;  // only with RestirGiSecondVertex::Cache
  VkExtent2D giResolution_{};
  vk::Buffer constants_;  // gpu::RestirGiConstants
  vk::Buffer blueNoise_;  // RestirGiConstants::blueNoise
  CandidateStage candidates_;
  TemporalStage temporal_;
  SpatialStage spatial_;
  ResolveStage resolve_;
  // The denoiser's pipelines exist only for the chosen one (issue 21 counts pipelines).
  std::optional<GiTemporalDenoise> temporalDenoise_;  // GiDenoiser::Evolve
  std::optional<GiSpatialDenoise> spatialDenoise_;    // GiDenoiser::Evolve and spatialDenoise
  std::unique_ptr<LibraryDenoiser> libraryDenoiser_;  // GiDenoiser::Svgf, Reblur, Hybrid
};

}  // namespace bounce
