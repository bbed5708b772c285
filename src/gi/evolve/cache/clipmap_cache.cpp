#include "gi/evolve/cache/clipmap_cache.h"

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

vk::Buffer deviceBuffer(vk::Context& context, VkDeviceSize bytes, const std::string& name,
                        VkBufferUsageFlags extra = 0) {
  return vk::Buffer(context, bytes, kStorage | extra, vk::MemoryUse::DeviceOnly, name);
}

}  // namespace

void validate(const ClipmapCacheSettings& s) {
  bool power = s.raysPerCell > 0 && s.raysPerCell <= gpu::CLIPMAP_ENTRIES &&
               (s.raysPerCell & (s.raysPerCell - 1)) == 0;
  if (!power) fail("clipmap cache: {} rays per cell; expected 1, 2, 4, 8 or 16", s.raysPerCell);
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

ClipmapCache::ClipmapCache(vk::Context& context, const GpuScene& gpuScene,
                           const GpuLightTables& lights, const ClipmapCacheSettings& settings)
    : context_(context),
      lights_(lights),
      settings_((validate(settings), settings)),
      constants_(deviceBuffer(context, sizeof(gpu::ClipmapCacheConstants), "cache.constants")),
      grid_(deviceBuffer(context, kTotalSlots * sizeof(uint32_t), "cache.grid")),
      cells_(
          deviceBuffer(context, gpu::CLIPMAP_MAX_CELLS * sizeof(gpu::ClipmapCell), "cache.cells")),
      entries_(deviceBuffer(
          context,
          VkDeviceSize(gpu::CLIPMAP_MAX_CELLS) * gpu::CLIPMAP_ENTRIES * sizeof(gpu::ClipmapEntry),
          "cache.entries")),
      pool_(deviceBuffer(context, gpu::CLIPMAP_MAX_CELLS * sizeof(uint32_t), "cache.pool")),
      counters_(deviceBuffer(context, sizeof(gpu::ClipmapCounters), "cache.counters")),
      frame_(deviceBuffer(context, sizeof(gpu::ClipmapFrameCounters), "cache.frame-counters",
                          VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT)),
      liveList_(
          deviceBuffer(context, 2 * gpu::CLIPMAP_MAX_CELLS * sizeof(uint32_t), "cache.live-list")),
      votes_(deviceBuffer(context, kTotalSlots * sizeof(gpu::ClipmapSlotVote), "cache.votes")),
      readback_(context, sizeof(gpu::ClipmapCounters) + sizeof(gpu::ClipmapFrameCounters),
                VK_BUFFER_USAGE_TRANSFER_DST_BIT, vk::MemoryUse::Readback, "cache.statistics"),
      lifetimes_(context, gpuScene, "gi/evolve/cache/cache_update_lifetimes", 0,
                 sizeof(gpu::ClipmapPassConstants)),
      clipmap_(context, gpuScene, "gi/evolve/cache/cache_update_clipmap", 0,
               sizeof(gpu::ClipmapPassConstants)),
      trace_(context, gpuScene, "gi/evolve/cache/cache_trace_diffuse_rays", 0,
             sizeof(gpu::ClipmapPassConstants)),
      buildSh_(context, gpuScene, "gi/evolve/cache/cache_build_sh", 0,
               sizeof(gpu::ClipmapPassConstants)),
      debugView_(context, gpuScene, "gi/evolve/cache/cache_debug", gpu::CACHE_LOOKUP_IMAGES,
                 sizeof(gpu::ClipmapPassConstants)),
      liveCellsView_(context, gpuScene, "gi/evolve/cache/cache_live_cells_view",
                     gpu::CACHE_LIVE_VIEW_BINDING_COUNT, sizeof(gpu::ClipmapPassConstants)) {
  std::memset(readback_.mapped(), 0, readback_.size());
  beginFullRefresh();  // the cache starts empty: a reset
}

gpu::ClipmapCacheAddresses ClipmapCache::addresses() const {
  return {grid_.address(),     cells_.address(), entries_.address(),  pool_.address(),
          counters_.address(), frame_.address(), liveList_.address(), votes_.address()};
}

// Cascade c's window is the 32^3 cells of side finestCellSize * 2^c centred on the cell that
// holds the camera; it moves by whole cells, so cells inside both windows keep their slot.
gpu::ClipmapCacheConstants ClipmapCache::makeConstants(const GiInputs& inputs) const {
  gpu::ClipmapCacheConstants c{};
  c.buffers = addresses();
  c.lights = lights_.address();
  glm::vec3 camera =
      inputs.frame.hostConstants ? inputs.frame.hostConstants->camera.position : glm::vec3(0.0f);
  for (uint32_t cascade = 0; cascade < gpu::CLIPMAP_CASCADES; ++cascade) {
    float cell = settings_.finestCellSize * float(1u << cascade);
    glm::ivec3 centre = glm::ivec3(glm::floor(camera / cell));
    c.cascadeOrigin[cascade] = glm::ivec4(centre - int(gpu::CLIPMAP_GRID / 2), 0);
  }
  c.cameraPosition = camera;
  c.finestCellSize = settings_.finestCellSize;
  c.frameIndex =
      inputs.frame.hostConstants ? inputs.frame.hostConstants->frameIndex : uint32_t(frames_);
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

void ClipmapCache::declareStatisticsReadback(graph::FrameGraph& graph) {
  CacheBuffers b = handles_;
  graph::BufferHandle readback =
      graph.importBuffer("cache.statistics", graph::ImportedBuffer::from(readback_));
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
  // The frame that ran declared the reset if one was pending (declareUpdate()).
  resetPending_ = false;
  if (fullRefreshLeft_ > 0) --fullRefreshLeft_;
  ++frames_;
  previous_ = last_;
  const auto* bytes = static_cast<const std::byte*>(readback_.mapped());
  std::memcpy(&last_.counters, bytes, sizeof(last_.counters));
  std::memcpy(&last_.frame, bytes + sizeof(last_.counters), sizeof(last_.frame));
  haveSnapshot_ = true;
}

std::vector<GiStatistic> ClipmapCache::statistics() const {
  if (!haveSnapshot_) return {};
  // Totals restart at zero after a reset; a total below the last one means exactly that.
  auto delta = [](uint32_t now, uint32_t before) {
    return double(now >= before ? now - before : now);
  };
  std::vector<GiStatistic> out;
  out.push_back({"cache.live-cells", double(last_.counters.allocated)});
  out.push_back({"cache.allocations",
                 delta(last_.counters.allocationsTotal, previous_.counters.allocationsTotal)});
  out.push_back({"cache.frees", delta(last_.counters.freesTotal, previous_.counters.freesTotal)});
  out.push_back({"cache.frees-by-scrolling", double(last_.frame.scrollFrees)});
  out.push_back({"cache.allocation-failures",
                 delta(last_.counters.allocationFailures, previous_.counters.allocationFailures)});
  for (uint32_t c = 0; c < gpu::CLIPMAP_CASCADES; ++c)
    out.push_back(
        {"cache.live-cells.cascade-" + std::to_string(c), double(last_.frame.liveCells[c])});
  return out;
}

}  // namespace bounce
