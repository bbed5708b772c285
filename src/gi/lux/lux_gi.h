// Lux's ReSTIR indirect (seed 002; `--gi lux`; gi10_lux_denoisers.md §2.3(c)): ReSTIR over a
// probe field, candidates drawn by cosine sampling and resampled with the probe field's radiance
// as the target. Docs: docs/gi/lux.md. By stage:
//
//   (cache-*)                  the probe field: Evolve's clipmap cache (32^3 cells per cascade,
//                              L1 SH of incoming radiance per cell), ClipmapCache::declareUpdate
//   lux-candidates             M cosine candidates, RIS with p_hat = probe radiance x cos: one
//                              direction and its W per GI pixel (no rays)
//   gi-trace-diffuse-rays,     the one ray per final candidate, its hit's shading and its NEE
//   gi-shade-diffuse-hits,     shadow ray (ReSTIR GI's, cache 2nd vertex: the probe field at
//   gi-trace-diffuse-nee-rays  the hit)
//   lux-resolve-candidates     candidate reservoirs (M = 1, W from RIS)
//   lux-probe-integral         test support: plain MC of the same integrand (integralSamples)
//   temporal, spatial, resolve ReSTIR GI's stages (src/gi/evolve/restir/): reuse with the
//                              reconnection Jacobian, a visibility ray per resolved sample
//   svgf-*                     SVGF (LuxSettings::svgf)
#pragma once
#include <memory>
#include <optional>

#include "denoise/svgf.h"
#include "gi/diffuse_gi.h"
#include "gi/evolve/cache/clipmap_cache.h"
#include "gi/evolve/restir/candidates.h"
#include "gi/evolve/restir/resolve.h"
#include "gi/evolve/restir/restir_gi_settings.h"
#include "gi/evolve/restir/spatial.h"
#include "gi/evolve/restir/temporal.h"
#include "gi/lux/lux_settings.h"
#include "lighting/gpu_light_tables.h"
#include "shared/lux_io.h"
#include "vk/resources.h"

namespace bounce {

class LuxGi final : public DiffuseGi {
 public:
  // `reuse`: the ReSTIR GI settings of the preset, whose temporal, spatial and resolve settings
  // Lux's reuse takes (its own candidates replace Evolve's: no validation rays, the cache at the
  // 2nd vertex, LuxSettings' denoiser); `cache`: the probe field's; `resolution`: render
  // resolution.
  LuxGi(vk::Context& context, GpuScene& gpuScene, const Scene& scene, const LuxSettings& settings,
        const RestirGiSettings& reuse, const ClipmapCacheSettings& cache, VkExtent2D resolution);

  DiffuseGiOutput declare(graph::FrameGraph& graph, const GiInputs& inputs) override;
  void afterFrame() override;
  std::vector<GiStatistic> statistics() const override { return cache_.statistics(); }
  void resetHistory() override;
  void lightingCut() override;
  const ClipmapCache* clipmapCache() const override { return &cache_; }

  // The ReSTIR GI settings Lux runs its reuse with (from `reuse`, see the constructor).
  static RestirGiSettings reuseSettings(RestirGiSettings reuse, const LuxSettings& lux);

 private:
  struct Rays {
    graph::ImageHandle rays, weight;
  };
  gpu::LuxPassConstants passConstants(const RestirFrame& f) const;
  RestirFrame beginFrame(const GiInputs& inputs);
  Rays declareCandidates(graph::FrameGraph& graph, const RestirFrame& f);
  Candidates declareResolveCandidates(graph::FrameGraph& graph, const RestirFrame& f,
                                      const Rays& rays, const GiHits& hits);
  void declareProbeIntegral(graph::FrameGraph& graph, const RestirFrame& f);

  LuxSettings settings_;
  RestirGiSettings reuse_;
  GpuLightTables lights_;  // before cache_, which refers to them
  ClipmapCache cache_;
  VkExtent2D giResolution_{};
  vk::Buffer constants_;  // gpu::RestirGiConstants
  bool lightCutPending_ = false;
  // Frames of settling still to come (RestirGiSettings::settleFrames, as RestirGi does): after a
  // reset or a lighting cut the probe field is still filling, so the reservoirs keep a short
  // history (settleHistoryScale) and SVGF none, or the dark samples of those frames linger.
  uint32_t settleFramesLeft_ = 0;
  ComputePass candidates_, resolveCandidates_, integral_;
  GiTracePasses trace_;  // the trace of Evolve's candidates (gi/evolve/restir/candidates.h)
  TemporalStage temporal_;
  SpatialStage spatial_;
  ResolveStage resolve_;
  std::unique_ptr<Svgf> svgf_;
};

}  // namespace bounce
