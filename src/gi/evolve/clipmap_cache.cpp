#include "gi/evolve/clipmap_cache.h"

#include <cstddef>

#include <cmath>
#include <cstring>

#include "core/error.h"

namespace bounce {

namespace {

using graph::Access;
using graph::QueueKind;

constexpr VkBufferUsageFlags kStorage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT |
                                        VK_BUFFER_USAGE_TRANSFER_DST_BIT |
                                        VK_BUFFER_USAGE_TRANSFER_SRC_BIT;
constexpr uint32_t kTotalSlots = gpu::CLIPMAP_CASCADES * gpu::CLIPMAP_SLOTS_PER_CASCADE;

uint32_t groupsFor(uint32_t items) {
  return (items + gpu::CLIPMAP_GROUP_SIZE - 1) / gpu::CLIPMAP_GROUP_SIZE;
}

vk::Buffer deviceBuffer(vk::Context& context, VkDeviceSize bytes, const std::string& name,
                        VkBufferUsageFlags extra = 0) {
  return vk::Buffer(context, bytes, kStorage | extra, vk::MemoryUse::DeviceOnly, name);
}

void checkSettings(const ClipmapCacheSettings& s) {
  bool power = s.raysPerCell > 0 && s.raysPerCell <= gpu::CLIPMAP_ENTRIES &&
               (s.raysPerCell & (s.raysPerCell - 1)) == 0;
  if (!power)
    fail("clipmap cache: {} rays per cell; expected 1, 2, 4, 8 or 16", s.raysPerCell);
  if (s.validationRaysPerCell > s.raysPerCell)
    fail("clipmap cache: {} validation rays per cell; at most the {} rays per cell",
         s.validationRaysPerCell, s.raysPerCell);
  if (!(s.finestCellSize > 0.0f) || !std::isfinite(s.finestCellSize))
    fail("clipmap cache: finest cell size {} m must be positive", s.finestCellSize);
  if (!(s.historyCap >= 1.0f)) fail("clipmap cache: history cap {} must be >= 1", s.historyCap);
  if (!(s.fullRefreshHistoryCap >= 0.0f) || !std::isfinite(s.fullRefreshHistoryCap))
    fail("clipmap cache: full-refresh history cap {} must be >= 0", s.fullRefreshHistoryCap);
  if (s.fullRefreshBounces < 1 || s.fullRefreshBounces > 8)
    fail("clipmap cache: full-refresh bounces {} must be in [1, 8]", s.fullRefreshBounces);
  if (s.maxStaleFrames < 1) fail("clipmap cache: max stale frames must be >= 1");
  if (s.maxLiveCells < 1 || s.maxLiveCells > gpu::CLIPMAP_MAX_CELLS)
    fail("clipmap cache: {} live cells at most; expected 1 to {}", s.maxLiveCells,
         gpu::CLIPMAP_MAX_CELLS);
}

}  // namespace

ClipmapCache::ClipmapCache(vk::Context& context, const GpuScene& gpuScene,
                           const GpuLightTables& lights, const ClipmapCacheSettings& settings)
    : context_(context),
      lights_(lights),
      settings_((checkSettings(settings), settings)),
      constants_(deviceBuffer(context, sizeof(gpu::ClipmapCacheConstants), "cache.constants")),
      grid_(deviceBuffer(context, kTotalSlots * sizeof(uint32_t), "cache.grid")),
      cells_(deviceBuffer(context, gpu::CLIPMAP_MAX_CELLS * sizeof(gpu::ClipmapCell),
                          "cache.cells")),
      entries_(deviceBuffer(context,
                            VkDeviceSize(gpu::CLIPMAP_MAX_CELLS) * gpu::CLIPMAP_ENTRIES *
                                sizeof(gpu::ClipmapEntry),
                            "cache.entries")),
      pool_(deviceBuffer(context, gpu::CLIPMAP_MAX_CELLS * sizeof(uint32_t), "cache.pool")),
      counters_(deviceBuffer(context, sizeof(gpu::ClipmapCounters), "cache.counters")),
      frame_(deviceBuffer(context, sizeof(gpu::ClipmapFrameCounters), "cache.frame-counters",
                          VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT)),
      liveList_(deviceBuffer(context, 2 * gpu::CLIPMAP_MAX_CELLS * sizeof(uint32_t),
                             "cache.live-list")),
      readback_(context, sizeof(gpu::ClipmapCounters) + sizeof(gpu::ClipmapFrameCounters),
                VK_BUFFER_USAGE_TRANSFER_DST_BIT, vk::MemoryUse::Readback, "cache.statistics"),
      lifetimes_(context, gpuScene, "gi/evolve/cache_update_lifetimes", 0,
                 sizeof(gpu::ClipmapPassConstants)),
      clipmap_(context, gpuScene, "gi/evolve/cache_update_clipmap", 0,
               sizeof(gpu::ClipmapPassConstants)),
      trace_(context, gpuScene, "gi/evolve/cache_trace_diffuse_rays", 0,
             sizeof(gpu::ClipmapPassConstants)),
      buildSh_(context, gpuScene, "gi/evolve/cache_build_sh", 0,
               sizeof(gpu::ClipmapPassConstants)),
      debugView_(context, gpuScene, "gi/evolve/cache_debug", gpu::CACHE_LOOKUP_IMAGES,
                 sizeof(gpu::ClipmapPassConstants)),
      liveCellsView_(context, gpuScene, "gi/evolve/cache_live_cells_view", 1,
                     sizeof(gpu::ClipmapPassConstants)) {
  std::memset(readback_.mapped(), 0, readback_.size());
  beginFullRefresh();  // the cache starts empty: a reset
}

gpu::ClipmapCacheAddresses ClipmapCache::addresses() const {
  return {grid_.address(),     cells_.address(),   entries_.address(), pool_.address(),
          counters_.address(), frame_.address(),   liveList_.address()};
}

// Cascade c's window is the 32^3 cells of side finestCellSize * 2^c centred on the cell that
// holds the camera; it moves by whole cells, so cells inside both windows keep their slot.
gpu::ClipmapCacheConstants ClipmapCache::makeConstants(const GiInputs& inputs) const {
  gpu::ClipmapCacheConstants c{};
  c.buffers = addresses();
  c.lights = lights_.address();
  glm::vec3 camera = inputs.frame.hostConstants ? inputs.frame.hostConstants->camera.position : glm::vec3(0.0f);
  for (uint32_t cascade = 0; cascade < gpu::CLIPMAP_CASCADES; ++cascade) {
    float cell = settings_.finestCellSize * float(1u << cascade);
    glm::ivec3 centre = glm::ivec3(glm::floor(camera / cell));
    c.cascadeOrigin[cascade] = glm::ivec4(centre - int(gpu::CLIPMAP_GRID / 2), 0);
  }
  c.cameraPosition = camera;
  c.finestCellSize = settings_.finestCellSize;
  c.frameIndex = inputs.frame.hostConstants ? inputs.frame.hostConstants->frameIndex : uint32_t(frames_);
  c.raysPerCell = settings_.raysPerCell;
  c.validationRaysPerCell = settings_.validationRaysPerCell;
  c.flags = settings_.alphaTest ? gpu::CLIPMAP_FLAG_ALPHA_TEST : 0u;
  c.historyCap = settings_.historyCap;
  c.maxStaleFrames = settings_.maxStaleFrames;
  c.poolCapacity = settings_.maxLiveCells;
  c.materialTextureSide = settings_.materialTextureSide;
  c.fullRefresh = fullRefreshLeft_ > 0 ? 1u : 0u;
  c.fullRefreshHistoryCap = settings_.fullRefreshHistoryCap;
  return c;
}

void ClipmapCache::declareUpdate(graph::FrameGraph& graph, const GiInputs& inputs) {
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
  ++frames_;

  // An empty cache: no cell in the grid, every cell dead, the pool the identity list.
  if (resetPending_) {
    resetPending_ = false;
    graph.addPass("cache-reset", QueueKind::Compute)
        .write(b.grid, Access::TransferDst)
        .write(b.cells, Access::TransferDst)
        .write(b.pool, Access::TransferDst)
        .write(b.counters, Access::TransferDst)
        .sideEffects()
        .record([=](VkCommandBuffer cmd, const graph::PassResources& r) {
          for (graph::BufferHandle h : {b.grid, b.cells, b.pool, b.counters})
            vkCmdFillBuffer(cmd, r.buffer(h).buffer, 0, VK_WHOLE_SIZE, 0u);
        });
  }

  constantsData_ = makeConstants(inputs);
  const uint32_t bounces = fullRefreshLeft_ > 0 ? settings_.fullRefreshBounces : 1u;
  if (fullRefreshLeft_ > 0) --fullRefreshLeft_;
  gpu::ClipmapPassConstants push{};
  push.cache = constants_.address();
  push.frame = inputs.frame.constantsAddress;
  push.buffers = addresses();
  push.maxStaleFrames = settings_.maxStaleFrames;
  gpu::ClipmapFrameCounters frameStart{};
  frameStart.traceDispatch = {0u, 1u, 1u};
  frameStart.rayDispatch = {0u, 1u, 1u};
  gpu::ClipmapCacheConstants constants = constantsData_;

  graph.addPass("cache-update-lifetimes", QueueKind::Compute)
      .write(b.constants, Access::TransferDst)
      .write(b.frame, Access::TransferDst)
      .write(b.cells, Access::StorageReadWrite)
      .write(b.grid, Access::StorageReadWrite)
      .write(b.pool, Access::StorageReadWrite)
      .write(b.counters, Access::StorageReadWrite)
      .sideEffects()
      .record([=, this](VkCommandBuffer cmd, const graph::PassResources& r) {
        vkCmdUpdateBuffer(cmd, r.buffer(b.constants).buffer, 0, sizeof(constants), &constants);
        vkCmdUpdateBuffer(cmd, r.buffer(b.frame).buffer, 0, sizeof(frameStart), &frameStart);
        lifetimes_.bind(cmd, push);
        vkCmdDispatch(cmd, groupsFor(gpu::CLIPMAP_MAX_CELLS), 1, 1);
      });
  graph.addPass("cache-update-clipmap", QueueKind::Compute)
      .read(b.constants, Access::StorageRead)
      .write(b.frame, Access::StorageReadWrite)
      .write(b.liveList, Access::StorageWrite)
      .write(b.cells, Access::StorageReadWrite)
      .write(b.grid, Access::StorageReadWrite)
      .write(b.pool, Access::StorageReadWrite)
      .write(b.counters, Access::StorageReadWrite)
      .sideEffects()
      .record([=, this](VkCommandBuffer cmd, const graph::PassResources&) {
        clipmap_.bind(cmd, push);
        vkCmdDispatch(cmd, groupsFor(kTotalSlots), 1, 1);
      });
  // A full refresh's extra bounces repeat the pair (ClipmapCacheSettings::fullRefreshBounces).
  for (uint32_t bounce = 0; bounce < bounces; ++bounce) {
    const std::string suffix = bounce == 0 ? "" : fmt::format("-bounce-{}", bounce + 1);
    gpu::ClipmapPassConstants bouncePush = push;
    bouncePush.bounce = bounce;
    declareLookup(graph.addPass("cache-trace-diffuse-rays" + suffix, QueueKind::Compute))
        .read(b.frame, Access::StorageRead)
        .read(b.frame, Access::IndirectRead)
        .read(b.liveList, Access::StorageRead)
        .read(inputs.frame.constants, Access::StorageRead)
        .read(inputs.frame.instances, Access::StorageRead)
        .read(inputs.frame.tlas, Access::StorageRead)
        .sideEffects()
        .record([=, this](VkCommandBuffer cmd, const graph::PassResources& r) {
          trace_.bind(cmd, bouncePush);
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
        .record([=, this](VkCommandBuffer cmd, const graph::PassResources& r) {
          buildSh_.bind(cmd, bouncePush);
          vkCmdDispatchIndirect(cmd, r.buffer(b.frame).buffer, 0);
        });
  }

  // Debug views; culled unless requested.
  constexpr VkFormat rgba16f = VK_FORMAT_R16G16B16A16_SFLOAT;
  graph::ImageHandle view = graph.createImage("cache", {rgba16f});
  VkExtent2D extent = inputs.frame.resolution;
  graph.addPass("cache-debug", QueueKind::Compute)
      .read(b.constants, Access::StorageRead)
      .read(b.grid, Access::StorageRead)
      .read(b.cells, Access::StorageRead)
      .read(inputs.frame.constants, Access::StorageRead)
      .read(inputs.gbuffer.normals, Access::StorageRead)
      .read(inputs.gbuffer.depth.current, Access::StorageRead)
      .read(inputs.gbuffer.flags, Access::StorageRead)
      .write(view, Access::StorageWrite)
      .record([=, this](VkCommandBuffer cmd, const graph::PassResources& r) {
        debugView_.bind(cmd, push,
                        {{gpu::CACHE_LOOKUP_BINDING_NORMALS, r.image(inputs.gbuffer.normals)},
                         {gpu::CACHE_LOOKUP_BINDING_DEPTH, r.image(inputs.gbuffer.depth.current)},
                         {gpu::CACHE_LOOKUP_BINDING_FLAGS, r.image(inputs.gbuffer.flags)},
                         {gpu::CACHE_LOOKUP_BINDING_OUTPUT, r.image(view)}});
        vk::ComputePipeline::dispatchCovering(cmd, extent.width, extent.height,
                                              gpu::HYBRID_GROUP_SIZE, gpu::HYBRID_GROUP_SIZE);
      });
  constexpr uint32_t barsHeight = gpu::CLIPMAP_LIVE_VIEW_BAR * gpu::CLIPMAP_CASCADES;
  graph::ImageHandle bars = graph.createImage(
      "cache.live-cells",
      {rgba16f, graph::ImageSize::fixed(gpu::CLIPMAP_LIVE_VIEW_WIDTH, barsHeight)});
  graph.addPass("cache-live-cells-view", QueueKind::Compute)
      .read(b.frame, Access::StorageRead)
      .write(bars, Access::StorageWrite)
      .record([=, this](VkCommandBuffer cmd, const graph::PassResources& r) {
        liveCellsView_.bind(cmd, push, {{0u, r.image(bars)}});
        vk::ComputePipeline::dispatchCovering(cmd, gpu::CLIPMAP_LIVE_VIEW_WIDTH, barsHeight, 8, 8);
      });
}

graph::PassBuilder ClipmapCache::declareLookup(graph::PassBuilder pass) const {
  return pass.read(handles_.constants, graph::Access::StorageRead)
      .write(handles_.grid, graph::Access::StorageReadWrite)
      .write(handles_.cells, graph::Access::StorageReadWrite)
      .write(handles_.entries, graph::Access::StorageReadWrite)
      .write(handles_.pool, graph::Access::StorageReadWrite)
      .write(handles_.counters, graph::Access::StorageReadWrite);
}

void ClipmapCache::declareStatisticsReadback(graph::FrameGraph& graph) {
  CacheBuffers b = handles_;
  graph::BufferHandle readback = graph.importBuffer(
      "cache.statistics", graph::ImportedBuffer::from(readback_));
  graph.addPass("cache-read-statistics", QueueKind::Compute)
      .read(b.counters, Access::TransferSrc)
      .read(b.frame, Access::TransferSrc)
      .write(readback, Access::TransferDst)
      .sideEffects()
      .record([=](VkCommandBuffer cmd, const graph::PassResources& r) {
        VkBufferCopy counters{0, 0, sizeof(gpu::ClipmapCounters)};
        VkBufferCopy frame{0, sizeof(gpu::ClipmapCounters), sizeof(gpu::ClipmapFrameCounters)};
        vkCmdCopyBuffer(cmd, r.buffer(b.counters).buffer, r.buffer(readback).buffer, 1, &counters);
        vkCmdCopyBuffer(cmd, r.buffer(b.frame).buffer, r.buffer(readback).buffer, 1, &frame);
      });
}

void ClipmapCache::afterFrame() {
  previous_ = last_;
  const auto* bytes = static_cast<const std::byte*>(readback_.mapped());
  std::memcpy(&last_.counters, bytes, sizeof(last_.counters));
  std::memcpy(&last_.frame, bytes + sizeof(last_.counters), sizeof(last_.frame));
  haveSnapshot_ = true;
}

std::vector<GiStatistic> ClipmapCache::statistics() const {
  if (!haveSnapshot_) return {};
  // Totals restart at zero after a reset; a total below the last one means exactly that.
  auto delta = [](uint32_t now, uint32_t before) { return double(now >= before ? now - before : now); };
  std::vector<GiStatistic> out;
  out.push_back({"cache.live-cells", double(last_.counters.allocated)});
  out.push_back({"cache.allocations",
                 delta(last_.counters.allocationsTotal, previous_.counters.allocationsTotal)});
  out.push_back({"cache.frees", delta(last_.counters.freesTotal, previous_.counters.freesTotal)});
  out.push_back({"cache.frees-by-scrolling", double(last_.frame.scrollFrees)});
  out.push_back({"cache.allocation-failures",
                 delta(last_.counters.allocationFailures, previous_.counters.allocationFailures)});
  for (uint32_t c = 0; c < gpu::CLIPMAP_CASCADES; ++c)
    out.push_back({"cache.live-cells.cascade-" + std::to_string(c),
                   double(last_.frame.liveCells[c])});
  return out;
}

}  // namespace bounce
