#include "passes/auto_exposure.h"

#include <cmath>

#include "core/error.h"

namespace bounce {

using graph::Access;
using graph::QueueKind;

void validate(const AutoExposureSettings& s) {
  if (!(s.lowPercentile >= 0.0f && s.lowPercentile < s.highPercentile && s.highPercentile <= 1.0f))
    fail("auto exposure percentiles {} .. {}: expected 0 <= low < high <= 1", s.lowPercentile,
         s.highPercentile);
  if (!(s.key > 0.0f) || !std::isfinite(s.key))
    fail("auto exposure key {}: expected a luminance above 0", s.key);
  const float histogramMin = float(gpu::EXPOSURE_HISTOGRAM_MIN_LOG2);
  const float histogramMax =
      histogramMin + float(gpu::EXPOSURE_HISTOGRAM_BINS) / float(gpu::EXPOSURE_BINS_PER_STOP);
  if (!(s.minLog2Luminance >= histogramMin && s.minLog2Luminance < s.maxLog2Luminance &&
        s.maxLog2Luminance <= histogramMax))
    fail("auto exposure luminance range 2^{} .. 2^{}: expected min < max within 2^{} .. 2^{}",
         s.minLog2Luminance, s.maxLog2Luminance, histogramMin, histogramMax);
  if (!(s.brighteningSeconds >= 0.0f) || !std::isfinite(s.brighteningSeconds))
    fail("auto exposure brightening time {} s: expected >= 0", s.brighteningSeconds);
  if (!(s.darkeningSeconds >= 0.0f) || !std::isfinite(s.darkeningSeconds))
    fail("auto exposure darkening time {} s: expected >= 0", s.darkeningSeconds);
}

AutoExposure::AutoExposure(vk::Context& context, const GpuScene& scene,
                           const AutoExposureSettings& settings)
    : settings_(settings),
      histogram_(context, scene, "passes/exposure_histogram", gpu::EXPOSURE_HISTOGRAM_BINDING_COUNT,
                 sizeof(gpu::ExposureHistogramConstants)),
      adapt_(context, scene, "passes/exposure_adapt", gpu::EXPOSURE_ADAPT_BINDING_COUNT,
             sizeof(gpu::ExposureAdaptConstants)),
      debugView_(context, scene, "passes/exposure_debug", gpu::EXPOSURE_DEBUG_BINDING_COUNT,
                 sizeof(gpu::ExposureDebugConstants)) {
  validate(settings);
}

Exposure AutoExposure::declare(graph::FrameGraph& graph, const HdrImage& hdr,
                               float compensationStops, float deltaSeconds) {
  const graph::BufferDesc histogramDesc{
      graph::BufferSize::fixed(sizeof(uint32_t) * gpu::EXPOSURE_HISTOGRAM_BINS)};
  // Persistent: zeroed when created and by exposure-adapt after every use.
  graph::BufferHandle histogram = graph.createPersistentBuffer("exposure.histogram", histogramDesc);
  graph::HistoryBuffer state = graph.createHistoryBuffer(
      "exposure.state", {graph::BufferSize::fixed(sizeof(gpu::ExposureState))});

  gpu::ExposureAdaptConstants adapt{};
  adapt.lowPercentile = settings_.lowPercentile;
  adapt.highPercentile = settings_.highPercentile;
  adapt.log2Key = std::log2(settings_.key);
  adapt.compensationStops = compensationStops;
  adapt.minLog2Luminance = settings_.minLog2Luminance;
  adapt.maxLog2Luminance = settings_.maxLog2Luminance;
  adapt.brighteningSeconds = settings_.brighteningSeconds;
  adapt.darkeningSeconds = settings_.darkeningSeconds;
  adapt.deltaSeconds = deltaSeconds;
  // No history: the first frame or a reset; the metered exposure is taken as it is.
  adapt.snap = graph.historyValid(state) ? 0u : 1u;

  declareHistogram(graph, hdr, histogram);
  declareAdapt(graph, histogram, state, adapt);
  declareDebugView(graph, state.current);
  return {state.current};
}

void AutoExposure::declareHistogram(graph::FrameGraph& graph, const HdrImage& hdr,
                                    graph::BufferHandle histogram) {
  graph.addPass("exposure-histogram", QueueKind::Compute)
      .read(hdr.radiance, Access::StorageRead, gpu::EXPOSURE_HISTOGRAM_BINDING_HDR)
      .write(histogram, Access::StorageReadWrite)
      .record([this, hdr, histogram](VkCommandBuffer cmd, const graph::PassResources& r) {
        histogram_.bind(cmd, gpu::ExposureHistogramConstants{r.buffer(histogram).address}, r);
        const VkExtent2D extent = r.image(hdr.radiance).extent;
        vk::ComputePipeline::dispatchCovering(cmd, extent.width, extent.height,
                                              gpu::EXPOSURE_HISTOGRAM_GROUP_SIZE,
                                              gpu::EXPOSURE_HISTOGRAM_GROUP_SIZE);
      });
}

void AutoExposure::declareAdapt(graph::FrameGraph& graph, graph::BufferHandle histogram,
                                const graph::HistoryBuffer& state,
                                gpu::ExposureAdaptConstants constants) {
  graph.addPass("exposure-adapt", QueueKind::Compute)
      .write(histogram, Access::StorageReadWrite)
      .read(state.previous, Access::StorageRead)
      .write(state.current, Access::StorageWrite)
      .record([this, histogram, state, constants](VkCommandBuffer cmd,
                                                  const graph::PassResources& r) mutable {
        constants.histogram = r.buffer(histogram).address;
        constants.previous = r.buffer(state.previous).address;
        constants.current = r.buffer(state.current).address;
        adapt_.bind(cmd, constants, r);
        vkCmdDispatch(cmd, 1, 1, 1);
      });
}

// `exposure`: the histogram, the metering window and the levels as an image.
void AutoExposure::declareDebugView(graph::FrameGraph& graph, graph::BufferHandle state) {
  graph::ImageHandle view = graph.createImage(
      "exposure", {VK_FORMAT_R16G16B16A16_SFLOAT,
                   graph::ImageSize::fixed(gpu::EXPOSURE_VIEW_WIDTH, gpu::EXPOSURE_VIEW_HEIGHT)});
  const float low = settings_.lowPercentile, high = settings_.highPercentile;
  graph.addPass("exposure-debug", QueueKind::Compute)
      .read(state, Access::StorageRead)
      .write(view, Access::StorageWrite, gpu::EXPOSURE_DEBUG_BINDING_VIEW)
      .record([this, state, low, high](VkCommandBuffer cmd, const graph::PassResources& r) {
        debugView_.bind(cmd, gpu::ExposureDebugConstants{r.buffer(state).address, low, high}, r);
        vk::ComputePipeline::dispatchCovering(cmd, gpu::EXPOSURE_VIEW_WIDTH,
                                              gpu::EXPOSURE_VIEW_HEIGHT, 8, 8);
      });
}

}  // namespace bounce
