// Evolve's world-space clipmap irradiance cache (seed 000, "Clipmap irradiance cache"; after
// kajiya's ircache): 12 cascades of 32^3 cells around the camera, cells of 16 ReSTIR entries in
// equal-area octahedral direction bins, each cell summarised as L1 SH of incoming radiance, at
// most 65,535 live cells from a pool. Layouts: shaders/shared/clipmap_cache_io.h.
//
// Per frame, before any consumer: declareUpdate() adds
//   cache-update-lifetimes   stale cells age; freed after maxStaleFrames (4)
//   cache-update-clipmap     cascades scroll with the camera; cells outside their window freed;
//                            the live list is built
//   cache-trace-diffuse-rays new candidates (and validation rays) per live cell
//   cache-build-sh           entries -> L1 SH
// and the debug views `cache` (cells shaded with their irradiance) and `cache.live-cells`.
// Consumers then look the cache up in their own passes (shaders/gi/evolve/cache/cache_lookup.glsl:
// cacheLookupIrradiance(clipmapCacheView(constantsAddress()), ...)), declaring the cache's
// buffers with declareLookup(); lookups mark cells used and allocate missing ones. The last
// consumer calls declareStatisticsReadback() so that statistics() counts its allocations.
//
//   ClipmapCache cache(context, gpuScene, settings.cache);
//   cache.declareUpdate(graph, inputs);
//   cache.declareLookup(graph.addPass("my-pass", QueueKind::Compute)).read(...).record(...);
//   cache.declareStatisticsReadback(graph);
//   ... after the submission: cache.afterFrame(); cache.statistics();
#pragma once
#include <array>
#include <vector>

#include "gi/diffuse_gi.h"
#include "gi/evolve/cache/clipmap_cache_settings.h"
#include "lighting/gpu_light_tables.h"
#include "passes/image_pass.h"
#include "shared/clipmap_cache_io.h"
#include "vk/resources.h"

namespace bounce {

// This frame's graph handles of the cache's buffers (valid after declareUpdate()).
struct CacheBuffers {
  graph::BufferHandle constants;  // ClipmapCacheConstants
  graph::BufferHandle grid;
  graph::BufferHandle cells;
  graph::BufferHandle entries;
  graph::BufferHandle pool;
  graph::BufferHandle counters;
  graph::BufferHandle frame;  // ClipmapFrameCounters
  graph::BufferHandle liveList;
  graph::BufferHandle votes;  // ClipmapSlotVote per grid slot
};

class ClipmapCache {
 public:
  // `lights`: the tables its rays' next-event estimation samples; must outlive the cache.
  ClipmapCache(vk::Context& context, const GpuScene& gpuScene, const GpuLightTables& lights,
               const ClipmapCacheSettings& settings);

  // Declares the four cache passes and the two debug-view passes (culled unless requested).
  void declareUpdate(graph::FrameGraph& graph, const GiInputs& inputs);
  // Adds what a pass calling cacheLookupIrradiance() needs: the constants (read) and the
  // buffers a lookup marks and allocates in (read-write). Returns `pass`.
  graph::PassBuilder declareLookup(graph::PassBuilder pass) const;
  // Copies the counters for statistics(); declare after the last pass that looks up.
  void declareStatisticsReadback(graph::FrameGraph& graph);

  VkDeviceAddress constantsAddress() const { return constants_.address(); }
  const CacheBuffers& buffers() const { return handles_; }
  const ClipmapCacheSettings& settings() const { return settings_; }

  // After the frame's submission: reads the counters copied by declareStatisticsReadback() and
  // advances the per-frame state (a pending reset done, the full refresh's countdown). Every
  // executed frame that declared the update must call it; a declared frame that never runs
  // must not.
  void afterFrame();
  // Live cells (total and per cascade), allocations, frees (all and by scrolling) and failed
  // allocations of the last frame.
  std::vector<GiStatistic> statistics() const;
  // Empties the cache (every cell back to the pool) at the next declareUpdate(), then refreshes
  // every cell fully for settings().fullRefreshFrames frames.
  void resetHistory() {
    resetPending_ = true;
    beginFullRefresh();
  }
  // The light changed everywhere at once (a lighting cut): the cells stay, but for the next
  // settings().fullRefreshFrames frames every cell traces all its entries each frame.
  void beginFullRefresh() { fullRefreshLeft_ = settings_.fullRefreshFrames; }

 private:
  gpu::ClipmapCacheAddresses addresses() const;
  gpu::ClipmapCacheConstants makeConstants(const GiInputs& inputs) const;
  // The passes of declareUpdate(), in order (cache_passes.cpp).
  void importBuffers(graph::FrameGraph& graph);
  void declareReset(graph::FrameGraph& graph);
  void declareLifetimes(graph::FrameGraph& graph, const gpu::ClipmapPassConstants& push);
  void declareClipmap(graph::FrameGraph& graph, const gpu::ClipmapPassConstants& push);
  void declareTraceAndBuildSh(graph::FrameGraph& graph, const GiInputs& inputs,
                              const gpu::ClipmapPassConstants& push);
  void declareDebugViews(graph::FrameGraph& graph, const GiInputs& inputs,
                         const gpu::ClipmapPassConstants& push);

  vk::Context& context_;
  const GpuLightTables& lights_;
  ClipmapCacheSettings settings_;
  vk::Buffer constants_, grid_, cells_, entries_, pool_, counters_, frame_, liveList_, votes_;
  vk::Buffer readback_;  // ClipmapCounters then ClipmapFrameCounters, host-visible
  ComputePass lifetimes_, clipmap_, trace_, buildSh_, debugView_, liveCellsView_;
  CacheBuffers handles_;
  gpu::ClipmapCacheConstants constantsData_{};
  bool resetPending_ = true;
  uint32_t fullRefreshLeft_ = 0;  // frames of full refresh still to come
  uint64_t frames_ = 0;

  struct Snapshot {
    gpu::ClipmapCounters counters{};
    gpu::ClipmapFrameCounters frame{};
  };
  Snapshot last_{}, previous_{};
  bool haveSnapshot_ = false;
};

}  // namespace bounce
