#include "denoise/reblur.h"

#include <algorithm>
#include <utility>

#include "core/error.h"

namespace bounce {

using graph::Access;

namespace {

constexpr VkFormat kRgba16f = VK_FORMAT_R16G16B16A16_SFLOAT;
// reblur.surface: depth bits and an octahedral snorm16 normal (denoise/packed_surface.glsl).
constexpr VkFormat kRg32ui = VK_FORMAT_R32G32_UINT;
constexpr VkFormat kRgba32ui = VK_FORMAT_R32G32B32A32_UINT;
constexpr VkFormat kR32f = VK_FORMAT_R32_SFLOAT;

void dispatch(VkCommandBuffer cmd, const gpu::ReblurConstants& c) {
  vk::ComputePipeline::dispatchCovering(cmd, c.resolution.x, c.resolution.y, gpu::REBLUR_GROUP_SIZE,
                                        gpu::REBLUR_GROUP_SIZE);
}

bool finiteAtLeast(float v, float lo) {
  return v >= lo && v < 1e30f;
}

}  // namespace

void validate(const ReblurSettings& s) {
  if (!finiteAtLeast(s.radiusReferenceHeight, 0.0f) || s.radiusReferenceHeight > 16384.0f)
    fail("ReBLUR: radius reference height {} must be 0 to 16384 pixels", s.radiusReferenceHeight);
  if (!finiteAtLeast(s.preBlurRadius, 0.0f) || s.preBlurRadius > 256.0f)
    fail("ReBLUR: pre-blur radius {} must be 0 to 256 pixels", s.preBlurRadius);
  if (!finiteAtLeast(s.maxBlurRadius, 0.0f) || s.maxBlurRadius > 256.0f ||
      !finiteAtLeast(s.minBlurRadius, 0.0f) || s.minBlurRadius > s.maxBlurRadius)
    fail("ReBLUR: blur radius {} (minimum {}) must be 0 to 256 pixels, minimum at most it",
         s.maxBlurRadius, s.minBlurRadius);
  if (!finiteAtLeast(s.maxAccumulatedFrames, 1.0f) || s.maxAccumulatedFrames > 1024.0f ||
      !finiteAtLeast(s.maxFastAccumulatedFrames, 1.0f) ||
      s.maxFastAccumulatedFrames > s.maxAccumulatedFrames)
    fail("ReBLUR: history lengths slow {} and fast {} must be 1 to 1024 frames, fast <= slow",
         s.maxAccumulatedFrames, s.maxFastAccumulatedFrames);
  if (!finiteAtLeast(s.historyFixFrames, 0.0f) || s.historyFixFrames > 64.0f ||
      !finiteAtLeast(s.historyFixStride, 0.0f) || s.historyFixStride > 64.0f)
    fail("ReBLUR: history fix frames {} and stride {} must be 0 to 64", s.historyFixFrames,
         s.historyFixStride);
  if (!(s.sigmaScale > 0.0f) || !finiteAtLeast(s.sigmaScale, 0.0f))
    fail("ReBLUR: sigma scale {} must be positive", s.sigmaScale);
  if (!finiteAtLeast(s.antilagSensitivity, 0.0f))
    fail("ReBLUR: anti-lag sensitivity {} must be 0 or more", s.antilagSensitivity);
  if (!finiteAtLeast(s.antiFireflySigma, 0.0f))
    fail("ReBLUR: anti-firefly sigma {} must be 0 (off) or more", s.antiFireflySigma);
  if (!finiteAtLeast(s.maxStabilizedFrames, 1.0f) || s.maxStabilizedFrames > 1024.0f)
    fail("ReBLUR: stabilised history {} frames must be 1 to 1024", s.maxStabilizedFrames);
  if (!(s.depthTolerance > 0.0f) || !(s.normalTolerance >= -1.0f && s.normalTolerance <= 1.0f) ||
      !finiteAtLeast(s.normalPower, 0.0f))
    fail(
        "ReBLUR: depth tolerance {} must be positive, normal tolerance {} in [-1, 1], normal "
        "power {} at least 0",
        s.depthTolerance, s.normalTolerance, s.normalPower);
}

// The read-only inputs are sampled images (docs/architecture.md, "Sampled inputs").
Reblur::Reblur(vk::Context& context, const GpuScene& scene, const ReblurSettings& settings,
               std::string name)
    : settings_(settings),
      name_(std::move(name)),
      preBlur_(
          context, scene, "denoise/reblur_pre_blur", gpu::REBLUR_PRE_BLUR_BINDING_COUNT,
          sizeof(gpu::ReblurConstants), 1, {},
          bindingMask({gpu::REBLUR_PRE_BLUR_BINDING_NOISY, gpu::REBLUR_PRE_BLUR_BINDING_DEPTH,
                       gpu::REBLUR_PRE_BLUR_BINDING_NORMALS, gpu::REBLUR_PRE_BLUR_BINDING_ALBEDO})),
      temporal_(
          context, scene, "denoise/reblur_temporal", gpu::REBLUR_TEMPORAL_BINDING_COUNT,
          sizeof(gpu::ReblurConstants), 1, {},
          bindingMask(
              {gpu::REBLUR_TEMPORAL_BINDING_INPUT, gpu::REBLUR_TEMPORAL_BINDING_SURFACE,
               gpu::REBLUR_TEMPORAL_BINDING_MOTION, gpu::REBLUR_TEMPORAL_BINDING_PREVIOUS_SURFACE,
               gpu::REBLUR_TEMPORAL_BINDING_PREVIOUS_HISTORY,
               gpu::REBLUR_TEMPORAL_BINDING_PREVIOUS_FAST, gpu::REBLUR_TEMPORAL_BINDING_SLOPE})),
      historyFix_(
          context, scene, "denoise/reblur_history_fix", gpu::REBLUR_HISTORY_FIX_BINDING_COUNT,
          sizeof(gpu::ReblurConstants), 1, {},
          bindingMask({gpu::REBLUR_HISTORY_FIX_BINDING_INPUT, gpu::REBLUR_HISTORY_FIX_BINDING_FAST,
                       gpu::REBLUR_HISTORY_FIX_BINDING_SURFACE,
                       gpu::REBLUR_HISTORY_FIX_BINDING_SLOPE})),
      blur_(context, scene, "denoise/reblur_blur", gpu::REBLUR_BLUR_BINDING_COUNT,
            sizeof(gpu::ReblurConstants), 2, {},
            bindingMask({gpu::REBLUR_BLUR_BINDING_INPUT, gpu::REBLUR_BLUR_BINDING_SURFACE,
                         gpu::REBLUR_BLUR_BINDING_TILES, gpu::REBLUR_BLUR_BINDING_SLOPE})),
      stabilize_(
          context, scene, "denoise/reblur_stabilize", gpu::REBLUR_STABILIZE_BINDING_COUNT,
          sizeof(gpu::ReblurConstants), 1, {},
          bindingMask(
              {gpu::REBLUR_STABILIZE_BINDING_INPUT, gpu::REBLUR_STABILIZE_BINDING_FAST_MOMENTS,
               gpu::REBLUR_STABILIZE_BINDING_MOTION, gpu::REBLUR_STABILIZE_BINDING_FOOTPRINT,
               gpu::REBLUR_STABILIZE_BINDING_PREVIOUS_STABLE,
               gpu::REBLUR_STABILIZE_BINDING_ALBEDO})) {
  validate(settings_);
}

float Reblur::scaled(float pixels, VkExtent2D resolution, float floor) const {
  const float reference = settings_.radiusReferenceHeight;
  if (!(reference > 0.0f)) return pixels;
  return std::max(pixels * float(resolution.height) / reference, floor);
}

gpu::ReblurConstants Reblur::constants(VkExtent2D resolution, const DenoiseInputs& in) const {
  const ReblurSettings& s = settings_;
  gpu::ReblurConstants c{};
  c.resolution = {resolution.width, resolution.height};
  c.flags = (in.octahedralNormals ? gpu::REBLUR_FLAG_OCTAHEDRAL_NORMALS : 0u) |
            (in.albedo ? gpu::REBLUR_FLAG_ALBEDO : 0u);
  c.blurRadius = scaled(s.maxBlurRadius, resolution, s.minBlurRadius);
  c.minBlurRadius = s.minBlurRadius;
  c.depthTolerance = s.depthTolerance;
  c.normalTolerance = s.normalTolerance;
  c.normalPower = s.normalPower;
  c.maxAccumulatedFrames = s.maxAccumulatedFrames;
  c.maxFastAccumulatedFrames = s.maxFastAccumulatedFrames;
  c.historyFixFrames = s.historyFixFrames;
  c.historyFixStride =
      s.historyFixStride > 0.0f ? scaled(s.historyFixStride, resolution, 1.0f) : 0.0f;
  c.sigmaScale = s.sigmaScale;
  c.antilagSensitivity = s.antilagSensitivity;
  c.maxStabilizedFrames = s.maxStabilizedFrames;
  c.antiFireflySigma = s.antiFireflySigma;
  return c;
}

void Reblur::declare(graph::FrameGraph& graph, VkExtent2D resolution, const DenoiseInputs& in,
                     graph::ImageHandle output) {
  declareSpatial(graph, resolution, in, declareTemporal(graph, resolution, in), output);
}

Reblur::Temporal Reblur::declareTemporal(graph::FrameGraph& graph, VkExtent2D resolution,
                                         const DenoiseInputs& in) {
  graph::HistoryImage surface = graph.createHistoryImage(name_ + ".surface", {kRg32ui});
  graph::HistoryImage fast = graph.createHistoryImage(name_ + ".fast", {kRgba16f});
  graph::HistoryImage history = graph.createHistoryImage(name_ + ".accumulated", {kRgba16f});
  const graph::ImageHandle accumulated = history.current;
  graph::ImageHandle preBlurred = graph.createImage(name_ + ".pre-blurred", {kRgba16f});
  graph::ImageHandle fixed = graph.createImage(name_ + ".fixed", {kRgba16f});
  graph::ImageHandle slope = graph.createImage(name_ + ".slope", {kR32f});
  graph::ImageHandle fastMoments = graph.createImage(name_ + ".fast-moments", {kRgba32ui});
  graph::ImageHandle footprint = graph.createImage(name_ + ".footprint", {VK_FORMAT_R8_UINT});
  const gpu::ReblurConstants c = constants(resolution, in);
  const bool valid = !in.dropHistory;

  graph::PassBuilder pre = graph.addPass(name_ + "-pre-blur", graph::QueueKind::Compute);
  pre.read(in.noisy, Access::SampledRead, gpu::REBLUR_PRE_BLUR_BINDING_NOISY)
      .read(in.depth, Access::SampledRead, gpu::REBLUR_PRE_BLUR_BINDING_DEPTH)
      .read(in.normals, Access::SampledRead, gpu::REBLUR_PRE_BLUR_BINDING_NORMALS)
      .write(surface.current, Access::StorageWrite, gpu::REBLUR_PRE_BLUR_BINDING_SURFACE)
      .write(preBlurred, Access::StorageWrite, gpu::REBLUR_PRE_BLUR_BINDING_OUTPUT)
      .write(slope, Access::StorageWrite, gpu::REBLUR_PRE_BLUR_BINDING_SLOPE);
  if (in.albedo)
    pre.read(*in.albedo, Access::SampledRead, gpu::REBLUR_PRE_BLUR_BINDING_ALBEDO);
  else
    pre.readPlaceholder(in.noisy, gpu::REBLUR_PRE_BLUR_BINDING_ALBEDO, Access::SampledRead);
  const float preBlurRadius =
      settings_.preBlurRadius > 0.0f
          ? scaled(settings_.preBlurRadius, resolution, settings_.minBlurRadius)
          : 0.0f;
  pre.record([this, c, preBlurRadius](VkCommandBuffer cmd, const graph::PassResources& r) {
    gpu::ReblurConstants k = c;
    k.blurRadius = preBlurRadius;
    k.frame = frame_;
    preBlur_.bind(cmd, k, r);
    dispatch(cmd, k);
  });

  graph.addPass(name_ + "-temporal", graph::QueueKind::Compute)
      .read(preBlurred, Access::SampledRead, gpu::REBLUR_TEMPORAL_BINDING_INPUT)
      .read(surface.current, Access::SampledRead, gpu::REBLUR_TEMPORAL_BINDING_SURFACE)
      .read(slope, Access::SampledRead, gpu::REBLUR_TEMPORAL_BINDING_SLOPE)
      .read(in.motion, Access::SampledRead, gpu::REBLUR_TEMPORAL_BINDING_MOTION)
      .read(surface.previous, Access::SampledRead, gpu::REBLUR_TEMPORAL_BINDING_PREVIOUS_SURFACE)
      .read(history.previous, Access::SampledRead, gpu::REBLUR_TEMPORAL_BINDING_PREVIOUS_HISTORY)
      .read(fast.previous, Access::SampledRead, gpu::REBLUR_TEMPORAL_BINDING_PREVIOUS_FAST)
      .write(fast.current, Access::StorageWrite, gpu::REBLUR_TEMPORAL_BINDING_FAST)
      .write(accumulated, Access::StorageWrite, gpu::REBLUR_TEMPORAL_BINDING_ACCUMULATED)
      .write(footprint, Access::StorageWrite, gpu::REBLUR_TEMPORAL_BINDING_FOOTPRINT)
      .record([this, c, valid, surface, history, fast](VkCommandBuffer cmd,
                                                       const graph::PassResources& r) {
        gpu::ReblurConstants k = c;
        k.historyValid =
            valid && r.historyValid(surface) && r.historyValid(history) && r.historyValid(fast);
        k.frame = frame_;
        temporal_.bind(cmd, k, r);
        dispatch(cmd, k);
      });

  graph.addPass(name_ + "-history-fix", graph::QueueKind::Compute)
      .read(accumulated, Access::SampledRead, gpu::REBLUR_HISTORY_FIX_BINDING_INPUT)
      .read(fast.current, Access::SampledRead, gpu::REBLUR_HISTORY_FIX_BINDING_FAST)
      .read(surface.current, Access::SampledRead, gpu::REBLUR_HISTORY_FIX_BINDING_SURFACE)
      .read(slope, Access::SampledRead, gpu::REBLUR_HISTORY_FIX_BINDING_SLOPE)
      .write(fixed, Access::StorageWrite, gpu::REBLUR_HISTORY_FIX_BINDING_OUTPUT)
      .write(fastMoments, Access::StorageWrite, gpu::REBLUR_HISTORY_FIX_BINDING_FAST_MOMENTS)
      .record([this, c](VkCommandBuffer cmd, const graph::PassResources& r) {
        historyFix_.bind(cmd, c, r);
        dispatch(cmd, c);
      });

  return {fixed, fastMoments, surface, slope, footprint};
}

void Reblur::declareSpatial(graph::FrameGraph& graph, VkExtent2D resolution,
                            const DenoiseInputs& in, const Temporal& temporal,
                            graph::ImageHandle output, std::optional<graph::ImageHandle> tiles) {
  graph::HistoryImage stable = graph.createHistoryImage(name_ + ".stable", {kRgba16f});
  graph::ImageHandle postBlurred = graph.createImage(name_ + ".post-blurred", {kRgba16f});
  graph::ImageHandle blurred = graph.createImage(name_ + ".blurred", {kRgba16f});
  const graph::ImageHandle fixed = temporal.fixed;
  const graph::HistoryImage surface = temporal.surface;
  gpu::ReblurConstants c = constants(resolution, in);
  if (tiles) c.flags |= gpu::REBLUR_FLAG_TILES;
  const bool valid = !in.dropHistory;

  // reblur-blur (set 0) and reblur-post-blur (set 1), one pipeline.
  const graph::ImageHandle blurIn[2] = {fixed, blurred};
  const graph::ImageHandle blurOut[2] = {blurred, postBlurred};
  for (uint32_t i = 0; i < 2; ++i) {
    graph::PassBuilder blur =
        graph.addPass(i == 0 ? name_ + "-blur" : name_ + "-post-blur", graph::QueueKind::Compute);
    blur.read(blurIn[i], Access::SampledRead, gpu::REBLUR_BLUR_BINDING_INPUT)
        .read(surface.current, Access::SampledRead, gpu::REBLUR_BLUR_BINDING_SURFACE)
        .read(temporal.slope, Access::SampledRead, gpu::REBLUR_BLUR_BINDING_SLOPE)
        .write(blurOut[i], Access::StorageWrite, gpu::REBLUR_BLUR_BINDING_OUTPUT);
    if (tiles)
      blur.read(*tiles, Access::SampledRead, gpu::REBLUR_BLUR_BINDING_TILES);
    else
      blur.readPlaceholder(blurIn[i], gpu::REBLUR_BLUR_BINDING_TILES, Access::SampledRead);
    blur.record([this, c, i](VkCommandBuffer cmd, const graph::PassResources& r) {
      gpu::ReblurConstants k = c;
      k.flags |= i == 1 ? gpu::REBLUR_FLAG_POST_BLUR : 0u;
      k.frame = frame_;
      blur_.bind(cmd, k, r, i);
      dispatch(cmd, k);
    });
  }

  graph::PassBuilder st = graph.addPass(name_ + "-stabilize", graph::QueueKind::Compute);
  st.read(postBlurred, Access::SampledRead, gpu::REBLUR_STABILIZE_BINDING_INPUT)
      .read(temporal.fastMoments, Access::SampledRead, gpu::REBLUR_STABILIZE_BINDING_FAST_MOMENTS)
      .read(in.motion, Access::SampledRead, gpu::REBLUR_STABILIZE_BINDING_MOTION)
      .read(temporal.footprint, Access::SampledRead, gpu::REBLUR_STABILIZE_BINDING_FOOTPRINT)
      .read(stable.previous, Access::SampledRead, gpu::REBLUR_STABILIZE_BINDING_PREVIOUS_STABLE)
      .write(stable.current, Access::StorageWrite, gpu::REBLUR_STABILIZE_BINDING_STABLE)
      .write(output, Access::StorageWrite, gpu::REBLUR_STABILIZE_BINDING_OUTPUT);
  if (in.albedo)
    st.read(*in.albedo, Access::SampledRead, gpu::REBLUR_STABILIZE_BINDING_ALBEDO);
  else
    st.readPlaceholder(in.noisy, gpu::REBLUR_STABILIZE_BINDING_ALBEDO, Access::SampledRead);
  st.record([this, c, valid, surface, stable](VkCommandBuffer cmd, const graph::PassResources& r) {
    gpu::ReblurConstants k = c;
    k.historyValid = valid && r.historyValid(surface) && r.historyValid(stable);
    k.frame = frame_++;
    stabilize_.bind(cmd, k, r);
    dispatch(cmd, k);
  });
}

}  // namespace bounce
