#include "gi/diffuse_gi.h"

namespace bounce {

std::unique_ptr<DiffuseGi> makeDiffuseGi(vk::Context& /*context*/, GpuScene& /*gpuScene*/,
                                         const Scene& /*scene*/, const HybridSettings& settings) {
  switch (settings.gi) {
    case GiMode::None:
      return nullptr;
  }
  return nullptr;
}

}  // namespace bounce
