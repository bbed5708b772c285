// The ray-tracing benchmark behind `bounce bench-rays`: Mrays/s of primary, sun-shadow and
// diffuse-bounce rays through the software BVH, timed with GPU timestamps.
#pragma once
#include <string>
#include <vector>

#include "rt/gpu_scene.h"
#include "scene/scene.h"
#include "scene/scene_options.h"
#include "vk/context.h"

namespace bounce {

struct RayKindResult {
  std::string kind;   // "primary", "shadow", "diffuse"
  uint64_t rays = 0;  // per dispatch
  double medianMilliseconds = 0.0;
  double minMilliseconds = 0.0;
  double mraysPerSecond = 0.0;  // from the median
  double hitFraction = 0.0;     // of the rays traced (shadow: fraction occluded)
};

struct RayBenchOptions {
  Resolution resolution{1920, 1080};
  uint32_t iterations = 9;
};

std::vector<RayKindResult> runRayBench(vk::Context& context, const GpuScene& gpuScene,
                                       const Scene& scene, const RayBenchOptions& options);

}  // namespace bounce
