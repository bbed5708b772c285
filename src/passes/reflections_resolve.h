// `reflections-resolve` (reflections_reuse.h; shaders/passes/reflections_resolve.comp): each
// traced pixel's reused reservoir as the demodulated reflection signal, reflections.resolved,
// in reflections.traced's format and meaning (shared/specular_io.h); pixels without reuse copy
// reflections.traced bit for bit.
#pragma once
#include "passes/reflections_temporal.h"

namespace bounce {

class ReflectionsResolvePass {
 public:
  ReflectionsResolvePass(vk::Context& context, const GpuScene& gpuScene);
  // Returns reflections.resolved.
  graph::ImageHandle declare(graph::FrameGraph& graph, const FrameContext& frame,
                             const GBuffer& gbuffer, const ReflectionReservoirImages& reservoir,
                             graph::ImageHandle traced, const ReflectionReuseFrame& f);

 private:
  ComputePass pass_;
};

}  // namespace bounce
