// Pass "trace-rays": traces a batch of rays given on the CPU through the GPU traversal and
// returns closest hits and visibility answers. Checks the GPU tracer against the CPU one.
#pragma once
#include <span>
#include <vector>

#include "rt/gpu_scene.h"
#include "shared/trace_io.h"
#include "vk/pipeline.h"

namespace bounce {

class TraceRaysPass {
 public:
  TraceRaysPass(vk::Context& context, const GpuScene& scene);
  std::vector<gpu::GpuHit> trace(std::span<const gpu::GpuRay> rays, bool alphaTest);

 private:
  vk::Context& context_;
  const GpuScene& scene_;
  vk::ComputePipeline pipeline_;
};

}  // namespace bounce
