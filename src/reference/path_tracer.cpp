#include "reference/path_tracer.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "core/error.h"
#include "passes/primary_view.h"
#include "vk/gpu_timer.h"

namespace bounce {

namespace {

using Clock = std::chrono::steady_clock;

constexpr const char* kPassName = "reference-path-trace";
constexpr uint32_t kMaxSamplesPerPixel = 1u << 24;  // sums of more lose float precision
constexpr uint32_t kMaxBounces = 1024;

template <typename T>
vk::Buffer uploadTable(vk::Context& context, const std::vector<T>& items, const char* name) {
  return vk::uploadVector(context, std::span(items), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                          std::string("reference.") + name);
}

void checkOptions(const ReferenceOptions& o) {
  if (o.width < 1 || o.height < 1 || o.width > 16384 || o.height > 16384)
    fail("reference: resolution {}x{} out of range (1..16384)", o.width, o.height);
  if (o.samplesPerPixel < 1 || o.samplesPerPixel > kMaxSamplesPerPixel)
    fail("--spp {}: expected 1..{}", o.samplesPerPixel, kMaxSamplesPerPixel);
  if (o.maxBounces > kMaxBounces)
    fail("--max-bounces {}: expected 0..{}", o.maxBounces, kMaxBounces);
  if (!(o.timeLimitSeconds >= 0.0) || !std::isfinite(o.timeLimitSeconds))
    fail("--time-limit {}: expected seconds >= 0", o.timeLimitSeconds);
  if (!(o.batchSeconds > 0.0)) fail("reference: batch time {} must be positive", o.batchSeconds);
}

// Samples in the next batch: as many as fit in the batch time at the speed measured so far,
// growing at most 4x per batch (the first batch of 1 sample is the measurement), and never past
// the target or, much, past the time limit.
uint32_t nextBatchSize(const ReferenceOptions& o, uint32_t done, uint32_t lastBatch,
                       double secondsPerSample, double elapsed) {
  uint32_t remaining = o.samplesPerPixel - done;
  if (done == 0 || secondsPerSample <= 0.0) return 1;
  double budget = o.batchSeconds;
  if (o.timeLimitSeconds > 0.0)
    budget = std::min(budget, std::max(o.timeLimitSeconds - elapsed, 0.0));
  double fit = std::floor(budget / secondsPerSample);
  uint32_t size = uint32_t(std::clamp(fit, 1.0, 4.0 * double(lastBatch)));
  return std::min(size, remaining);
}

}  // namespace

ReferencePathTracer::ReferencePathTracer(vk::Context& context, const GpuScene& gpuScene,
                                         const Scene& scene)
    : context_(context),
      gpuScene_(gpuScene),
      sky_(scene.sky),
      sun_(scene.sun),
      lights_(buildLightTable(scene, gpuScene.bvh())),
      pipeline_(context, "reference/path_trace", {&gpuScene.setLayout()},
                sizeof(gpu::ReferenceConstants), gpuScene.specialization()) {
  emissiveTriangles_ = uploadTable(context, lights_.emissiveTriangles, "emissive-triangles");
  punctualLights_ = uploadTable(context, lights_.punctualLights, "punctual-lights");
  lightAlias_ = uploadTable(context, lights_.alias, "light-alias");
  distantLights_ = uploadTable(context, lights_.distantLights, "distant-lights");
  materialLightAreaPdf_ = uploadTable(context, lights_.materialLightAreaPdf, "material-light-pdf");
}

gpu::ReferenceSettings ReferencePathTracer::makeSettings(const Camera& camera,
                                                         const ReferenceOptions& options) const {
  gpu::ReferenceSettings s{};
  s.camera = makeGpuCamera(camera, options.width, options.height, gpuScene_.bounds());
  s.lights.emissiveTriangles = emissiveTriangles_.address();
  s.lights.punctualLights = punctualLights_.address();
  s.lights.lightAlias = lightAlias_.address();
  s.lights.distantLights = distantLights_.address();
  s.lights.materialLightAreaPdf = materialLightAreaPdf_.address();
  s.resolution = {options.width, options.height};
  s.maxBounces = options.maxBounces;
  s.seed = options.seed;
  s.flags = (options.lambert ? gpu::REFERENCE_FLAG_LAMBERT : 0u) |
            (options.pixelCentre ? gpu::REFERENCE_FLAG_PIXEL_CENTRE : 0u);
  s.lights.emissiveTriangleCount = uint32_t(lights_.emissiveTriangles.size());
  s.lights.localLightCount = lights_.localLightCount();
  s.lights.distantLightCount = uint32_t(lights_.distantLights.size());
  s.skyRadiance = sky_.radiance;
  s.skyModel =
      sky_.model == SkyModel::Daylight ? gpu::REFERENCE_SKY_DAYLIGHT : gpu::REFERENCE_SKY_CONSTANT;
  s.skyTowardSun = -glm::normalize(sun_.direction);
  s.skyTurbidity = sky_.turbidity;
  s.skyScale = daylightSkyScale(sun_);
  return s;
}

ReferenceResult ReferencePathTracer::render(const Camera& camera, const ReferenceOptions& options) {
  checkOptions(options);
  const size_t pixels = size_t(options.width) * options.height;
  // Every buffer of the run is made here, before the sample loop.
  std::vector<glm::vec4> zeros(pixels, glm::vec4(0.0f));
  vk::Buffer accumulation =
      vk::uploadVector(context_, std::span<const glm::vec4>(zeros),
                       VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                       "reference.accumulation");
  std::vector<uint32_t> counterValues(gpu::REFERENCE_COUNTER_COUNT, 0u);
  vk::Buffer counters = vk::uploadVector(
      context_, std::span<const uint32_t>(counterValues),
      VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT, "reference.counters");
  gpu::ReferenceSettings settings = makeSettings(camera, options);
  settings.accumulation = accumulation.address();
  settings.counters = counters.address();
  vk::Buffer settingsBuffer =
      vk::uploadBuffer(context_, std::as_bytes(std::span(&settings, 1)),
                       VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "reference.settings");
  vk::GpuTimer timer(context_, 2);

  ReferenceResult result;
  const auto start = Clock::now();
  double secondsPerSample = 0.0;
  uint32_t batch = 0;
  while (result.samplesPerPixel < options.samplesPerPixel) {
    double elapsed = std::chrono::duration<double>(Clock::now() - start).count();
    batch = nextBatchSize(options, result.samplesPerPixel, batch, secondsPerSample, elapsed);
    gpu::ReferenceConstants pc{settingsBuffer.address(), result.samplesPerPixel, batch};
    const auto batchStart = Clock::now();
    context_.submitAndWait([&](VkCommandBuffer cmd) {
      vk::computeBarrier(cmd);  // after the uploads and the previous batch
      if (timer.available()) {
        timer.reset(cmd);
        timer.begin(cmd, kPassName);
      }
      pipeline_.bind(cmd, {gpuScene_.descriptorSet()});
      pipeline_.push(cmd, pc);
      vk::ComputePipeline::dispatchCovering(cmd, options.width, options.height,
                                            gpu::REFERENCE_GROUP_SIZE, gpu::REFERENCE_GROUP_SIZE);
      if (timer.available()) timer.end(cmd);
    });
    const double batchSeconds = std::chrono::duration<double>(Clock::now() - batchStart).count();
    secondsPerSample = batchSeconds / double(batch);
    if (timer.available()) result.gpuMilliseconds += timer.read().at(0).milliseconds;
    result.samplesPerPixel += batch;
    ++result.batches;
    result.seconds = std::chrono::duration<double>(Clock::now() - start).count();
    if (options.onProgress)
      options.onProgress({result.samplesPerPixel, options.samplesPerPixel, result.seconds,
                          options.timeLimitSeconds});
    if (options.cancel && options.cancel->load() &&
        result.samplesPerPixel < options.samplesPerPixel) {
      result.cancelled = true;
      break;
    }
    if (options.timeLimitSeconds > 0.0 && result.seconds >= options.timeLimitSeconds &&
        result.samplesPerPixel < options.samplesPerPixel) {
      result.stoppedByTimeLimit = true;
      break;
    }
  }

  std::vector<glm::vec4> sums(pixels);
  vk::downloadBuffer(context_, accumulation, std::as_writable_bytes(std::span(sums)));
  vk::downloadBuffer(context_, counters, std::as_writable_bytes(std::span(counterValues)));
  result.droppedSamples = counterValues[gpu::REFERENCE_COUNTER_NON_FINITE];
  result.image = ImageRGBA32F(int(options.width), int(options.height));
  const float scale = 1.0f / float(result.samplesPerPixel);
  for (size_t i = 0; i < pixels; ++i) {
    glm::vec3 mean = glm::vec3(sums[i]) * scale;
    result.image.set(int(i % options.width), int(i / options.width), glm::vec4(mean, 1.0f));
  }
  return result;
}

}  // namespace bounce
