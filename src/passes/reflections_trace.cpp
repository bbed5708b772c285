#include "passes/reflections_trace.h"

#include <cmath>

#include "core/error.h"
#include "lighting/specular_albedo.h"

namespace bounce {

using graph::Access;

void validate(const ReflectionSettings& s) {
  if (s.divisor > 16) fail("reflection divisor {}: expected 0 (off) to 16", s.divisor);
  if (!(s.maxTracedRoughness >= 0.0f && s.maxTracedRoughness <= 1.0f))
    fail("reflection max traced roughness {}: expected 0 to 1", s.maxTracedRoughness);
  if (!(s.mirrorRoughness >= 0.0f && s.mirrorRoughness <= s.maxTracedRoughness))
    fail("reflection mirror roughness {}: expected 0 to the max traced roughness ({})",
         s.mirrorRoughness, s.maxTracedRoughness);
  if (s.materialTextureSide > 16384)
    fail("reflection material texture side {}: expected 0 (full resolution) to 16384",
         s.materialTextureSide);
}

ReflectionsTracePass::ReflectionsTracePass(vk::Context& context, const GpuScene& gpuScene,
                                           const Scene& scene,
                                           const SpecularAlbedoTable& specularAlbedo,
                                           const ReflectionSettings& settings)
    : settings_(settings),
      specularAlbedo_(specularAlbedo),
      lights_(context, gpuScene, scene),
      pass_(context, gpuScene, "passes/reflections_trace", gpu::REFLECTIONS_TRACE_BINDING_COUNT,
            sizeof(gpu::ReflectionPassConstants)) {}

gpu::ReflectionPassConstants ReflectionsTracePass::constants(const FrameContext& frame,
                                                             VkDeviceAddress cache) const {
  const VkExtent2D traced = settings_.resolution(frame.resolution);
  gpu::ReflectionPassConstants c{};
  c.frame = frame.constantsAddress;
  c.specularAlbedo = specularAlbedo_.address();
  c.lights = lights_.address();
  c.cache = cache;
  c.tracedResolution = {traced.width, traced.height};
  c.divisor = settings_.divisor;
  c.mirrorRoughness = settings_.mirrorRoughness;
  c.maxTracedRoughness = settings_.maxTracedRoughness;
  c.materialTextureSide = settings_.materialTextureSide;
  return c;
}

TracedReflections ReflectionsTracePass::declare(graph::FrameGraph& graph, const FrameContext& frame,
                                                const GBuffer& gbuffer,
                                                const RadianceCacheLookup& cache) {
  TracedReflections out;
  out.traced = graph.createImage(
      "reflections.traced",
      {VK_FORMAT_R16G16B16A16_SFLOAT, graph::ImageSize::dividedRes(settings_.divisor)});
  const gpu::ReflectionPassConstants push = constants(frame, cache.constants);
  const VkExtent2D extent = settings_.resolution(frame.resolution);
  graph::PassBuilder added = graph.addPass("reflections-trace", graph::QueueKind::Compute);
  graph::PassBuilder pass = cache.constants != 0 ? cache.declare(added) : added;
  pass.read(frame.constants, Access::StorageRead)
      .read(frame.instances, Access::StorageRead)
      .read(frame.tlas, Access::StorageRead)
      .read(gbuffer.normals, Access::StorageRead, gpu::REFLECTIONS_TRACE_BINDING_NORMALS)
      .read(gbuffer.depth.current, Access::StorageRead, gpu::REFLECTIONS_TRACE_BINDING_DEPTH)
      .read(gbuffer.emissive, Access::StorageRead, gpu::REFLECTIONS_TRACE_BINDING_EMISSIVE)
      .read(gbuffer.flags, Access::StorageRead, gpu::REFLECTIONS_TRACE_BINDING_FLAGS)
      .write(out.traced, Access::StorageWrite, gpu::REFLECTIONS_TRACE_BINDING_TRACED)
      .record([this, push, extent](VkCommandBuffer cmd, const graph::PassResources& r) {
        pass_.bind(cmd, push, r);
        vk::ComputePipeline::dispatchCovering(cmd, extent.width, extent.height,
                                              gpu::HYBRID_GROUP_SIZE, gpu::HYBRID_GROUP_SIZE);
      });
  return out;
}

}  // namespace bounce
