// `--gi cache`: Evolve's clipmap irradiance cache alone as the frame's diffuse GI, so
// the cache can be seen and measured before ReSTIR GI uses it. After the cache's own passes,
// `gi-cache-lookup` writes gi.diffuse = irradiance / pi at each pixel's surface point (the mean
// of four jittered lookups); composite multiplies it by the albedo. Multi-bounce light comes
// from the cache's recursive lookups.
#pragma once
#include "gi/diffuse_gi.h"
#include "gi/evolve/cache/clipmap_cache.h"

namespace bounce {

class CacheGi final : public DiffuseGi {
 public:
  CacheGi(vk::Context& context, GpuScene& gpuScene, const Scene& scene,
          const ClipmapCacheSettings& settings);

  DiffuseGiOutput declare(graph::FrameGraph& graph, const GiInputs& inputs) override;
  void afterFrame() override { cache_.afterFrame(); }
  std::vector<GiStatistic> statistics() const override { return cache_.statistics(); }
  void resetHistory() override { cache_.resetHistory(); }
  void lightingCut() override { cache_.beginFullRefresh(); }

  ClipmapCache& cache() { return cache_; }
  const ClipmapCache* clipmapCache() const override { return &cache_; }

 private:
  GpuLightTables lights_;  // before cache_, which refers to them
  ClipmapCache cache_;
  ComputePass lookup_;
};

}  // namespace bounce
