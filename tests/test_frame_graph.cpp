// The frame graph's logic without a GPU: pass order, the barriers derived from declared
// accesses (layouts, stages, access masks), transient and history resources across frames,
// culling, debug-view placement and the errors for bad declarations.
#include <cstdint>
#include <cstring>
#include <functional>
#include <initializer_list>
#include <string>

#include <gtest/gtest.h>

#include "core/error.h"
#include "graph/debug_view_image.h"
#include "graph/frame_graph.h"

namespace bounce::graph {
namespace {

const ImageDesc kColor{VK_FORMAT_R16G16B16A16_SFLOAT};
const BufferDesc kBuffer{BufferSize::fixed(1024)};

constexpr VkPipelineStageFlags2 kCompute = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;

// The barrier before `pass` on `resource`; fails the test when there is none.
const Barrier& barrierOf(const FramePlan& plan, const std::string& pass,
                         const std::string& resource) {
  const PassPlan* p = plan.pass(pass);
  if (!p) throw std::runtime_error("no pass " + pass + " in the plan");
  const PlannedBarrier* b = p->barrierFor(resource);
  if (!b) throw std::runtime_error("no barrier on " + resource + " before " + pass);
  return b->barrier;
}

bool hasBarrier(const FramePlan& plan, const std::string& pass, const std::string& resource) {
  const PassPlan* p = plan.pass(pass);
  return p && p->barrierFor(resource);
}

std::vector<std::string> passNames(const FramePlan& plan) {
  std::vector<std::string> names;
  for (const PassPlan& p : plan.passes) names.push_back(p.name);
  return names;
}

// Runs `declare` and expects a bounce::Error whose message contains every fragment.
void expectError(const std::function<void()>& declare,
                 std::initializer_list<const char*> fragments) {
  try {
    declare();
  } catch (const Error& e) {
    std::string message = e.what();
    for (const char* fragment : fragments)
      EXPECT_NE(message.find(fragment), std::string::npos)
          << "'" << fragment << "' missing from: " << message;
    return;
  }
  ADD_FAILURE() << "no error thrown";
}

TEST(FrameGraph, PassesRunInDeclarationOrder) {
  FrameGraph graph;
  ImageHandle a = graph.createImage("a", kColor);
  ImageHandle b = graph.createImage("b", kColor);
  ImageHandle out = graph.createPersistentImage("out", kColor);
  graph.addPass("vbuffer", QueueKind::Compute).write(a, Access::StorageWrite);
  graph.addPass("gbuffer", QueueKind::Compute)
      .read(a, Access::StorageRead)
      .write(b, Access::StorageWrite);
  graph.addPass("composite", QueueKind::Compute)
      .read(b, Access::SampledRead)
      .write(out, Access::StorageWrite);
  graph.addPass("tonemap", QueueKind::Compute).write(out, Access::StorageReadWrite);
  const FramePlan& plan = graph.compile();
  EXPECT_EQ(passNames(plan),
            (std::vector<std::string>{"vbuffer", "gbuffer", "composite", "tonemap"}));
  EXPECT_TRUE(plan.culledPasses.empty());
}

TEST(FrameGraph, StorageWriteThenSampledReadChangesLayout) {
  FrameGraph graph;
  ImageHandle normal = graph.createImage("gbuffer.normal", kColor);
  ImageHandle out = graph.createPersistentImage("out", kColor);
  graph.addPass("gbuffer", QueueKind::Compute).write(normal, Access::StorageWrite);
  graph.addPass("shade", QueueKind::Compute)
      .read(normal, Access::SampledRead)
      .write(out, Access::StorageWrite);
  const FramePlan& plan = graph.compile();

  // First use of a transient: from UNDEFINED, nothing to wait for.
  const Barrier& first = barrierOf(plan, "gbuffer", "gbuffer.normal");
  EXPECT_EQ(first.oldLayout, VK_IMAGE_LAYOUT_UNDEFINED);
  EXPECT_EQ(first.newLayout, VK_IMAGE_LAYOUT_GENERAL);
  EXPECT_EQ(first.srcStages, VK_PIPELINE_STAGE_2_NONE);
  EXPECT_EQ(first.dstStages, kCompute);
  EXPECT_EQ(first.dstAccess, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);

  const Barrier& read = barrierOf(plan, "shade", "gbuffer.normal");
  EXPECT_EQ(read.oldLayout, VK_IMAGE_LAYOUT_GENERAL);
  EXPECT_EQ(read.newLayout, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
  EXPECT_EQ(read.srcStages, kCompute);
  EXPECT_EQ(read.srcAccess, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  EXPECT_EQ(read.dstStages, kCompute);
  EXPECT_EQ(read.dstAccess, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
}

TEST(FrameGraph, WriteAfterWriteFlushesTheFirstWrite) {
  FrameGraph graph;
  BufferHandle counts = graph.createPersistentBuffer("counts", kBuffer);
  graph.addPass("clear", QueueKind::Compute).write(counts, Access::TransferDst);
  graph.addPass("count", QueueKind::Compute).write(counts, Access::StorageReadWrite);
  const FramePlan& plan = graph.compile();
  EXPECT_FALSE(hasBarrier(plan, "clear", "counts"));  // never used before: nothing to wait for
  const PlannedBarrier* b = plan.pass("count")->barrierFor("counts");
  ASSERT_NE(b, nullptr);
  EXPECT_FALSE(b->isImage);
  EXPECT_EQ(b->barrier.srcStages, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT);
  EXPECT_EQ(b->barrier.srcAccess, VK_ACCESS_2_TRANSFER_WRITE_BIT);
  EXPECT_EQ(b->barrier.dstStages, kCompute);
  EXPECT_EQ(b->barrier.dstAccess,
            VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
}

TEST(FrameGraph, WriteAfterReadIsAnExecutionDependency) {
  FrameGraph graph;
  ImageHandle image = graph.createPersistentImage("image", kColor);
  ImageHandle out = graph.createPersistentImage("out", kColor);
  graph.addPass("write", QueueKind::Compute).write(image, Access::StorageWrite);
  graph.addPass("read", QueueKind::Compute)
      .read(image, Access::StorageRead)
      .write(out, Access::StorageWrite);
  graph.addPass("rewrite", QueueKind::Compute).write(image, Access::StorageWrite);
  const FramePlan& plan = graph.compile();
  const Barrier& war = barrierOf(plan, "rewrite", "image");
  EXPECT_EQ(war.srcStages & kCompute, kCompute);
  EXPECT_EQ(war.srcAccess, VK_ACCESS_2_NONE);  // the write was made available before "read"
  EXPECT_EQ(war.oldLayout, VK_IMAGE_LAYOUT_GENERAL);
  EXPECT_EQ(war.newLayout, VK_IMAGE_LAYOUT_GENERAL);
  EXPECT_EQ(war.dstAccess, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
}

TEST(FrameGraph, ColorAttachmentThenStorageRead) {
  FrameGraph graph;
  ImageHandle ids = graph.createImage("vbuffer.ids", {VK_FORMAT_R32G32_UINT});
  ImageHandle out = graph.createPersistentImage("gbuffer.out", kColor);
  graph.addPass("vbuffer", QueueKind::Graphics).write(ids, Access::ColorAttachmentWrite);
  graph.addPass("gbuffer", QueueKind::Compute)
      .read(ids, Access::StorageRead)
      .write(out, Access::StorageWrite);
  const FramePlan& plan = graph.compile();

  const Barrier& toAttachment = barrierOf(plan, "vbuffer", "vbuffer.ids");
  EXPECT_EQ(toAttachment.oldLayout, VK_IMAGE_LAYOUT_UNDEFINED);
  EXPECT_EQ(toAttachment.newLayout, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
  EXPECT_EQ(toAttachment.dstStages, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT);

  const Barrier& read = barrierOf(plan, "gbuffer", "vbuffer.ids");
  EXPECT_EQ(read.srcStages, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT);
  EXPECT_EQ(read.srcAccess, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT);  // read bits need no flush
  EXPECT_EQ(read.dstStages, kCompute);
  EXPECT_EQ(read.dstAccess, VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
  EXPECT_EQ(read.oldLayout, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
  EXPECT_EQ(read.newLayout, VK_IMAGE_LAYOUT_GENERAL);
}

TEST(FrameGraph, DepthAttachmentThenSampledInGraphicsPass) {
  FrameGraph graph;
  ImageHandle depth = graph.createImage("depth", {VK_FORMAT_D32_SFLOAT});
  ImageHandle out = graph.createPersistentImage("out", kColor);
  graph.addPass("vbuffer", QueueKind::Graphics).write(depth, Access::DepthAttachmentWrite);
  graph.addPass("forward", QueueKind::Graphics)
      .read(depth, Access::SampledRead)
      .write(out, Access::ColorAttachmentWrite);
  const FramePlan& plan = graph.compile();
  const Barrier& read = barrierOf(plan, "forward", "depth");
  EXPECT_EQ(read.srcStages, VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT |
                                VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT);
  EXPECT_EQ(read.srcAccess, VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT);
  EXPECT_EQ(read.dstStages,
            VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT);
  EXPECT_EQ(read.oldLayout, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL);
  EXPECT_EQ(read.newLayout, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
}

TEST(FrameGraph, ReadsAfterReadsNeedNoBarrierUnlessTheLayoutChanges) {
  FrameGraph graph;
  ImageHandle image = graph.createImage("image", kColor);
  ImageHandle out = graph.createPersistentImage("out", kColor);
  graph.addPass("write", QueueKind::Compute).write(image, Access::StorageWrite);
  graph.addPass("sample-1", QueueKind::Compute)
      .read(image, Access::SampledRead)
      .write(out, Access::StorageReadWrite);
  graph.addPass("sample-2", QueueKind::Compute)
      .read(image, Access::SampledRead)
      .write(out, Access::StorageReadWrite);
  graph.addPass("load", QueueKind::Compute)
      .read(image, Access::StorageRead)
      .write(out, Access::StorageReadWrite);
  const FramePlan& plan = graph.compile();
  EXPECT_TRUE(hasBarrier(plan, "sample-1", "image"));
  EXPECT_FALSE(hasBarrier(plan, "sample-2", "image"));
  const Barrier& relayout = barrierOf(plan, "load", "image");
  EXPECT_EQ(relayout.oldLayout, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
  EXPECT_EQ(relayout.newLayout, VK_IMAGE_LAYOUT_GENERAL);
  EXPECT_EQ(relayout.srcStages & kCompute, kCompute);  // waits for the sampling passes
}

TEST(FrameGraph, BarriersOfOnePassAreMergedIntoOneList) {
  FrameGraph graph;
  ImageHandle a = graph.createImage("a", kColor);
  BufferHandle b = graph.createBuffer("b", kBuffer);
  ImageHandle out = graph.createPersistentImage("out", kColor);
  graph.addPass("produce", QueueKind::Compute)
      .write(a, Access::StorageWrite)
      .write(b, Access::StorageWrite);
  graph.addPass("consume", QueueKind::Compute)
      .read(a, Access::SampledRead)
      .read(b, Access::StorageRead)
      .write(out, Access::StorageWrite);
  const FramePlan& plan = graph.compile();
  const PassPlan* consume = plan.pass("consume");
  ASSERT_NE(consume, nullptr);
  EXPECT_EQ(consume->barriers.size(), 3u);  // a, b, and out's first transition
  EXPECT_TRUE(consume->barrierFor("a")->isImage);
  EXPECT_FALSE(consume->barrierFor("b")->isImage);
}

// Declares the same frame as a renderer would every frame: a TAA-like history pass.
struct HistoryFrame {
  HistoryImage color;
  ImageHandle scratch;
  bool valid = false;
};

HistoryFrame declareHistoryFrame(FrameGraph& graph) {
  graph.beginFrame();
  HistoryFrame f;
  f.scratch = graph.createImage("scratch", kColor);
  f.color = graph.createHistoryImage("taa.color", kColor);
  ImageHandle out = graph.createPersistentImage("out", kColor);
  f.valid = graph.historyValid(f.color);
  graph.addPass("render", QueueKind::Compute).write(f.scratch, Access::StorageWrite);
  graph.addPass("taa", QueueKind::Compute)
      .read(f.scratch, Access::SampledRead)
      .read(f.color.previous, Access::SampledRead)
      .write(f.color.current, Access::StorageWrite);
  graph.addPass("tonemap", QueueKind::Compute)
      .read(f.color.current, Access::StorageRead)
      .write(out, Access::StorageWrite);
  graph.compile();
  return f;
}

TEST(FrameGraph, HistoryPreviousSeesLastFramesLayout) {
  FrameGraph graph;
  HistoryFrame frame0 = declareHistoryFrame(graph);
  EXPECT_FALSE(frame0.valid);
  const Barrier& firstPrevious = barrierOf(graph.plan(), "taa", "taa.color.previous");
  EXPECT_EQ(firstPrevious.oldLayout, VK_IMAGE_LAYOUT_UNDEFINED);
  EXPECT_EQ(firstPrevious.newLayout, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
  graph.endFrame();

  for (int frame = 1; frame <= 2; ++frame) {
    SCOPED_TRACE(frame);
    HistoryFrame f = declareHistoryFrame(graph);
    EXPECT_TRUE(f.valid);
    // Last frame "taa" wrote it (GENERAL) and "tonemap" read it in GENERAL.
    const Barrier& previous = barrierOf(graph.plan(), "taa", "taa.color.previous");
    EXPECT_EQ(previous.oldLayout, VK_IMAGE_LAYOUT_GENERAL);
    EXPECT_EQ(previous.newLayout, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    EXPECT_EQ(previous.srcStages & kCompute, kCompute);
    // The image written now was last frame's `previous`, left SHADER_READ_ONLY.
    const Barrier& current = barrierOf(graph.plan(), "taa", "taa.color");
    EXPECT_EQ(current.oldLayout, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    EXPECT_EQ(current.newLayout, VK_IMAGE_LAYOUT_GENERAL);
    EXPECT_EQ(current.srcAccess, VK_ACCESS_2_NONE);  // only reads to wait for
    // The transient starts from UNDEFINED again, but waits for last frame's reader.
    const Barrier& scratch = barrierOf(graph.plan(), "render", "scratch");
    EXPECT_EQ(scratch.oldLayout, VK_IMAGE_LAYOUT_UNDEFINED);
    EXPECT_EQ(scratch.srcStages, kCompute);
    graph.endFrame();
  }

  graph.resetHistory();
  EXPECT_FALSE(declareHistoryFrame(graph).valid);
  graph.endFrame();
  EXPECT_TRUE(declareHistoryFrame(graph).valid);
}

TEST(FrameGraph, HistorySidesSwapEveryFrame) {
  FrameGraph graph;
  declareHistoryFrame(graph);
  // Both sides' states are committed under their physical keys; the side written in frame 0
  // is the one read as `previous` in frame 1, so its exit state must be GENERAL.
  std::string writtenKey;
  for (const auto& [key, state] : graph.plan().exitStates)
    if (key.rfind("taa.color#", 0) == 0 && state.layout == VK_IMAGE_LAYOUT_GENERAL)
      writtenKey = key;
  ASSERT_FALSE(writtenKey.empty());
  graph.endFrame();
  declareHistoryFrame(graph);
  for (const auto& [key, state] : graph.plan().exitStates)
    if (key == writtenKey)
      EXPECT_EQ(state.layout, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);  // read as previous
}

TEST(FrameGraph, DeclarationsRunAgainWithoutBeginFrame) {
  FrameGraph graph;
  declareHistoryFrame(graph);
  graph.endFrame();
  // Not declared again: the same passes compile against the new states.
  const FramePlan& plan = graph.compile();
  EXPECT_EQ(barrierOf(plan, "taa", "taa.color.previous").oldLayout, VK_IMAGE_LAYOUT_GENERAL);
}

TEST(FrameGraph, UnreadPassesAreCulledSideEffectsKept) {
  FrameGraph graph;
  ImageHandle used = graph.createImage("used", kColor);
  ImageHandle unused = graph.createImage("unused", kColor);
  ImageHandle chain = graph.createImage("chain", kColor);
  ImageHandle chainEnd = graph.createImage("chain-end", kColor);
  ImageHandle overwritten = graph.createImage("overwritten", kColor);
  ImageHandle out = graph.createPersistentImage("out", kColor);
  BufferHandle cache = graph.createPersistentBuffer("cache", kBuffer);
  graph.addPass("produce", QueueKind::Compute).write(used, Access::StorageWrite);
  graph.addPass("orphan", QueueKind::Compute).write(unused, Access::StorageWrite);
  graph.addPass("chain-1", QueueKind::Compute).write(chain, Access::StorageWrite);
  graph.addPass("chain-2", QueueKind::Compute)
      .read(chain, Access::StorageRead)
      .write(chainEnd, Access::StorageWrite);
  graph.addPass("early", QueueKind::Compute).write(overwritten, Access::StorageWrite);
  graph.addPass("late", QueueKind::Compute).write(overwritten, Access::StorageWrite);
  graph.addPass("consume", QueueKind::Compute)
      .read(used, Access::SampledRead)
      .read(overwritten, Access::StorageRead)
      .write(out, Access::StorageWrite);
  graph.addPass("cache-update", QueueKind::Compute).write(cache, Access::StorageReadWrite);
  graph.addPass("stats", QueueKind::Compute).read(used, Access::StorageRead).sideEffects();
  const FramePlan& plan = graph.compile();
  EXPECT_EQ(passNames(plan),
            (std::vector<std::string>{"produce", "late", "consume", "cache-update", "stats"}));
  EXPECT_EQ(plan.culledPasses, (std::vector<std::string>{"orphan", "chain-1", "chain-2", "early"}));
  EXPECT_TRUE(plan.culled("orphan"));
  EXPECT_FALSE(plan.culled("stats"));
  EXPECT_NE(graph.describe().find("culled: orphan"), std::string::npos);
}

TEST(FrameGraph, ReadbackBuffersAreMadeVisibleToTheHost) {
  FrameGraph graph;
  BufferHandle stats =
      graph.createPersistentBuffer("stats", {BufferSize::fixed(256), vk::MemoryUse::Readback});
  graph.addPass("count", QueueKind::Compute).write(stats, Access::StorageWrite);
  const FramePlan& plan = graph.compile();
  ASSERT_EQ(plan.finalBarriers.size(), 1u);
  const Barrier& host = plan.finalBarriers[0].barrier;
  EXPECT_EQ(host.srcStages, kCompute);
  EXPECT_EQ(host.srcAccess, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  EXPECT_EQ(host.dstStages, VK_PIPELINE_STAGE_2_HOST_BIT);
  EXPECT_EQ(host.dstAccess, VK_ACCESS_2_HOST_READ_BIT);
}

TEST(FrameGraph, ImportedImageStartsInItsGivenLayout) {
  FrameGraph graph;
  ImportedImage texture{.image = reinterpret_cast<VkImage>(uintptr_t(0x1000)),
                        .view = reinterpret_cast<VkImageView>(uintptr_t(0x2000)),
                        .format = VK_FORMAT_R8G8B8A8_UNORM,
                        .extent = {4, 4},
                        .layout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
  ImageHandle albedo = graph.importImage("scene.albedo", texture);
  ImageHandle out = graph.createPersistentImage("out", kColor);
  graph.addPass("shade", QueueKind::Compute)
      .read(albedo, Access::SampledRead)
      .write(out, Access::StorageWrite);
  EXPECT_FALSE(hasBarrier(graph.compile(), "shade", "scene.albedo"));  // already readable
}

// An imported image its owner writes between frames (a host's G-buffer): every frame, not only
// the first, starts with a barrier from any earlier write, in the layout the owner gives.
TEST(FrameGraph, ExternallyWrittenImportWaitsForTheOwnerEveryFrame) {
  FrameGraph graph;
  ImportedImage host{.image = reinterpret_cast<VkImage>(uintptr_t(0x10)),
                     .view = reinterpret_cast<VkImageView>(uintptr_t(0x20)),
                     .format = VK_FORMAT_R32_SFLOAT,
                     .extent = {4, 4},
                     .layout = VK_IMAGE_LAYOUT_GENERAL,
                     .externalWrites = true};
  for (int frame = 0; frame < 2; ++frame) {
    SCOPED_TRACE(frame);
    graph.beginFrame();
    ImageHandle depth = graph.importImage("host.depth", host);
    ImageHandle out = graph.createPersistentImage("out", kColor);
    graph.addPass("import", QueueKind::Compute)
        .read(depth, Access::StorageRead)
        .write(out, Access::StorageWrite);
    const Barrier& b = barrierOf(graph.compile(), "import", "host.depth");
    EXPECT_EQ(b.srcStages, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT);
    EXPECT_EQ(b.srcAccess, VK_ACCESS_2_MEMORY_WRITE_BIT);
    EXPECT_EQ(b.dstStages, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
    EXPECT_EQ(b.oldLayout, VK_IMAGE_LAYOUT_GENERAL);
    EXPECT_EQ(b.newLayout, VK_IMAGE_LAYOUT_GENERAL);
    graph.endFrame();
  }
}

TEST(FrameGraph, DebugViewCopiesRightAfterThePassAndKeepsItAlive) {
  FrameGraph graph;
  ImageHandle normal = graph.createImage("gbuffer.normal", kColor);
  ImageHandle out = graph.createPersistentImage("out", kColor);
  graph.addPass("gbuffer", QueueKind::Compute).write(normal, Access::StorageWrite);
  graph.addPass("composite", QueueKind::Compute).write(out, Access::StorageWrite);
  EXPECT_TRUE(graph.compile().culled("gbuffer"));  // nobody reads the normals

  graph.requestDebugView("gbuffer");
  graph.requestDebugView("out");
  const FramePlan& plan = graph.compile();
  EXPECT_EQ(passNames(plan), (std::vector<std::string>{"gbuffer", "debug-view:gbuffer", "composite",
                                                       "debug-view:out"}));
  const Barrier& copy = barrierOf(plan, "debug-view:gbuffer", "gbuffer.normal");
  EXPECT_EQ(copy.newLayout, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
  EXPECT_EQ(copy.dstStages, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT);
  EXPECT_EQ(plan.finalBarriers.size(), 2u);  // both readbacks, for the host

  graph.clearDebugViews();
  EXPECT_TRUE(graph.compile().culled("gbuffer"));
}

// ---- errors -----------------------------------------------------------------------------------

TEST(FrameGraphErrors, ReadingAnUnwrittenTransientNamesPassAndResource) {
  expectError(
      [] {
        FrameGraph graph;
        ImageHandle noise = graph.createImage("blue-noise", kColor);
        ImageHandle out = graph.createPersistentImage("out", kColor);
        graph.addPass("shadows-trace", QueueKind::Compute)
            .read(noise, Access::SampledRead)
            .write(out, Access::StorageWrite);
        graph.compile();
      },
      {"shadows-trace", "blue-noise", "no pass writes it"});

  expectError(
      [] {
        FrameGraph graph;
        ImageHandle noise = graph.createImage("blue-noise", kColor);
        ImageHandle out = graph.createPersistentImage("out", kColor);
        graph.addPass("shadows-trace", QueueKind::Compute)
            .read(noise, Access::SampledRead)
            .write(out, Access::StorageWrite);
        graph.addPass("noise-gen", QueueKind::Compute).write(noise, Access::StorageWrite);
        graph.compile();
      },
      {"shadows-trace", "blue-noise", "noise-gen", "declared later"});
}

TEST(FrameGraphErrors, DuplicateNames) {
  expectError(
      [] {
        FrameGraph graph;
        graph.addPass("gbuffer", QueueKind::Compute);
        graph.addPass("gbuffer", QueueKind::Compute);
      },
      {"pass 'gbuffer' declared twice"});
  expectError(
      [] {
        FrameGraph graph;
        (void)graph.createImage("depth", kColor);
        (void)graph.createBuffer("depth", kBuffer);
      },
      {"resource 'depth' declared twice"});
}

TEST(FrameGraphErrors, UnknownDebugViewListsValidNames) {
  FrameGraph graph;
  ImageHandle out = graph.createPersistentImage("out", kColor);
  graph.addPass("tonemap", QueueKind::Compute).write(out, Access::StorageWrite);
  graph.requestDebugView("tonemapp");
  expectError([&] { graph.compile(); }, {"tonemapp", "passes: tonemap", "resources: out"});
  EXPECT_NO_THROW(graph.compile());  // the misspelt request was dropped
}

TEST(FrameGraphErrors, BadAccessDeclarations) {
  FrameGraph graph;
  ImageHandle image = graph.createImage("image", kColor);
  BufferHandle buffer = graph.createBuffer("buffer", kBuffer);
  HistoryImage history = graph.createHistoryImage("history", kColor);
  expectError([&] { graph.addPass("a", QueueKind::Compute).read(image, Access::StorageWrite); },
              {"'a'", "StorageWrite", "use write()"});
  expectError(
      [&] { graph.addPass("b", QueueKind::Compute).write(buffer, Access::ColorAttachmentWrite); },
      {"'b'", "ColorAttachmentWrite", "buffer 'buffer'"});
  expectError(
      [&] {
        graph.addPass("c", QueueKind::Compute)
            .write(image, Access::StorageWrite)
            .write(image, Access::StorageWrite);
      },
      {"'c'", "'image' twice"});
  expectError(
      [&] { graph.addPass("d", QueueKind::Compute).write(history.previous, Access::StorageWrite); },
      {"'d'", "history.previous", "read-only"});
}

// One image, one binding, except for a placeholder: an image bound only to fill a binding the
// shader ignores in this configuration, which may repeat an image but not a binding.
TEST(FrameGraphErrors, BindingsAndPlaceholders) {
  FrameGraph graph;
  ImageHandle image = graph.createImage("image", kColor);
  ImageHandle other = graph.createImage("other", kColor);
  expectError(
      [&] {
        graph.addPass("a", QueueKind::Compute)
            .read(image, Access::StorageRead, 0)
            .read(image, Access::StorageRead, 1);
      },
      {"'a'", "'image' twice", "bindings 0 and 1"});
  expectError(
      [&] {
        graph.addPass("b", QueueKind::Compute)
            .read(image, Access::StorageRead, 0)
            .read(other, Access::StorageRead, 0);
      },
      {"'b'", "'image' and 'other' both at binding 0"});
  EXPECT_NO_THROW(graph.addPass("c", QueueKind::Compute)
                      .read(image, Access::StorageRead, 0)
                      .readPlaceholder(image, 1));
  expectError(
      [&] {
        graph.addPass("d", QueueKind::Compute)
            .read(image, Access::StorageRead, 0)
            .readPlaceholder(other, 0);
      },
      {"'d'", "placeholder 'other'", "binding 0"});
  // A sampled binding's placeholder is a SampledRead, merged with the pass's sampled read of
  // the image; a placeholder cannot write, and a storage placeholder of an image the pass
  // samples would need two layouts at once.
  EXPECT_NO_THROW(graph.addPass("e", QueueKind::Compute)
                      .read(image, Access::SampledRead, 0)
                      .readPlaceholder(image, 1, Access::SampledRead));
  expectError(
      [&] {
        graph.addPass("f", QueueKind::Compute)
            .read(image, Access::SampledRead, 0)
            .readPlaceholder(other, 1, Access::StorageWrite);
      },
      {"'f'", "placeholder 'other'", "binding 1", "StorageRead or SampledRead"});
  expectError(
      [&] {
        graph.addPass("g", QueueKind::Compute)
            .read(image, Access::SampledRead, 0)
            .readPlaceholder(image, 1);
      },
      {"'g'", "'image'"});
}

TEST(FrameGraphErrors, HistoryNobodyWrites) {
  expectError(
      [] {
        FrameGraph graph;
        HistoryImage history = graph.createHistoryImage("gi.reservoirs", kColor);
        ImageHandle out = graph.createPersistentImage("out", kColor);
        graph.addPass("gi-restir-temporal", QueueKind::Compute)
            .read(history.previous, Access::StorageRead)
            .write(out, Access::StorageWrite);
        graph.compile();
      },
      {"gi.reservoirs", "no pass writes it"});
}

TEST(FrameGraphErrors, ExecuteWithoutAllocate) {
  FrameGraph graph;
  expectError([&] { graph.execute(VK_NULL_HANDLE); }, {"allocate()"});
}

TEST(FrameGraph, DebugViewTexelsBecomeAnImage) {
  DebugView view{.name = "shadows-trace",
                 .resource = "shadows",
                 .isImage = true,
                 .format = VK_FORMAT_R32_SFLOAT,
                 .width = 2,
                 .height = 1,
                 .layers = 1};
  float texels[2] = {0.25f, 4.0f};
  view.bytes.resize(sizeof(texels));
  std::memcpy(view.bytes.data(), texels, sizeof(texels));
  ImageRGBA32F image = debugViewImage(view);
  ASSERT_EQ(image.width, 2);
  EXPECT_EQ(image.at(0, 0), glm::vec4(0.25f, 0.25f, 0.25f, 1.0f));
  EXPECT_EQ(image.at(1, 0), glm::vec4(4.0f, 4.0f, 4.0f, 1.0f));
  view.format = VK_FORMAT_BC1_RGB_UNORM_BLOCK;
  expectError([&] { debugViewImage(view); }, {"shadows-trace"});
}

}  // namespace
}  // namespace bounce::graph
