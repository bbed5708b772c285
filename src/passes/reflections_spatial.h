// `reflections-spatial` (reflections_reuse.h; shaders/passes/reflections_spatial.comp): each
// traced pixel's reservoir merged with ReflectionSettings::spatialSamples neighbours' within
// spatialRadius x roughness traced pixels, 1/Z normalised, no visibility test. Writes
// reflections.spatial.* (this frame only: not fed back).
#pragma once
#include "passes/reflections_temporal.h"

namespace bounce {

class ReflectionsSpatialPass {
 public:
  ReflectionsSpatialPass(vk::Context& context, const GpuScene& gpuScene);
  ReflectionReservoirImages declare(graph::FrameGraph& graph, const FrameContext& frame,
                                    const GBuffer& gbuffer, const ReflectionReservoirImages& input,
                                    const ReflectionReuseFrame& f);

 private:
  ComputePass pass_;
};

}  // namespace bounce
