// `reflections-upsample`: reflections.traced to render resolution with a joint bilateral
// upsample that keeps to each pixel's surface and normal
// (shaders/passes/reflections_upsample.comp), writing `reflections`, which composite reads. Stands
// where `reflections-denoise` will (DESIGN.md §4 step 6): temporal reuse and filtering come with
// it.
#pragma once
#include "passes/reflections_trace.h"

namespace bounce {

struct Reflections {
  graph::ImageHandle radiance;  // reflections: rgba16f, the demodulated signal; w = 1 where set
};

class ReflectionsUpsamplePass {
 public:
  ReflectionsUpsamplePass(vk::Context& context, const GpuScene& gpuScene);
  // `constants`: the trace's push constants this frame (ReflectionsTracePass::constants).
  Reflections declare(graph::FrameGraph& graph, const FrameContext& frame, const GBuffer& gbuffer,
                      const TracedReflections& traced,
                      const gpu::ReflectionPassConstants& constants);

 private:
  ComputePass pass_;
};

}  // namespace bounce
