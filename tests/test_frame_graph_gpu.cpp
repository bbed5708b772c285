// The frame graph on a real device (lavapipe in CI) with validation and synchronization
// validation on: a small compute frame (fill a pattern, blend it with last frame's history, sum
// the rows into a buffer, copy that to the host, clear the buffer) runs for 20 frames, and again
// after a resize.
// Every value is checked exactly against the same rules run on the CPU; the validation layers
// must stay silent, frames must not allocate, every pass gets a timestamp, an unread pass is
// culled, and two debug views (a pass and a resource) read back the right texels.
#include <cstring>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/error.h"
#include "graph/frame_graph.h"
#include "tests/graph_test_io.h"
#include "vk/context.h"
#include "vk/gpu_timer.h"
#include "vk/pipeline.h"
#include "vk/resources.h"

namespace bounce::graph {
namespace {

using namespace bounce::gpu;  // the test shaders' bindings and rules

constexpr uint32_t kFrames = 20;
constexpr uint32_t kMaxRows = 64;
const VkExtent2D kResolution{16, 8};
const VkExtent2D kResizedResolution{12, 6};

// The test frame computed on the CPU: last frame's accumulation in, this frame's out.
struct CpuFrame {
  std::vector<uint32_t> pattern;
  std::vector<uint32_t> accumulation;
  std::vector<uint32_t> rowSums;
};

CpuFrame runOnCpu(VkExtent2D size, uint32_t frame, const std::vector<uint32_t>* previous) {
  CpuFrame f;
  f.pattern.resize(size.width * size.height);
  f.accumulation.resize(f.pattern.size());
  f.rowSums.assign(size.height, 0u);
  for (uint32_t y = 0; y < size.height; ++y)
    for (uint32_t x = 0; x < size.width; ++x) {
      uint32_t i = y * size.width + x;
      f.pattern[i] = gpu::graphTestPattern({x, y}, frame);
      uint32_t here = previous ? (*previous)[i] : 0u;
      uint32_t right =
          previous ? (*previous)[y * size.width + std::min(x + 1, size.width - 1)] : 0u;
      f.accumulation[i] = gpu::graphTestBlend(f.pattern[i], here, right);
      f.rowSums[y] += f.accumulation[i];
    }
  return f;
}

std::vector<uint32_t> asWords(const std::vector<std::byte>& bytes) {
  std::vector<uint32_t> words(bytes.size() / 4);
  std::memcpy(words.data(), bytes.data(), words.size() * 4);
  return words;
}

// Pipelines and descriptor sets of the three shader passes; sets are rewritten by each pass's
// callback because the history images swap every frame.
struct TestPipelines {
  explicit TestPipelines(vk::Context& context)
      : context(context),
        fillLayout(context, {{GRAPH_TEST_BINDING_PATTERN, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE}}),
        blendLayout(context, {{GRAPH_TEST_BINDING_PATTERN, VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE},
                              {GRAPH_TEST_BINDING_PREVIOUS, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE},
                              {GRAPH_TEST_BINDING_CURRENT, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE}}),
        sumLayout(context, {{GRAPH_TEST_BINDING_ACCUMULATION, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE}}),
        pool(context, 3, 4),
        fill(context, "tests/graph_fill", {&fillLayout}, sizeof(gpu::GraphTestConstants)),
        blend(context, "tests/graph_blend", {&blendLayout}, sizeof(gpu::GraphTestConstants)),
        sum(context, "tests/graph_sum_rows", {&sumLayout}, sizeof(gpu::GraphTestConstants)),
        fillSet(pool.allocate(fillLayout)),
        blendSet(pool.allocate(blendLayout)),
        sumSet(pool.allocate(sumLayout)) {}

  void writeImage(VkDescriptorSet set, uint32_t binding, VkDescriptorType type,
                  const ResolvedImage& image) const {
    VkDescriptorImageInfo info{VK_NULL_HANDLE, image.view, image.layout};
    VkWriteDescriptorSet write{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    write.dstSet = set;
    write.dstBinding = binding;
    write.descriptorCount = 1;
    write.descriptorType = type;
    write.pImageInfo = &info;
    vkUpdateDescriptorSets(context.device(), 1, &write, 0, nullptr);
  }

  vk::Context& context;
  vk::DescriptorSetLayout fillLayout, blendLayout, sumLayout;
  vk::DescriptorPool pool;
  vk::ComputePipeline fill, blend, sum;
  VkDescriptorSet fillSet, blendSet, sumSet;
};

class FrameGraphGpu : public ::testing::Test {
 protected:
  FrameGraphGpu()
      : context_(vk::contextOptionsFromEnvironment(
            {.validation = true, .synchronizationValidation = true})),
        pipelines_(context_),
        hostRowSums_(context_, kMaxRows * sizeof(uint32_t), VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                     vk::MemoryUse::Readback, "row-sums.host"),
        timer_(context_) {}

  // The frame, declared the way the renderer declares its own: one straight-line function.
  void declareFrame(uint32_t frame) {
    graph_.beginFrame();
    ImageHandle pattern = graph_.createImage("pattern", {VK_FORMAT_R32_UINT});
    HistoryImage accumulation = graph_.createHistoryImage("accumulation", {VK_FORMAT_R32_UINT});
    BufferHandle rowSums = graph_.createBuffer("row-sums", {BufferSize::perPixel(4)});
    BufferHandle hostRowSums =
        graph_.importBuffer("row-sums.host", ImportedBuffer::from(hostRowSums_));
    ImageHandle scratch = graph_.createImage("scratch", {VK_FORMAT_R32_UINT});
    historyValid_ = graph_.historyValid(accumulation);
    auto constants = [accumulation, frame](const PassResources& r, VkDeviceAddress rowSums) {
      VkExtent2D size = r.renderResolution();
      return gpu::GraphTestConstants{
          rowSums, {size.width, size.height}, frame, r.historyValid(accumulation) ? 1u : 0u};
    };

    graph_.addPass("fill", QueueKind::Compute)
        .write(pattern, Access::StorageWrite)
        .record([=, this](VkCommandBuffer cmd, const PassResources& r) {
          pipelines_.writeImage(pipelines_.fillSet, GRAPH_TEST_BINDING_PATTERN,
                                VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, r.image(pattern));
          dispatchImage(cmd, pipelines_.fill, pipelines_.fillSet, constants(r, 0), r);
        });
    graph_.addPass("blend", QueueKind::Compute)
        .read(pattern, Access::SampledRead)
        .read(accumulation.previous, Access::StorageRead)
        .write(accumulation.current, Access::StorageWrite)
        .record([=, this](VkCommandBuffer cmd, const PassResources& r) {
          VkDescriptorSet set = pipelines_.blendSet;
          pipelines_.writeImage(set, GRAPH_TEST_BINDING_PATTERN, VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE,
                                r.image(pattern));
          pipelines_.writeImage(set, GRAPH_TEST_BINDING_PREVIOUS, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,
                                r.image(accumulation.previous));
          pipelines_.writeImage(set, GRAPH_TEST_BINDING_CURRENT, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,
                                r.image(accumulation.current));
          dispatchImage(cmd, pipelines_.blend, set, constants(r, 0), r);
        });
    graph_.addPass("sum-rows", QueueKind::Compute)
        .read(accumulation.current, Access::StorageRead)
        .write(rowSums, Access::StorageWrite)
        .record([=, this](VkCommandBuffer cmd, const PassResources& r) {
          pipelines_.writeImage(pipelines_.sumSet, GRAPH_TEST_BINDING_ACCUMULATION,
                                VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, r.image(accumulation.current));
          pipelines_.sum.bind(cmd, {pipelines_.sumSet});
          pipelines_.sum.push(cmd, constants(r, r.buffer(rowSums).address));
          vk::ComputePipeline::dispatchCovering(cmd, r.renderResolution().height, 1,
                                                GRAPH_TEST_GROUP_SIZE, 1);
        });
    graph_.addPass("copy-out", QueueKind::Compute)
        .read(rowSums, Access::TransferSrc)
        .write(hostRowSums, Access::TransferDst)
        .record([=](VkCommandBuffer cmd, const PassResources& r) {
          VkBufferCopy region{0, 0, r.renderResolution().height * sizeof(uint32_t)};
          vkCmdCopyBuffer(cmd, r.buffer(rowSums).buffer, r.buffer(hostRowSums).buffer, 1, &region);
        });
    // Reuses the row sums once copied: a write after read within the frame.
    graph_.addPass("clear-row-sums", QueueKind::Compute)
        .write(rowSums, Access::TransferDst)
        .sideEffects()
        .record([=](VkCommandBuffer cmd, const PassResources& r) {
          vkCmdFillBuffer(cmd, r.buffer(rowSums).buffer, 0, VK_WHOLE_SIZE, 0);
        });
    graph_.addPass("unused", QueueKind::Compute)
        .write(scratch, Access::StorageWrite)
        .record([this](VkCommandBuffer, const PassResources&) { unusedPassRan_ = true; });
  }

  void dispatchImage(VkCommandBuffer cmd, const vk::ComputePipeline& pipeline, VkDescriptorSet set,
                     const gpu::GraphTestConstants& constants, const PassResources& r) {
    pipeline.bind(cmd, {set});
    pipeline.push(cmd, constants);
    vk::ComputePipeline::dispatchCovering(cmd, r.renderResolution().width,
                                          r.renderResolution().height, GRAPH_TEST_GROUP_SIZE,
                                          GRAPH_TEST_GROUP_SIZE);
  }

  std::vector<vk::PassTiming> runFrame(uint32_t frame) {
    declareFrame(frame);
    context_.submitAndWait([&](VkCommandBuffer cmd) {
      timer_.reset(cmd);
      graph_.execute(cmd, &timer_);
    });
    return timer_.read();
  }

  std::vector<uint32_t> hostRowSums(uint32_t rows) const {
    const uint32_t* words = hostRowSums_.mappedAs<uint32_t>();
    return std::vector<uint32_t>(words, words + rows);
  }

  // Runs `frames` frames at `resolution` and checks each against the CPU; the first frame
  // starts without history.
  void runAndCheck(VkExtent2D resolution, uint32_t firstFrame, uint32_t frames) {
    std::vector<uint32_t> previous;
    for (uint32_t frame = firstFrame; frame < firstFrame + frames; ++frame) {
      SCOPED_TRACE(frame);
      std::vector<vk::PassTiming> timings = runFrame(frame);
      EXPECT_EQ(historyValid_, frame != firstFrame);
      CpuFrame expected = runOnCpu(resolution, frame, historyValid_ ? &previous : nullptr);
      EXPECT_EQ(hostRowSums(resolution.height), expected.rowSums);
      checkDebugViews(resolution, expected, frame);
      checkTimings(timings);
      previous = expected.accumulation;
      if (frame == firstFrame + 2) allocationsAfterFrame2_ = context_.allocationCount();
      if (frame > firstFrame + 2) EXPECT_EQ(context_.allocationCount(), allocationsAfterFrame2_);
    }
  }

  void checkDebugViews(VkExtent2D resolution, const CpuFrame& expected, uint32_t frame) {
    DebugView blend = graph_.readDebugView("blend");  // the pass: its output, accumulation
    EXPECT_EQ(blend.resource, "accumulation");
    EXPECT_EQ(blend.frame, frame);
    EXPECT_EQ(blend.width, resolution.width);
    EXPECT_EQ(blend.height, resolution.height);
    EXPECT_EQ(asWords(blend.bytes), expected.accumulation);
    DebugView pattern = graph_.readDebugView("pattern");  // a transient resource
    EXPECT_EQ(pattern.format, VK_FORMAT_R32_UINT);
    EXPECT_EQ(asWords(pattern.bytes), expected.pattern);
  }

  void checkTimings(const std::vector<vk::PassTiming>& timings) {
    const FramePlan& plan = graph_.plan();
    ASSERT_EQ(timings.size(), plan.passes.size());
    double total = 0.0;
    for (size_t i = 0; i < timings.size(); ++i) {
      EXPECT_EQ(timings[i].name, plan.passes[i].name);
      EXPECT_GE(timings[i].milliseconds, 0.0);
      total += timings[i].milliseconds;
    }
    if (timer_.available()) EXPECT_GT(total, 0.0);
  }

  vk::Context context_;
  TestPipelines pipelines_;
  vk::Buffer hostRowSums_;
  vk::GpuTimer timer_;
  FrameGraph graph_;  // after the resources it imports: destroyed first
  bool historyValid_ = false;
  bool unusedPassRan_ = false;
  uint64_t allocationsAfterFrame2_ = 0;
};

TEST_F(FrameGraphGpu, TwentyFramesMatchTheCpuWithoutValidationErrorsOrAllocations) {
  graph_.requestDebugView("blend");
  graph_.requestDebugView("pattern");
  declareFrame(0);
  graph_.allocate(context_, kResolution);
  runAndCheck(kResolution, 0, kFrames);

  const FramePlan& plan = graph_.plan();
  std::vector<std::string> names;
  for (const PassPlan& p : plan.passes) names.push_back(p.name);
  EXPECT_EQ(names, (std::vector<std::string>{"fill", "blend", "debug-view:blend", "sum-rows",
                                             "copy-out", "clear-row-sums", "debug-view:pattern"}));
  EXPECT_EQ(plan.culledPasses, std::vector<std::string>{"unused"});
  EXPECT_FALSE(unusedPassRan_);
  EXPECT_EQ(context_.validationErrorCount(), 0u);
}

TEST_F(FrameGraphGpu, ResizeRecreatesResourcesAndRestartsHistory) {
  graph_.requestDebugView("blend");
  graph_.requestDebugView("pattern");
  declareFrame(0);
  graph_.allocate(context_, kResolution);
  runAndCheck(kResolution, 0, 3);

  uint64_t before = context_.allocationCount();
  declareFrame(3);
  graph_.allocate(context_, kResizedResolution);
  EXPECT_GT(context_.allocationCount(), before);  // resolution-sized resources were replaced
  runAndCheck(kResizedResolution, 3, 4);
  EXPECT_EQ(graph_.renderResolution().width, kResizedResolution.width);
  EXPECT_EQ(context_.validationErrorCount(), 0u);
}

TEST_F(FrameGraphGpu, ExecuteWithoutAllocatingNewResourcesFails) {
  declareFrame(0);
  graph_.allocate(context_, kResolution);
  graph_.beginFrame();
  ImageHandle extra = graph_.createImage("extra", {VK_FORMAT_R32_UINT});
  graph_.addPass("late-addition", QueueKind::Compute)
      .write(extra, Access::StorageWrite)
      .sideEffects();
  try {
    graph_.execute(VK_NULL_HANDLE);  // fails while resolving, before recording anything
    ADD_FAILURE() << "execute() allocated or ignored a resource that allocate() never created";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("'extra'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("allocate()"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace bounce::graph
