// `--gi gi10`: AMD's GI-1.0 as Capsaicin implements it (seed 001, corrected by
// research/gi10_lux_denoisers.md §1; docs/gi/gi10.md says what is implemented and what is not).
// Two cache levels: screen probes (8x8 cells on 8x8-pixel tiles, a quarter ray per pixel) and a
// world-space hash-grid radiance cache that the probe rays' hits are lit from. Passes, in
// frame order (Capsaicin's stage names, §1.2; shaders/gi/gi10/<name>.comp):
//
//   gi10-clear-counters            this frame's constants, counters zeroed (a reset clears all)
//   gi10-purge-radiance-cache      cells untouched for 50 frames evicted; live cells counted
//   gi10-spawn-screen-probes       one new probe per 16x16 tile at a Halton-jittered pixel
//   gi10-reproject-screen-probes   last frame's probes re-anchored and re-binned per tile
//   gi10-populate-screen-probes    the new probes' rays: sky, emission, direct light,
//                                  feedback; samples into the hash grid
//   gi10-update-radiance-cache     the cells' running means
//   gi10-resolve-radiance-cache    probe rays take their cell's radiance
//   gi10-blend-screen-probes       new rays vs reprojected radiance (hysteresis)
//   gi10-project-screen-probes     probes -> L2 SH
//   gi10-interpolate-screen-probes per pixel from four probes -> gi10.irradiance
//   gi10-reproject-gi              temporal accumulation -> gi10.gi (history)
//   gi10-filter-gi-x, -y           bilateral blur of short-history pixels -> gi.diffuse
//   gi10-read-statistics           the counters copied for statistics()
//
// Debug views (culled unless requested, `--view NAME`): `gi10.probes-view` (each tile's probe
// cells; gi10-probes-debug), `gi10.cache-view` (the hash-grid cell at each pixel's surface, alpha
// its confidence; gi10-cache-debug), and every image above (gi10.irradiance, gi10.gi,
// gi10.filter-x).
//
// Memory is made in the constructor, sized from the resolution (docs/gi/gi10.md: bytes at
// 1920x1080).
#pragma once
#include <array>

#include "gi/diffuse_gi.h"
#include "gi/gi10/gi10_settings.h"
#include "lighting/gpu_light_tables.h"
#include "passes/image_pass.h"
#include "shared/gi10_io.h"
#include "vk/resources.h"

namespace bounce {

class Gi10Gi final : public DiffuseGi {
 public:
  Gi10Gi(vk::Context& context, GpuScene& gpuScene, const Scene& scene, const Gi10Settings& settings,
         VkExtent2D resolution);

  DiffuseGiOutput declare(graph::FrameGraph& graph, const GiInputs& inputs) override;
  void afterFrame() override;
  // Probe rays, spawned, reprojected probes, empty tiles, cache inserts, overflow, live cells,
  // feedback hits of the last frame; the GPU bytes the system holds.
  std::vector<GiStatistic> statistics() const override;
  void resetHistory() override { resetPending_ = true; }
  void lightingCut() override { lightingCutPending_ = true; }

  // Bytes of the buffers made in the constructor (images of the frame graph not included).
  uint64_t bufferBytes() const;

 private:
  struct Buffers {
    graph::BufferHandle constants, probes[2], radiance[2], sh, spawn, rays, cache, counters;
  };
  gpu::Gi10Constants makeConstants(const GiInputs& inputs) const;
  Buffers importBuffers(graph::FrameGraph& graph) const;
  void declareStart(graph::FrameGraph& graph, const Buffers& b, const gpu::Gi10Constants& k);
  void declareProbes(graph::FrameGraph& graph, const GiInputs& inputs, const Buffers& b,
                     const gpu::Gi10PassConstants& push, graph::ImageHandle previousGi);
  graph::ImageHandle declareResolve(graph::FrameGraph& graph, const GiInputs& inputs,
                                    const Buffers& b, const gpu::Gi10PassConstants& push,
                                    graph::HistoryImage gi);
  void declareStatisticsReadback(graph::FrameGraph& graph, const Buffers& b);
  void declareDebugViews(graph::FrameGraph& graph, const GiInputs& inputs, const Buffers& b,
                         const gpu::Gi10PassConstants& push);

  vk::Context& context_;
  Gi10Settings settings_;
  VkExtent2D resolution_;
  glm::uvec2 probeGrid_, spawnGrid_;
  uint32_t buckets_;
  GpuLightTables lights_;
  vk::Buffer constants_, probes_[2], radiance_[2], sh_, spawn_, rays_, cache_, counters_;
  vk::Buffer readback_;  // Gi10Counters, host-visible
  ComputePass purge_, spawnPass_, reproject_, populate_, update_, resolve_, blend_, project_,
      interpolate_, reprojectGi_, filter_, probesDebug_, cacheDebug_;
  uint32_t parity_ = 0;  // which of probes_/radiance_ is this frame's
  uint32_t frame_ = 0;   // frames since the last reset
  bool resetPending_ = true;
  bool lightingCutPending_ = false;
  bool haveCounters_ = false;
  gpu::Gi10Counters last_{};
};

}  // namespace bounce
