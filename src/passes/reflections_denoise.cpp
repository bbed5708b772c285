#include "passes/reflections_denoise.h"

#include <cmath>

#include "core/error.h"
#include "shared/restir_gi_io.h"

namespace bounce {

using graph::Access;

void validate(const ReflectionDenoiseSettings& s) {
  auto within = [](float v, float lo, float hi) { return v >= lo && v <= hi; };  // false for NaN
  if (!within(s.mirrorHistoryFrames, 1.0f, 256.0f))
    fail("reflection denoise mirror history frames {}: expected 1 to 256", s.mirrorHistoryFrames);
  if (!within(s.glossyHistoryFrames, s.mirrorHistoryFrames, 256.0f))
    fail("reflection denoise glossy history frames {}: expected the mirror history ({}) to 256",
         s.glossyHistoryFrames, s.mirrorHistoryFrames);
  if (!(s.glossyHistoryRoughness > 0.0f && s.glossyHistoryRoughness <= 1.0f))
    fail("reflection denoise glossy history roughness {}: expected above 0, at most 1",
         s.glossyHistoryRoughness);
  if (!within(s.virtualRoughnessLimit, 0.0f, 1.0f))
    fail("reflection denoise virtual roughness limit {}: expected 0 to 1", s.virtualRoughnessLimit);
  if (!(s.planeTolerance > 0.0f && std::isfinite(s.planeTolerance)))
    fail("reflection denoise plane tolerance {}: expected a fraction of view depth above 0",
         s.planeTolerance);
  if (!(s.normalToleranceDegrees > 0.0f && s.normalToleranceDegrees <= 180.0f))
    fail("reflection denoise normal tolerance {} degrees: expected above 0, at most 180",
         s.normalToleranceDegrees);
  if (!(s.mirrorNormalToleranceDegrees > 0.0f &&
        s.mirrorNormalToleranceDegrees <= s.normalToleranceDegrees))
    fail(
        "reflection denoise mirror normal tolerance {} degrees: expected above 0, at most the "
        "normal tolerance ({})",
        s.mirrorNormalToleranceDegrees, s.normalToleranceDegrees);
  if (!(s.roughnessTolerance > 0.0f && std::isfinite(s.roughnessTolerance)))
    fail("reflection denoise roughness tolerance {}: expected above 0", s.roughnessTolerance);
  if (!(s.ghostSigma >= 0.0f && std::isfinite(s.ghostSigma)))
    fail("reflection denoise ghost sigma {}: expected 0 (never cut) or more", s.ghostSigma);
  if (!within(s.responsiveFrames, 1.0f, s.mirrorHistoryFrames))
    fail("reflection denoise responsive frames {}: expected 1 to the mirror history ({})",
         s.responsiveFrames, s.mirrorHistoryFrames);
  if (!within(s.fastHistoryFrames, 1.0f, s.mirrorHistoryFrames))
    fail("reflection denoise fast history frames {}: expected 1 to the mirror history ({})",
         s.fastHistoryFrames, s.mirrorHistoryFrames);
  if (!(s.motionParallaxTolerance >= 0.0f && s.motionParallaxTolerance <= 1.0f))
    fail("reflection denoise motion parallax tolerance {}: expected 0 (no test) to 1",
         s.motionParallaxTolerance);
  if (!(s.lagSigma >= 0.0f && std::isfinite(s.lagSigma)))
    fail("reflection denoise lag sigma {}: expected 0 (never) or more", s.lagSigma);
  if (!within(s.spatialMaxRadius, 0.0f, 16.0f))
    fail("reflection denoise spatial max radius {}: expected 0 (off) to 16 traced pixels",
         s.spatialMaxRadius);
  if (!within(s.spatialFootprintScale, 0.0f, 4.0f))
    fail("reflection denoise spatial footprint scale {}: expected 0 to 4", s.spatialFootprintScale);
}

// reflections-denoise-temporal's inputs are sampled images (texelFetch: faster than a storage
// image's imageLoad on an H100; docs/architecture.md, "Sampled inputs").
constexpr uint64_t kTemporalSampled =
    bindingMask({gpu::REFLECTIONS_DENOISE_TEMPORAL_BINDING_TRACED,
                 gpu::REFLECTIONS_DENOISE_TEMPORAL_BINDING_NORMALS,
                 gpu::REFLECTIONS_DENOISE_TEMPORAL_BINDING_DEPTH,
                 gpu::REFLECTIONS_DENOISE_TEMPORAL_BINDING_EMISSIVE,
                 gpu::REFLECTIONS_DENOISE_TEMPORAL_BINDING_FLAGS,
                 gpu::REFLECTIONS_DENOISE_TEMPORAL_BINDING_VELOCITY,
                 gpu::REFLECTIONS_DENOISE_TEMPORAL_BINDING_PREVIOUS,
                 gpu::REFLECTIONS_DENOISE_TEMPORAL_BINDING_PREVIOUS_MOMENTS,
                 gpu::REFLECTIONS_DENOISE_TEMPORAL_BINDING_PREVIOUS_SURFACE,
                 gpu::REFLECTIONS_DENOISE_TEMPORAL_BINDING_PREVIOUS_FAST,
                 gpu::REFLECTIONS_DENOISE_TEMPORAL_BINDING_CANDIDATE_SAMPLE,
                 gpu::REFLECTIONS_DENOISE_TEMPORAL_BINDING_CANDIDATE_ORIGIN});

ReflectionsDenoisePass::ReflectionsDenoisePass(vk::Context& context, const GpuScene& gpuScene,
                                               const ReflectionDenoiseSettings& settings)
    : settings_(settings),
      temporal_(context, gpuScene, "passes/reflections_denoise_temporal",
                gpu::REFLECTIONS_DENOISE_TEMPORAL_BINDING_COUNT,
                sizeof(gpu::ReflectionDenoiseConstants), 1, {}, kTemporalSampled),
      spatial_(context, gpuScene, "passes/reflections_denoise_spatial",
               gpu::REFLECTIONS_DENOISE_SPATIAL_BINDING_COUNT,
               sizeof(gpu::ReflectionDenoiseConstants)) {}

gpu::ReflectionDenoiseConstants ReflectionsDenoisePass::constants(
    const gpu::ReflectionPassConstants& trace) const {
  const ReflectionDenoiseSettings& s = settings_;
  gpu::ReflectionDenoiseConstants c{};
  c.frame = trace.frame;
  c.tracedResolution = trace.tracedResolution;
  c.divisor = trace.divisor;
  c.maxTracedRoughness = trace.maxTracedRoughness;
  c.mirrorHistoryFrames = s.mirrorHistoryFrames;
  c.glossyHistoryFrames = s.glossyHistoryFrames;
  c.glossyHistoryRoughness = s.glossyHistoryRoughness;
  c.virtualRoughnessLimit = s.virtualRoughnessLimit;
  c.planeTolerance = s.planeTolerance;
  c.normalTolerance = s.normalToleranceDegrees * float(M_PI) / 180.0f;
  c.mirrorNormalTolerance = s.mirrorNormalToleranceDegrees * float(M_PI) / 180.0f;
  c.roughnessTolerance = s.roughnessTolerance;
  c.ghostSigma = s.ghostSigma;
  c.responsiveFrames = s.responsiveFrames;
  c.spatialMaxRadius = s.spatialMaxRadius;
  c.spatialFootprintScale = s.spatialFootprintScale;
  c.fastHistoryFrames = s.fastHistoryFrames;
  c.lagSigma = s.lagSigma;
  c.motionParallaxTolerance = s.motionParallaxTolerance;
  c.flags = s.poisonInput ? gpu::REFLECTION_DENOISE_FLAG_POISON_INPUT : 0u;
  return c;
}

TracedReflections ReflectionsDenoisePass::declare(graph::FrameGraph& graph,
                                                  const FrameContext& frame, const GBuffer& gbuffer,
                                                  const TracedReflections& traced,
                                                  const gpu::ReflectionPassConstants& trace) {
  constexpr VkFormat rgba16f = VK_FORMAT_R16G16B16A16_SFLOAT;
  const graph::ImageSize size = graph::ImageSize::dividedRes(trace.divisor);
  graph::HistoryImage temporal = graph.createHistoryImage("reflections.temporal", {rgba16f, size});
  graph::HistoryImage moments = graph.createHistoryImage("reflections.temporal-moments",
                                                         {VK_FORMAT_R32G32B32A32_SFLOAT, size});
  graph::HistoryImage surface = graph.createHistoryImage("reflections.temporal-surface",
                                                         {VK_FORMAT_R32G32B32A32_SFLOAT, size});
  graph::HistoryImage fast = graph.createHistoryImage("reflections.temporal-fast", {rgba16f, size});
  TracedReflections out{graph.createImage("reflections.denoised", {rgba16f, size})};
  const gpu::ReflectionDenoiseConstants push = constants(trace);
  const VkExtent2D extent{trace.tracedResolution.x, trace.tracedResolution.y};
  auto dispatch = [extent](VkCommandBuffer cmd) {
    vk::ComputePipeline::dispatchCovering(cmd, extent.width, extent.height, gpu::HYBRID_GROUP_SIZE,
                                          gpu::HYBRID_GROUP_SIZE);
  };

  graph.addPass("reflections-denoise-temporal", graph::QueueKind::Compute)
      .read(frame.constants, Access::StorageRead)
      // The first image written is the pass's debug view: the running mean.
      .write(temporal.current, Access::StorageWrite,
             gpu::REFLECTIONS_DENOISE_TEMPORAL_BINDING_CURRENT)
      .write(moments.current, Access::StorageWrite,
             gpu::REFLECTIONS_DENOISE_TEMPORAL_BINDING_CURRENT_MOMENTS)
      .write(surface.current, Access::StorageWrite,
             gpu::REFLECTIONS_DENOISE_TEMPORAL_BINDING_CURRENT_SURFACE)
      .write(fast.current, Access::StorageWrite,
             gpu::REFLECTIONS_DENOISE_TEMPORAL_BINDING_CURRENT_FAST)
      .read(traced.traced, Access::SampledRead, gpu::REFLECTIONS_DENOISE_TEMPORAL_BINDING_TRACED)
      .read(gbuffer.normals, Access::SampledRead, gpu::REFLECTIONS_DENOISE_TEMPORAL_BINDING_NORMALS)
      .read(gbuffer.depth.current, Access::SampledRead,
            gpu::REFLECTIONS_DENOISE_TEMPORAL_BINDING_DEPTH)
      .read(gbuffer.emissive, Access::SampledRead,
            gpu::REFLECTIONS_DENOISE_TEMPORAL_BINDING_EMISSIVE)
      .read(gbuffer.flags, Access::SampledRead, gpu::REFLECTIONS_DENOISE_TEMPORAL_BINDING_FLAGS)
      .read(gbuffer.velocity, Access::SampledRead,
            gpu::REFLECTIONS_DENOISE_TEMPORAL_BINDING_VELOCITY)
      .read(temporal.previous, Access::SampledRead,
            gpu::REFLECTIONS_DENOISE_TEMPORAL_BINDING_PREVIOUS)
      .read(moments.previous, Access::SampledRead,
            gpu::REFLECTIONS_DENOISE_TEMPORAL_BINDING_PREVIOUS_MOMENTS)
      .read(surface.previous, Access::SampledRead,
            gpu::REFLECTIONS_DENOISE_TEMPORAL_BINDING_PREVIOUS_SURFACE)
      .read(fast.previous, Access::SampledRead,
            gpu::REFLECTIONS_DENOISE_TEMPORAL_BINDING_PREVIOUS_FAST)
      .read(traced.candidate[gpu::GI_RESERVOIR_SAMPLE], Access::SampledRead,
            gpu::REFLECTIONS_DENOISE_TEMPORAL_BINDING_CANDIDATE_SAMPLE)
      .read(traced.candidate[gpu::GI_RESERVOIR_ORIGIN], Access::SampledRead,
            gpu::REFLECTIONS_DENOISE_TEMPORAL_BINDING_CANDIDATE_ORIGIN)
      .record([this, push, frame, temporal, moments, surface, fast, dispatch](
                  VkCommandBuffer cmd, const graph::PassResources& r) {
        gpu::ReflectionDenoiseConstants c = push;
        // After a lighting cut the history holds the old light: start afresh (as the shadows
        // do); a camera cut or a resize resets every history of the graph.
        c.historyValid = !frame.lightingCut && r.historyValid(temporal) &&
                         r.historyValid(moments) && r.historyValid(surface) && r.historyValid(fast);
        temporal_.bind(cmd, c, r);
        dispatch(cmd);
      });

  graph.addPass("reflections-denoise-spatial", graph::QueueKind::Compute)
      .read(frame.constants, Access::StorageRead)
      .write(out.traced, Access::StorageWrite, gpu::REFLECTIONS_DENOISE_SPATIAL_BINDING_OUTPUT)
      .read(temporal.current, Access::StorageRead,
            gpu::REFLECTIONS_DENOISE_SPATIAL_BINDING_TEMPORAL)
      .read(moments.current, Access::StorageRead, gpu::REFLECTIONS_DENOISE_SPATIAL_BINDING_MOMENTS)
      .read(surface.current, Access::StorageRead, gpu::REFLECTIONS_DENOISE_SPATIAL_BINDING_SURFACE)
      .read(gbuffer.depth.current, Access::StorageRead,
            gpu::REFLECTIONS_DENOISE_SPATIAL_BINDING_DEPTH)
      .record([this, push, dispatch](VkCommandBuffer cmd, const graph::PassResources& r) {
        spatial_.bind(cmd, push, r);
        dispatch(cmd);
      });
  return out;
}

}  // namespace bounce
