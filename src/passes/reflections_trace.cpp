#include "passes/reflections_trace.h"

#include <cmath>

#include "core/error.h"
#include "lighting/specular_albedo.h"
#include "shared/reflections_reuse_io.h"
#include "shared/restir_gi_io.h"

namespace bounce {

using graph::Access;

void validate(const ReflectionSettings& s) {
  if (s.divisor > 16) fail("reflection divisor {}: expected 0 (off) to 16", s.divisor);
  if (!(s.maxTracedRoughness >= 0.0f && s.maxTracedRoughness <= 1.0f))
    fail("reflection max traced roughness {}: expected 0 to 1", s.maxTracedRoughness);
  if (!(s.mirrorRoughness >= 0.0f && s.mirrorRoughness <= s.maxTracedRoughness))
    fail("reflection mirror roughness {}: expected 0 to the max traced roughness ({})",
         s.mirrorRoughness, s.maxTracedRoughness);
  if (!(s.hitRegularization >= 0.0f && s.hitRegularization <= 16.0f))
    fail("reflection hit regularization {}: expected 0 (none) to 16", s.hitRegularization);
  if (!(s.mirrorDirectionToleranceDegrees >= 0.0f && s.mirrorDirectionToleranceDegrees <= 180.0f))
    fail("reflection mirror direction tolerance {} degrees: expected 0 to 180",
         s.mirrorDirectionToleranceDegrees);
  if (s.materialTextureSide > 16384)
    fail("reflection material texture side {}: expected 0 (full resolution) to 16384",
         s.materialTextureSide);
  if (!(s.reuseMinRoughness >= s.mirrorRoughness && s.reuseMinRoughness <= s.maxTracedRoughness))
    fail(
        "reflection reuse min roughness {}: expected the mirror roughness ({}) to the max traced "
        "roughness ({})",
        s.reuseMinRoughness, s.mirrorRoughness, s.maxTracedRoughness);
  if (!(s.temporalMaxM >= 0.0f && s.temporalMaxM <= 1000.0f))
    fail("reflection temporal max M {}: expected 0 (no temporal reuse) to 1000", s.temporalMaxM);
  if (!(s.motionParallaxTolerance >= 0.0f && s.motionParallaxTolerance <= 1.0f))
    fail("reflection motion parallax tolerance {}: expected 0 (no test) to 1",
         s.motionParallaxTolerance);
  if (s.spatialSamples > gpu::REFLECTION_REUSE_MAX_SPATIAL_SAMPLES)
    fail("reflection spatial samples {}: expected 0 (no spatial reuse) to {}", s.spatialSamples,
         gpu::REFLECTION_REUSE_MAX_SPATIAL_SAMPLES);
  if (!(s.spatialRadius >= 0.0f && s.spatialRadius <= 64.0f))
    fail("reflection spatial radius {}: expected 0 to 64 traced pixels", s.spatialRadius);
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
  c.seed = settings_.seed;
  c.hitRegularization = settings_.hitRegularization;
  c.mirrorDirectionCosine =
      std::cos(settings_.mirrorDirectionToleranceDegrees * float(M_PI) / 180.0f);
  return c;
}

TracedReflections ReflectionsTracePass::declare(graph::FrameGraph& graph, const FrameContext& frame,
                                                const GBuffer& gbuffer,
                                                const RadianceCacheLookup& cache) {
  TracedReflections out;
  const graph::ImageSize size = graph::ImageSize::dividedRes(settings_.divisor);
  out.traced = graph.createImage("reflections.traced", {VK_FORMAT_R16G16B16A16_SFLOAT, size});
  const char* names[4] = {"sample", "radiance", "origin", "normals"};
  for (uint32_t i = 0; i < 4; ++i)
    out.candidate[i] =
        graph.createImage(std::string("reflections.candidate.") + names[i],
                          {i == gpu::GI_RESERVOIR_NORMALS ? VK_FORMAT_R16G16B16A16_SFLOAT
                                                          : VK_FORMAT_R32G32B32A32_SFLOAT,
                           size});
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
      .write(out.traced, Access::StorageWrite, gpu::REFLECTIONS_TRACE_BINDING_TRACED);
  for (uint32_t i = 0; i < 4; ++i)
    pass.write(out.candidate[i], Access::StorageWrite,
               gpu::REFLECTIONS_TRACE_BINDING_CANDIDATE + i);
  pass.record([this, push, extent](VkCommandBuffer cmd, const graph::PassResources& r) {
    pass_.bind(cmd, push, r);
    vk::ComputePipeline::dispatchCovering(cmd, extent.width, extent.height, gpu::HYBRID_GROUP_SIZE,
                                          gpu::HYBRID_GROUP_SIZE);
  });
  return out;
}

}  // namespace bounce
