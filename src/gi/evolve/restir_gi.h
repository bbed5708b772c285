// Evolve's ReSTIR GI chain (seed 000; DESIGN.md §4 step 5; issue 6): `--gi evolve`.
//
//   (cache-*)                  the clipmap cache's update (ClipmapCache::declareUpdate), when the
//                              2nd vertex continues into the cache (RestirGiSecondVertex::Cache)
//   gi-prepare-diffuse-rays    a uniform hemisphere direction per GI pixel (blue noise); every
//                              3rd frame a validation ray along the history reservoir's sample
//   gi-trace-diffuse-rays      closest hit; sky on a miss; emission, NEE set-up, the cache lookup
//                              (Cache) or a continued path (Path) at the 2nd vertex
//   gi-trace-diffuse-nee-rays  visibility of the NEE rays
//   gi-resolve-diffuse-rays    candidate reservoirs (one sample, W = 2 pi, M = 1), or on
//                              validation rays the checked history reservoir; reservoir validity
//   gi-restir-temporal         sub-pixel-aware reprojection + up to 5 history reservoirs
//                              (permutation sampling); the only reservoir fed back (history)
//   gi-restir-spatial-0/-1     spatial reuse, 8 samples / large radius then 5 / small radius
//   gi-trace-spatial-validation-rays  visibility of reused samples (W = 0 when occluded); the
//                              spatial occlusion validity mask (history)
//   gi-restir-patch-reservoir  rejected reservoirs take the first valid one of their 2x2 patch
//   gi-trace-resolve-visibility  pixels beside an occluder: which of the resolve's samples
//                              they cannot see (shadow rays), and no spatial denoise there
//   gi-restir-resolve          reservoirs -> L1 SH -> gi.diffuse at render resolution
//   gi-temporal-denoise        running mean with variance clipping (when enabled)
//   gi-spatial-denoise         edge-aware blur (desktop preset)
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

#include "gi/diffuse_gi.h"
#include "gi/evolve/clipmap_cache.h"
#include "gi/evolve/restir_gi_pass.h"
#include "gi/evolve/restir_gi_settings.h"
#include "lighting/gpu_light_tables.h"
#include "shared/restir_gi_io.h"
#include "vk/resources.h"

namespace bounce {

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

 private:
  using ReservoirImages = std::array<graph::ImageHandle, 4>;  // sample, radiance, origin, normals
  gpu::RestirGiPassConstants passConstants(const GiInputs& inputs, bool historyValid,
                                           uint32_t variant = 0) const;
  void declareReservoirPass(graph::FrameGraph& graph, const GiInputs& in, const char* name,
                            RestirGiPass& pass, uint32_t variant, const ReservoirImages& input,
                            const ReservoirImages& output, graph::ImageHandle estimate);
  ReservoirImages declareSpatialChain(graph::FrameGraph& graph, const GiInputs& in,
                                      const ReservoirImages& temporal,
                                      const std::optional<graph::HistoryImage>& occlusionValidity);

  RestirGiSettings settings_;
  // Frames of settling still to come (RestirGiSettings::settleFrames) and this frame's scale
  // of the temporal histories (RestirGiPassConstants::historyScale).
  uint32_t settleFramesLeft_ = 0;
  float historyScale_ = 1.0f;
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
  RestirGiPass prepare_, trace_, traceNee_, candidates_, temporal_, spatial0_, spatial1_,
      spatialValidation_, patch_, resolveVisibility_, resolve_, spatialDenoise_, denoise_;
};

}  // namespace bounce
