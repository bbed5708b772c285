// The clipmap cache's passes on the frame graph, in frame order (clipmap_cache.h).
#include <cstddef>
#include <string>

#include <fmt/format.h>

#include "gi/evolve/cache/clipmap_cache.h"

namespace bounce {

using graph::Access;
using graph::QueueKind;

namespace {

constexpr uint32_t kTotalSlots = gpu::CLIPMAP_CASCADES * gpu::CLIPMAP_SLOTS_PER_CASCADE;

uint32_t groupsFor(uint32_t items) {
  return (items + gpu::CLIPMAP_GROUP_SIZE - 1) / gpu::CLIPMAP_GROUP_SIZE;
}

}  // namespace

void ClipmapCache::declareUpdate(graph::FrameGraph& graph, const GiInputs& inputs) {
  importBuffers(graph);
  // Declaring changes no state: a frame may be declared and never run (the pass and resource
  // names for --view), so the pending reset and the refresh countdown advance in afterFrame().
  if (resetPending_) declareReset(graph);
  constantsData_ = makeConstants(inputs);
  const uint32_t bounces = fullRefreshLeft_ > 0 ? settings_.fullRefreshBounces : 1u;
  gpu::ClipmapPassConstants push{};
  push.cache = constants_.address();
  push.frame = inputs.frame.constantsAddress;
  push.buffers = addresses();
  push.maxStaleFrames = settings_.maxStaleFrames;
  declareLifetimes(graph, push);
  declareClipmap(graph, push);
  // A full refresh's extra bounces repeat the pair (ClipmapCacheSettings::fullRefreshBounces).
  for (uint32_t bounce = 0; bounce < bounces; ++bounce) {
    gpu::ClipmapPassConstants bouncePush = push;
    bouncePush.bounce = bounce;
    declareTraceAndBuildSh(graph, inputs, bouncePush);
  }
  declareDebugViews(graph, inputs, push);
}

void ClipmapCache::importBuffers(graph::FrameGraph& graph) {
  using graph::ImportedBuffer;
  CacheBuffers& b = handles_;
  b.constants = graph.importBuffer("cache.constants", ImportedBuffer::from(constants_));
  b.grid = graph.importBuffer("cache.grid", ImportedBuffer::from(grid_));
  b.cells = graph.importBuffer("cache.cells", ImportedBuffer::from(cells_));
  b.entries = graph.importBuffer("cache.entries", ImportedBuffer::from(entries_));
  b.pool = graph.importBuffer("cache.pool", ImportedBuffer::from(pool_));
  b.counters = graph.importBuffer("cache.counters", ImportedBuffer::from(counters_));
  b.frame = graph.importBuffer("cache.frame-counters", ImportedBuffer::from(frame_));
  b.liveList = graph.importBuffer("cache.live-list", ImportedBuffer::from(liveList_));
  b.votes = graph.importBuffer("cache.votes", ImportedBuffer::from(votes_));
}

// An empty cache: no cell in the grid, every cell dead, the pool the identity list, no votes.
void ClipmapCache::declareReset(graph::FrameGraph& graph) {
  const CacheBuffers b = handles_;
  graph.addPass("cache-reset", QueueKind::Compute)
      .write(b.grid, Access::TransferDst)
      .write(b.cells, Access::TransferDst)
      .write(b.pool, Access::TransferDst)
      .write(b.counters, Access::TransferDst)
      .write(b.votes, Access::TransferDst)
      .sideEffects()
      .record([b](VkCommandBuffer cmd, const graph::PassResources& r) {
        for (graph::BufferHandle h : {b.grid, b.cells, b.pool, b.counters, b.votes})
          vkCmdFillBuffer(cmd, r.buffer(h).buffer, 0, VK_WHOLE_SIZE, 0u);
      });
}

// cache-update-lifetimes: uploads this frame's constants and zeroes the frame counters first.
void ClipmapCache::declareLifetimes(graph::FrameGraph& graph,
                                    const gpu::ClipmapPassConstants& push) {
  const CacheBuffers b = handles_;
  gpu::ClipmapFrameCounters frameStart{};
  frameStart.traceDispatch = {0u, 1u, 1u};
  frameStart.rayDispatch = {0u, 1u, 1u};
  const gpu::ClipmapCacheConstants constants = constantsData_;
  graph.addPass("cache-update-lifetimes", QueueKind::Compute)
      .write(b.constants, Access::TransferDst)
      .write(b.frame, Access::TransferDst)
      .write(b.cells, Access::StorageReadWrite)
      .write(b.grid, Access::StorageReadWrite)
      .write(b.pool, Access::StorageReadWrite)
      .write(b.counters, Access::StorageReadWrite)
      .read(b.votes, Access::StorageRead)
      .sideEffects()
      .record([this, b, push, frameStart, constants](VkCommandBuffer cmd,
                                                     const graph::PassResources& r) {
        vkCmdUpdateBuffer(cmd, r.buffer(b.constants).buffer, 0, sizeof(constants), &constants);
        vkCmdUpdateBuffer(cmd, r.buffer(b.frame).buffer, 0, sizeof(frameStart), &frameStart);
        lifetimes_.bind(cmd, push, r);
        vkCmdDispatch(cmd, groupsFor(gpu::CLIPMAP_MAX_CELLS), 1, 1);
      });
}

void ClipmapCache::declareClipmap(graph::FrameGraph& graph, const gpu::ClipmapPassConstants& push) {
  const CacheBuffers b = handles_;
  graph.addPass("cache-update-clipmap", QueueKind::Compute)
      .read(b.constants, Access::StorageRead)
      .write(b.frame, Access::StorageReadWrite)
      .write(b.liveList, Access::StorageWrite)
      .write(b.cells, Access::StorageReadWrite)
      .write(b.grid, Access::StorageReadWrite)
      .write(b.pool, Access::StorageReadWrite)
      .write(b.counters, Access::StorageReadWrite)
      .write(b.votes, Access::StorageReadWrite)
      .sideEffects()
      .record([this, push](VkCommandBuffer cmd, const graph::PassResources& r) {
        clipmap_.bind(cmd, push, r);
        vkCmdDispatch(cmd, groupsFor(kTotalSlots), 1, 1);
      });
}

// cache-trace-diffuse-rays and cache-build-sh for bounce `push.bounce` (suffixed -bounce-N
// after the first).
void ClipmapCache::declareTraceAndBuildSh(graph::FrameGraph& graph, const GiInputs& inputs,
                                          const gpu::ClipmapPassConstants& push) {
  const CacheBuffers b = handles_;
  const std::string suffix = push.bounce == 0 ? "" : fmt::format("-bounce-{}", push.bounce + 1);
  declareLookup(graph.addPass("cache-trace-diffuse-rays" + suffix, QueueKind::Compute))
      .read(b.frame, Access::StorageRead)
      .read(b.frame, Access::IndirectRead)
      .read(b.liveList, Access::StorageRead)
      .read(inputs.frame.constants, Access::StorageRead)
      .read(inputs.frame.instances, Access::StorageRead)
      .read(inputs.frame.tlas, Access::StorageRead)
      .sideEffects()
      .record([this, b, push](VkCommandBuffer cmd, const graph::PassResources& r) {
        trace_.bind(cmd, push, r);
        vkCmdDispatchIndirect(cmd, r.buffer(b.frame).buffer,
                              offsetof(gpu::ClipmapFrameCounters, rayDispatch));
      });
  graph.addPass("cache-build-sh" + suffix, QueueKind::Compute)
      .read(b.frame, Access::StorageRead)
      .read(b.frame, Access::IndirectRead)
      .read(b.liveList, Access::StorageRead)
      .read(b.entries, Access::StorageRead)
      .write(b.cells, Access::StorageReadWrite)
      .sideEffects()
      .record([this, b, push](VkCommandBuffer cmd, const graph::PassResources& r) {
        buildSh_.bind(cmd, push, r);
        vkCmdDispatchIndirect(cmd, r.buffer(b.frame).buffer, 0);
      });
}

graph::PassBuilder ClipmapCache::declareLookup(graph::PassBuilder pass) const {
  return pass.read(handles_.constants, Access::StorageRead)
      .write(handles_.grid, Access::StorageReadWrite)
      .write(handles_.cells, Access::StorageReadWrite)
      .write(handles_.entries, Access::StorageReadWrite)
      .write(handles_.pool, Access::StorageReadWrite)
      .write(handles_.counters, Access::StorageReadWrite)
      .write(handles_.votes, Access::StorageReadWrite);
}

// `cache` (cells shaded with their irradiance) and `cache.live-cells`; culled unless requested.
void ClipmapCache::declareDebugViews(graph::FrameGraph& graph, const GiInputs& inputs,
                                     const gpu::ClipmapPassConstants& push) {
  const CacheBuffers b = handles_;
  constexpr VkFormat rgba16f = VK_FORMAT_R16G16B16A16_SFLOAT;
  graph::ImageHandle view = graph.createImage("cache", {rgba16f});
  const VkExtent2D extent = inputs.frame.resolution;
  const GBuffer& g = inputs.gbuffer;
  graph.addPass("cache-debug", QueueKind::Compute)
      .read(b.constants, Access::StorageRead)
      .read(b.grid, Access::StorageRead)
      .read(b.cells, Access::StorageRead)
      .read(inputs.frame.constants, Access::StorageRead)
      .read(g.normals, Access::StorageRead, gpu::CACHE_LOOKUP_BINDING_NORMALS)
      .read(g.depth.current, Access::StorageRead, gpu::CACHE_LOOKUP_BINDING_DEPTH)
      .read(g.flags, Access::StorageRead, gpu::CACHE_LOOKUP_BINDING_FLAGS)
      .write(view, Access::StorageWrite, gpu::CACHE_LOOKUP_BINDING_OUTPUT)
      .record([this, push, extent](VkCommandBuffer cmd, const graph::PassResources& r) {
        debugView_.bind(cmd, push, r);
        vk::ComputePipeline::dispatchCovering(cmd, extent.width, extent.height,
                                              gpu::HYBRID_GROUP_SIZE, gpu::HYBRID_GROUP_SIZE);
      });
  constexpr uint32_t barsHeight = gpu::CLIPMAP_LIVE_VIEW_BAR * gpu::CLIPMAP_CASCADES;
  graph::ImageHandle bars = graph.createImage(
      "cache.live-cells",
      {rgba16f, graph::ImageSize::fixed(gpu::CLIPMAP_LIVE_VIEW_WIDTH, barsHeight)});
  graph.addPass("cache-live-cells-view", QueueKind::Compute)
      .read(b.frame, Access::StorageRead)
      .write(bars, Access::StorageWrite, gpu::CACHE_LIVE_VIEW_BINDING_OUTPUT)
      .record([this, push](VkCommandBuffer cmd, const graph::PassResources& r) {
        liveCellsView_.bind(cmd, push, r);
        vk::ComputePipeline::dispatchCovering(cmd, gpu::CLIPMAP_LIVE_VIEW_WIDTH, barsHeight, 8, 8);
      });
}

}  // namespace bounce
