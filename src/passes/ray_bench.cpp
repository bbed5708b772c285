#include "passes/ray_bench.h"

#include <algorithm>
#include <cmath>

#include "passes/primary_view.h"
#include "shared/bench_rays_io.h"
#include "vk/gpu_timer.h"
#include "vk/pipeline.h"

namespace bounce {

namespace {

const char* kKindNames[] = {"primary", "shadow", "diffuse"};

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  return values.empty() ? 0.0 : values[values.size() / 2];
}

// Fraction of traced rays whose result is 1 (hit / occluded); 2 marks pixels with no ray.
double hitFraction(const std::vector<uint32_t>& results, uint64_t* traced) {
  uint64_t hits = 0, count = 0;
  for (uint32_t r : results) {
    if (r == 2u) continue;
    ++count;
    hits += r;
  }
  *traced = count;
  return count ? double(hits) / double(count) : 0.0;
}

}  // namespace

std::vector<RayKindResult> runRayBench(vk::Context& context, const GpuScene& gpuScene,
                                       const Scene& scene, const RayBenchOptions& options) {
  const uint32_t w = options.resolution.width, h = options.resolution.height;
  const uint64_t pixels = uint64_t(w) * h;
  vk::ComputePipeline pipeline(context, "rt/bench_rays", {&gpuScene.setLayout()},
                               sizeof(gpu::BenchRaysConstants));
  vk::Buffer surfaces(context, pixels * sizeof(gpu::BenchSurface),
                      VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUse::DeviceOnly,
                      "bench-rays.surfaces");
  std::vector<vk::Buffer> results;
  for (int k = 0; k < 3; ++k)
    results.emplace_back(context, pixels * sizeof(uint32_t),
                         VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                         vk::MemoryUse::DeviceOnly, std::string("bench-rays.") + kKindNames[k]);
  vk::GpuTimer timer(context);

  gpu::BenchRaysConstants pc{};
  pc.camera = makeGpuCamera(effectiveCamera(scene), w, h, gpuScene.bounds());
  pc.surfaces = surfaces.address();
  pc.resolution = {w, h};
  glm::vec3 sunDir =
      scene.sun.irradiance > 0.0f ? scene.sun.direction : glm::vec3(-0.3f, -1.0f, -0.2f);
  pc.toSun = -glm::normalize(sunDir);
  pc.sunCosHalfAngle = std::cos(glm::radians(scene.sun.angularDiameterDegrees * 0.5f));

  std::vector<std::vector<double>> times(3);
  for (uint32_t it = 0; it < options.iterations; ++it) {
    pc.frame = it;
    context.submitAndWait([&](VkCommandBuffer cmd) {
      timer.reset(cmd);
      pipeline.bind(cmd, {gpuScene.descriptorSet()});
      for (uint32_t mode = 0; mode < 3; ++mode) {
        pc.mode = mode;
        pc.results = results[mode].address();
        pipeline.push(cmd, pc);
        timer.begin(cmd, kKindNames[mode]);
        vk::ComputePipeline::dispatchCovering(cmd, w, h, gpu::BENCH_RAYS_GROUP_SIZE,
                                              gpu::BENCH_RAYS_GROUP_SIZE);
        timer.end(cmd);
        vk::computeBarrier(cmd);
      }
    });
    std::vector<vk::PassTiming> t = timer.read();
    for (size_t k = 0; k < t.size(); ++k) times[k].push_back(t[k].milliseconds);
  }

  std::vector<RayKindResult> out;
  for (uint32_t k = 0; k < 3; ++k) {
    std::vector<uint32_t> r(pixels);
    vk::downloadBuffer(context, results[k], std::as_writable_bytes(std::span(r)));
    RayKindResult kind;
    kind.kind = kKindNames[k];
    kind.hitFraction = hitFraction(r, &kind.rays);
    kind.medianMilliseconds = median(times[k]);
    kind.minMilliseconds =
        times[k].empty() ? 0.0 : *std::min_element(times[k].begin(), times[k].end());
    kind.mraysPerSecond =
        kind.medianMilliseconds > 0.0 ? double(kind.rays) / (kind.medianMilliseconds * 1e3) : 0.0;
    out.push_back(kind);
  }
  return out;
}

}  // namespace bounce
