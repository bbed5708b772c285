// `reflections-trace-mirrors` (docs/reflections.md, "Mirrors at render resolution"): a mirror ray
// of its own for each render pixel below ReflectionSettings::mirrorRoughness whose upsampled
// reflection came from rays that look elsewhere (a curved mirror), written into `reflections`
// after reflections-upsample (shaders/passes/reflections_trace_mirrors.comp). Runs where
// ReflectionSettings::mirrorPassEnabled().
#pragma once
#include "passes/reflections_trace.h"
#include "passes/reflections_upsample.h"

namespace bounce {

class ReflectionsTraceMirrorsPass {
 public:
  ReflectionsTraceMirrorsPass(vk::Context& context, const GpuScene& gpuScene);
  // `constants`: the trace's push constants this frame (ReflectionsTracePass::constants, with
  // the cache's address); `traced`: what reflections-upsample read; `reflections` is
  // overwritten at the mirror pixels that trace.
  void declare(graph::FrameGraph& graph, const FrameContext& frame, const GBuffer& gbuffer,
               const RadianceCacheLookup& cache, const gpu::ReflectionPassConstants& constants,
               const TracedReflections& traced, const Reflections& reflections);

 private:
  ComputePass pass_;
};

}  // namespace bounce
