// `reference`: the ground-truth renderer (DESIGN.md §6). A progressive path tracer on the GPU
// (pass "reference-path-trace", shaders/reference/) over exactly the scene the real-time
// pipeline sees: the same BVH, glTF metallic-roughness materials and textures, alpha cut-outs,
// one-sided emissive triangles, KHR point/spot/directional lights, the sun and the sky.
// Progressive: samples are added to a running sum in batches sized to keep each GPU submission
// short, so a time limit can stop it between batches.
#pragma once
#include <atomic>
#include <cstdint>
#include <functional>

#include "lighting/light_table.h"
#include "rt/gpu_scene.h"
#include "scene/scene.h"
#include "shared/reference_io.h"
#include "tools/image_io.h"
#include "vk/pipeline.h"

namespace bounce {

struct ReferenceProgress {
  uint32_t samplesDone = 0;
  uint32_t samplesTarget = 0;     // --spp
  double seconds = 0.0;           // since the first batch started
  double timeLimitSeconds = 0.0;  // 0 = none
};

struct ReferenceOptions {
  uint32_t width = 0;
  uint32_t height = 0;
  uint32_t samplesPerPixel = 64;  // at least 1
  // Scattering events per path: 1 = direct lighting only (camera -> surface -> light), 0 = only
  // what the camera sees directly (emitters, sky). Russian roulette ends most paths far earlier.
  uint32_t maxBounces = 16;
  uint32_t seed = 1;     // same seed, same device: the same image, bit for bit
  bool lambert = false;  // every material pure Lambert with its base colour (textures, emission
                         // and alpha kept): the mode for comparisons with other renderers
  // Camera rays through pixel centres only, no anti-aliasing: the mode for comparing with the
  // real-time frame, which takes one sample at each pixel centre.
  bool pixelCentre = false;
  // Stop after the batch during which this many seconds have passed (0 = no limit); the result
  // then has fewer samples than samplesPerPixel.
  double timeLimitSeconds = 0.0;
  // Wall time a batch (one GPU submission) aims at: short enough for progress, time limits and
  // GPU watchdogs (~2 s), long enough to amortise submission overhead.
  double batchSeconds = 0.25;
  std::function<void(const ReferenceProgress&)> onProgress;  // after every batch; may be empty
  // Checked after every batch: once true, the render stops and returns what it has (at least
  // one batch). Set from another thread or a signal handler (a lock-free atomic store is
  // async-signal-safe), e.g. by `bounce reference` on Ctrl-C.
  const std::atomic<bool>* cancel = nullptr;
};

struct ReferenceResult {
  ImageRGBA32F image;  // linear scene-referred radiance, alpha 1
  uint32_t samplesPerPixel = 0;
  uint32_t batches = 0;
  double seconds = 0.0;          // wall time of the sampling loop
  double gpuMilliseconds = 0.0;  // sum of the pass's GPU timestamps (0 without timestamps)
  uint64_t droppedSamples = 0;   // NaN/infinite samples left out of the sums (should be 0)
  bool stoppedByTimeLimit = false;
  bool cancelled = false;  // stopped early through ReferenceOptions::cancel
};

class ReferencePathTracer {
 public:
  // Gathers the scene's lights; `scene` must be the one `gpuScene` was built from.
  ReferencePathTracer(vk::Context& context, const GpuScene& gpuScene, const Scene& scene);

  // Renders `camera`'s view. Throws bounce::Error for options out of range.
  ReferenceResult render(const Camera& camera, const ReferenceOptions& options);

  const LightTable& lights() const { return lights_; }

 private:
  gpu::ReferenceSettings makeSettings(const Camera& camera, const ReferenceOptions& options) const;

  vk::Context& context_;
  const GpuScene& gpuScene_;
  Sky sky_;
  Sun sun_;
  LightTable lights_;
  vk::Buffer emissiveTriangles_, punctualLights_, lightAlias_, distantLights_,
      materialLightAreaPdf_;
  vk::ComputePipeline pipeline_;
};

}  // namespace bounce
