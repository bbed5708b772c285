#include "gi/diffuse_gi.h"

#include "gi/evolve/cache_gi.h"
#include "gi/evolve/restir_gi.h"

namespace bounce {

std::unique_ptr<DiffuseGi> makeDiffuseGi(vk::Context& context, GpuScene& gpuScene,
                                         const Scene& scene, const HybridSettings& settings) {
  switch (settings.gi) {
    case GiMode::None:
      return nullptr;
    case GiMode::Evolve:
      return std::make_unique<RestirGi>(context, gpuScene, scene, settings);
    case GiMode::Cache:
      return std::make_unique<CacheGi>(context, gpuScene, scene, settings);
  }
  return nullptr;
}

}  // namespace bounce
