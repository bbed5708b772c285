#include "gi/gi10/gi10_gi.h"

#include <algorithm>
#include <bit>
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
constexpr uint32_t kMinCacheSlots = 4096;

vk::Buffer deviceBuffer(vk::Context& context, VkDeviceSize bytes, const std::string& name) {
  return vk::Buffer(context, bytes, kStorage, vk::MemoryUse::DeviceOnly, name);
}

uint32_t divideUp(uint32_t a, uint32_t b) {
  return (a + b - 1) / b;
}

uint32_t cacheBuckets(const Gi10Settings& s, VkExtent2D resolution) {
  uint64_t pixels = uint64_t(resolution.width) * resolution.height;
  uint64_t slots = std::bit_ceil(std::max<uint64_t>(kMinCacheSlots, pixels / s.pixelsPerCacheSlot));
  return uint32_t(slots / gpu::GI10_BUCKET_SLOTS);
}

}  // namespace

void validate(const Gi10Settings& s) {
  if (s.spawnTile < 8 || s.spawnTile > 64 || s.spawnTile % 8 != 0)
    fail("gi10: spawn tile {} px; expected a multiple of 8 from 8 to 64", s.spawnTile);
  if (!(s.cacheCellPixels > 0.0f) || !std::isfinite(s.cacheCellPixels))
    fail("gi10: cache cell footprint {} px must be positive", s.cacheCellPixels);
  if (!(s.minCellSize > 0.0f) || !std::isfinite(s.minCellSize))
    fail("gi10: min cell size {} m must be positive", s.minCellSize);
  if (s.decayFrames < 1) fail("gi10: decay frames must be >= 1");
  if (s.maxSampleCount < 1) fail("gi10: max sample count must be >= 1");
  if (s.pixelsPerCacheSlot < 1 || s.pixelsPerCacheSlot > 1024)
    fail("gi10: {} pixels per cache slot; expected 1 to 1024", s.pixelsPerCacheSlot);
  if (!(s.historyCap >= 1.0f) || !std::isfinite(s.historyCap))
    fail("gi10: history cap {} must be >= 1", s.historyCap);
}

Gi10Gi::Gi10Gi(vk::Context& context, GpuScene& gpuScene, const Scene& scene,
               const Gi10Settings& settings, VkExtent2D resolution)
    : context_(context),
      settings_((validate(settings), settings)),
      resolution_(resolution),
      probeGrid_(divideUp(resolution.width, gpu::GI10_PROBE_SIZE),
                 divideUp(resolution.height, gpu::GI10_PROBE_SIZE)),
      spawnGrid_(divideUp(resolution.width, settings.spawnTile),
                 divideUp(resolution.height, settings.spawnTile)),
      buckets_(cacheBuckets(settings, resolution)),
      lights_(context, gpuScene, scene),
      purge_(context, gpuScene, "gi/gi10/purge_radiance_cache", 0, sizeof(gpu::Gi10PassConstants)),
      spawnPass_(context, gpuScene, "gi/gi10/spawn_screen_probes", gpu::GI10_SPAWN_BINDING_COUNT,
                 sizeof(gpu::Gi10PassConstants)),
      reproject_(context, gpuScene, "gi/gi10/reproject_screen_probes",
                 gpu::GI10_REPROJECT_BINDING_COUNT, sizeof(gpu::Gi10PassConstants)),
      populate_(context, gpuScene, "gi/gi10/populate_screen_probes",
                gpu::GI10_POPULATE_BINDING_COUNT, sizeof(gpu::Gi10PassConstants)),
      update_(context, gpuScene, "gi/gi10/update_radiance_cache", 0,
              sizeof(gpu::Gi10PassConstants)),
      resolve_(context, gpuScene, "gi/gi10/resolve_radiance_cache", 0,
               sizeof(gpu::Gi10PassConstants)),
      blend_(context, gpuScene, "gi/gi10/blend_screen_probes", 0, sizeof(gpu::Gi10PassConstants)),
      project_(context, gpuScene, "gi/gi10/project_screen_probes", 0,
               sizeof(gpu::Gi10PassConstants)),
      interpolate_(context, gpuScene, "gi/gi10/interpolate_screen_probes",
                   gpu::GI10_INTERPOLATE_BINDING_COUNT, sizeof(gpu::Gi10PassConstants)),
      reprojectGi_(context, gpuScene, "gi/gi10/reproject_gi", gpu::GI10_REPROJECT_GI_BINDING_COUNT,
                   sizeof(gpu::Gi10PassConstants)),
      filter_(context, gpuScene, "gi/gi10/filter_gi", gpu::GI10_FILTER_BINDING_COUNT,
              sizeof(gpu::Gi10PassConstants), 2),
      probesDebug_(context, gpuScene, "gi/gi10/probes_debug", 1, sizeof(gpu::Gi10PassConstants)),
      cacheDebug_(context, gpuScene, "gi/gi10/cache_debug", 3, sizeof(gpu::Gi10PassConstants)) {
  const VkDeviceSize tiles = VkDeviceSize(probeGrid_.x) * probeGrid_.y;
  const VkDeviceSize spawnTiles = VkDeviceSize(spawnGrid_.x) * spawnGrid_.y;
  const VkDeviceSize cells = gpu::GI10_PROBE_CELLS;
  constants_ = deviceBuffer(context, sizeof(gpu::Gi10Constants), "gi10.constants");
  for (uint32_t i = 0; i < 2; ++i) {
    probes_[i] = deviceBuffer(context, tiles * sizeof(gpu::Gi10Probe), "gi10.probes");
    radiance_[i] = deviceBuffer(context, tiles * cells * 2 * sizeof(uint32_t), "gi10.radiance");
  }
  sh_ = deviceBuffer(context, tiles * 9 * 3 * sizeof(float), "gi10.sh");
  spawn_ = deviceBuffer(context, spawnTiles * 2 * sizeof(uint32_t), "gi10.spawn");
  rays_ = deviceBuffer(context, spawnTiles * cells * sizeof(gpu::Gi10Ray), "gi10.rays");
  cache_ = deviceBuffer(
      context, VkDeviceSize(buckets_) * gpu::GI10_BUCKET_SLOTS * sizeof(gpu::Gi10CacheCell),
      "gi10.cache");
  counters_ = deviceBuffer(context, sizeof(gpu::Gi10Counters), "gi10.counters");
  readback_ = vk::Buffer(context, sizeof(gpu::Gi10Counters), VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                         vk::MemoryUse::Readback, "gi10.statistics");
}

uint64_t Gi10Gi::bufferBytes() const {
  uint64_t bytes = constants_.size() + sh_.size() + spawn_.size() + rays_.size() + cache_.size() +
                   counters_.size();
  for (uint32_t i = 0; i < 2; ++i) bytes += probes_[i].size() + radiance_[i].size();
  return bytes;
}

gpu::Gi10Constants Gi10Gi::makeConstants(const GiInputs& inputs) const {
  const uint32_t current = parity_, previous = 1 - parity_;
  gpu::Gi10Constants k{};
  k.lights = lights_.address();
  k.probes = probes_[current].address();
  k.previousProbes = probes_[previous].address();
  k.radiance = radiance_[current].address();
  k.previousRadiance = radiance_[previous].address();
  k.sh = sh_.address();
  k.spawn = spawn_.address();
  k.rays = rays_.address();
  k.cache = cache_.address();
  k.counters = counters_.address();
  k.probeGrid = probeGrid_;
  k.spawnGrid = spawnGrid_;
  k.spawnTile = settings_.spawnTile;
  k.bucketMask = buckets_ - 1;
  // A reset or a lighting cut starts the probes, the cache and the accumulation afresh.
  k.historyValid = resetPending_ || lightingCutPending_ || frame_ == 0 ? 0u : 1u;
  k.flags = (settings_.alphaTest ? gpu::GI10_FLAG_ALPHA_TEST : 0u) |
            (settings_.feedback ? gpu::GI10_FLAG_FEEDBACK : 0u) |
            (settings_.filter ? gpu::GI10_FLAG_FILTER : 0u) |
            (settings_.probeHysteresis ? gpu::GI10_FLAG_HYSTERESIS : 0u);
  // |up| is tan(fovY / 2) (the image plane's half-height at distance 1).
  const float tanHalfFov = glm::length(inputs.frame.hostConstants->camera.up);
  k.pixelFootprint = 2.0f * tanHalfFov / float(resolution_.height);
  k.cacheCellPixels = settings_.cacheCellPixels;
  k.minCellSize = settings_.minCellSize;
  k.decayFrames = settings_.decayFrames;
  k.maxSampleCount = settings_.maxSampleCount;
  k.materialTextureSide = settings_.materialTextureSide;
  k.frame = frame_;
  k.historyCap = settings_.historyCap;
  return k;
}

Gi10Gi::Buffers Gi10Gi::importBuffers(graph::FrameGraph& graph) const {
  using graph::ImportedBuffer;
  Buffers b;
  b.constants = graph.importBuffer("gi10.constants", ImportedBuffer::from(constants_));
  for (uint32_t i = 0; i < 2; ++i) {
    b.probes[i] = graph.importBuffer(i == 0 ? "gi10.probes-0" : "gi10.probes-1",
                                     ImportedBuffer::from(probes_[i]));
    b.radiance[i] = graph.importBuffer(i == 0 ? "gi10.radiance-0" : "gi10.radiance-1",
                                       ImportedBuffer::from(radiance_[i]));
  }
  b.sh = graph.importBuffer("gi10.sh", ImportedBuffer::from(sh_));
  b.spawn = graph.importBuffer("gi10.spawn", ImportedBuffer::from(spawn_));
  b.rays = graph.importBuffer("gi10.rays", ImportedBuffer::from(rays_));
  b.cache = graph.importBuffer("gi10.cache", ImportedBuffer::from(cache_));
  b.counters = graph.importBuffer("gi10.counters", ImportedBuffer::from(counters_));
  return b;
}

DiffuseGiOutput Gi10Gi::declare(graph::FrameGraph& graph, const GiInputs& inputs) {
  const Buffers b = importBuffers(graph);
  const gpu::Gi10Constants k = makeConstants(inputs);
  graph::HistoryImage gi = graph.createHistoryImage("gi10.gi", {VK_FORMAT_R16G16B16A16_SFLOAT});
  declareStart(graph, b, k);
  const gpu::Gi10PassConstants push{inputs.frame.constantsAddress, constants_.address(), 0, 0};
  declareProbes(graph, inputs, b, push, gi.previous);
  graph::ImageHandle output = declareResolve(graph, inputs, b, push, gi);
  declareStatisticsReadback(graph, b);
  declareDebugViews(graph, inputs, b, push);
  return {output};
}

// gi10-clear-counters: after a reset (or a lighting cut) the cache and both probe buffers are
// zeroed (no cell, no probe); every frame the constants are written and the counters zeroed.
void Gi10Gi::declareStart(graph::FrameGraph& graph, const Buffers& b, const gpu::Gi10Constants& k) {
  const bool clear = k.historyValid == 0;
  graph.addPass("gi10-clear-counters", QueueKind::Compute)
      .write(b.constants, Access::TransferDst)
      .write(b.counters, Access::TransferDst)
      .write(b.cache, Access::TransferDst)
      .write(b.probes[0], Access::TransferDst)
      .write(b.probes[1], Access::TransferDst)
      .sideEffects()
      .record([b, k, clear](VkCommandBuffer cmd, const graph::PassResources& r) {
        vkCmdUpdateBuffer(cmd, r.buffer(b.constants).buffer, 0, sizeof(k), &k);
        vkCmdFillBuffer(cmd, r.buffer(b.counters).buffer, 0, VK_WHOLE_SIZE, 0u);
        if (!clear) return;
        for (graph::BufferHandle h : {b.cache, b.probes[0], b.probes[1]})
          vkCmdFillBuffer(cmd, r.buffer(h).buffer, 0, VK_WHOLE_SIZE, 0u);
      });
}

void Gi10Gi::declareStatisticsReadback(graph::FrameGraph& graph, const Buffers& b) {
  graph::BufferHandle readback =
      graph.importBuffer("gi10.statistics", graph::ImportedBuffer::from(readback_));
  graph.addPass("gi10-read-statistics", QueueKind::Compute)
      .read(b.counters, Access::TransferSrc)
      .write(readback, Access::TransferDst)
      .sideEffects()
      .record([b, readback](VkCommandBuffer cmd, const graph::PassResources& r) {
        VkBufferCopy copy{0, 0, sizeof(gpu::Gi10Counters)};
        vkCmdCopyBuffer(cmd, r.buffer(b.counters).buffer, r.buffer(readback).buffer, 1, &copy);
      });
}

void Gi10Gi::afterFrame() {
  std::memcpy(&last_, readback_.mapped(), sizeof(last_));
  haveCounters_ = true;
  parity_ = 1 - parity_;
  frame_ = resetPending_ ? 1 : frame_ + 1;
  resetPending_ = false;
  lightingCutPending_ = false;
}

std::vector<GiStatistic> Gi10Gi::statistics() const {
  std::vector<GiStatistic> s;
  s.push_back({"gi10_buffer_bytes", double(bufferBytes())});
  s.push_back({"gi10_cache_slots", double(uint64_t(buckets_) * gpu::GI10_BUCKET_SLOTS)});
  if (!haveCounters_) return s;
  s.push_back({"gi10_probe_rays", double(last_.probeRays)});
  s.push_back({"gi10_spawned_probes", double(last_.spawnedProbes)});
  s.push_back({"gi10_reprojected_probes", double(last_.reprojectedProbes)});
  s.push_back({"gi10_empty_tiles", double(last_.emptyTiles)});
  s.push_back({"gi10_cache_inserts", double(last_.cacheInserts)});
  s.push_back({"gi10_cache_overflow", double(last_.cacheOverflow)});
  s.push_back({"gi10_live_cells", double(last_.liveCells)});
  s.push_back({"gi10_feedback_hits", double(last_.feedbackHits)});
  return s;
}

}  // namespace bounce
