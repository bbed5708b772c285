#include "passes/reflections_reuse.h"

#include "lighting/specular_albedo.h"

namespace bounce {

ReflectionsReuse::ReflectionsReuse(vk::Context& context, const GpuScene& gpuScene,
                                   const SpecularAlbedoTable& specularAlbedo,
                                   const ReflectionSettings& settings)
    : settings_(settings),
      specularAlbedo_(specularAlbedo),
      temporal_(context, gpuScene),
      spatial_(context, gpuScene),
      resolve_(context, gpuScene) {}

gpu::ReflectionReuseConstants ReflectionsReuse::constants(const FrameContext& frame) const {
  const VkExtent2D traced = settings_.resolution(frame.resolution);
  gpu::ReflectionReuseConstants c{};
  c.frame = frame.constantsAddress;
  c.specularAlbedo = specularAlbedo_.address();
  c.tracedResolution = {traced.width, traced.height};
  c.divisor = settings_.divisor;
  c.historyValid = 0;  // reflections-temporal sets it from its history
  c.reuseMinRoughness = settings_.reuseMinRoughness;
  c.maxTracedRoughness = settings_.maxTracedRoughness;
  c.temporalMaxM = settings_.temporalMaxM;
  c.spatialRadius = settings_.spatialRadius;
  c.spatialSamples = settings_.spatialSamples;
  c.seed = settings_.seed;
  c.motionParallaxTolerance = settings_.motionParallaxTolerance;
  return c;
}

TracedReflections ReflectionsReuse::declare(graph::FrameGraph& graph, const FrameContext& frame,
                                            const GBuffer& gbuffer,
                                            const TracedReflections& traced) {
  const ReflectionReuseFrame f{constants(frame), graph::ImageSize::dividedRes(settings_.divisor),
                               settings_.resolution(frame.resolution)};
  ReflectionReservoirImages temporal =
      temporal_.declare(graph, frame, gbuffer, traced.candidate, f);
  ReflectionReservoirImages spatial = spatial_.declare(graph, frame, gbuffer, temporal, f);
  TracedReflections out = traced;
  out.traced = resolve_.declare(graph, frame, gbuffer, spatial, traced.traced, f);
  return out;
}

}  // namespace bounce
