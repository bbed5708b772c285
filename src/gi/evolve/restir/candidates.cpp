#include "gi/evolve/restir/candidates.h"

namespace bounce {

using graph::Access;
using graph::QueueKind;

namespace {

constexpr VkFormat kRgba32f = VK_FORMAT_R32G32B32A32_SFLOAT;
constexpr VkFormat kRgba16f = VK_FORMAT_R16G16B16A16_SFLOAT;

bool historyValid(const graph::PassResources& r, const RestirFrame& f,
                  const ReservoirHistory& history) {
  bool valid = !f.lightCutPending;
  for (const graph::HistoryImage& image : history) valid = valid && r.historyValid(image);
  return valid;
}

}  // namespace

uint32_t secondVertexConstant(RestirGiSecondVertex v) {
  switch (v) {
    case RestirGiSecondVertex::Path:
      return gpu::RESTIR_GI_SECOND_VERTEX_PATH;
    case RestirGiSecondVertex::Cache:
      return gpu::RESTIR_GI_SECOND_VERTEX_CACHE;
    default:
      return gpu::RESTIR_GI_SECOND_VERTEX_NEE;
  }
}

CandidateStage::CandidateStage(vk::Context& context, const GpuScene& scene, uint32_t secondVertex)
    : prepare_(context, scene, "gi/evolve/restir/gi_prepare_diffuse_rays",
               gpu::GI_PREPARE_BINDING_COUNT),
      trace_(context, scene, secondVertex),
      resolve_(context, scene, "gi/evolve/restir/gi_resolve_diffuse_rays",
               gpu::GI_CANDIDATES_BINDING_COUNT) {}

Candidates CandidateStage::declare(graph::FrameGraph& graph, const RestirFrame& f,
                                   const ReservoirHistory& history, ClipmapCache* cache) {
  graph::ImageHandle rays = declarePrepare(graph, f, history);
  GiHits hits = declareGiTrace(graph, f, rays, cache, trace_);
  // The trace is the chain's last cache lookup.
  if (cache) cache->declareStatisticsReadback(graph);
  return declareResolve(graph, f, history, rays, hits);
}

graph::ImageHandle CandidateStage::declarePrepare(graph::FrameGraph& graph, const RestirFrame& f,
                                                  const ReservoirHistory& history) {
  graph::ImageHandle rays = graph.createImage("gi.rays", {kRgba32f, f.giSize});
  const GBuffer& g = f.in.gbuffer;
  graph.addPass("gi-prepare-diffuse-rays", QueueKind::Compute)
      .write(rays, Access::StorageWrite, gpu::GI_PREPARE_BINDING_RAYS)
      .read(f.in.frame.constants, Access::StorageRead)
      .read(g.normals, Access::StorageRead, gpu::GI_PREPARE_BINDING_NORMALS)
      .read(g.depth.current, Access::StorageRead, gpu::GI_PREPARE_BINDING_DEPTH)
      .read(g.flags, Access::StorageRead, gpu::GI_PREPARE_BINDING_FLAGS)
      .read(g.velocity, Access::StorageRead, gpu::GI_PREPARE_BINDING_VELOCITY)
      .read(history[0].previous, Access::StorageRead, gpu::GI_PREPARE_BINDING_PREVIOUS_SAMPLE)
      .read(history[2].previous, Access::StorageRead, gpu::GI_PREPARE_BINDING_PREVIOUS_ORIGIN)
      .read(history[3].previous, Access::StorageRead, gpu::GI_PREPARE_BINDING_PREVIOUS_NORMALS)
      .record([this, f, history](VkCommandBuffer cmd, const graph::PassResources& r) {
        prepare_.record(cmd, r, f.passConstants(historyValid(r, f, history)), f.giResolution);
      });
  return rays;
}

GiTracePasses::GiTracePasses(vk::Context& context, const GpuScene& scene, uint32_t secondVertex)
    : trace(context, scene, "gi/evolve/restir/gi_trace_diffuse_rays", gpu::GI_TRACE_BINDING_COUNT),
      shade(context, scene, "gi/evolve/restir/gi_shade_diffuse_hits", gpu::GI_SHADE_BINDING_COUNT,
            std::span<const uint32_t>(&secondVertex, 1)),
      traceNee(context, scene, "gi/evolve/restir/gi_trace_diffuse_nee_rays",
               gpu::GI_NEE_BINDING_COUNT) {}

GiHits declareGiTrace(graph::FrameGraph& graph, const RestirFrame& f, graph::ImageHandle rays,
                      const ClipmapCache* cache, GiTracePasses& passes) {
  const graph::ImageHandle ids =
      graph.createImage("gi.hit-ids", {VK_FORMAT_R32G32B32A32_UINT, f.giSize});
  const graph::ImageHandle barycentrics =
      graph.createImage("gi.hit-barycentrics", {VK_FORMAT_R32G32_SFLOAT, f.giSize});
  graph.addPass("gi-trace-diffuse-rays", QueueKind::Compute)
      .write(ids, Access::StorageWrite, gpu::GI_TRACE_BINDING_HIT_IDS)
      .write(barycentrics, Access::StorageWrite, gpu::GI_TRACE_BINDING_HIT_BARYCENTRICS)
      .read(f.in.frame.constants, Access::StorageRead)
      .read(f.in.frame.instances, Access::StorageRead)
      .read(f.in.frame.tlas, Access::StorageRead)
      .read(f.in.gbuffer.normals, Access::StorageRead, gpu::GI_TRACE_BINDING_NORMALS)
      .read(f.in.gbuffer.depth.current, Access::StorageRead, gpu::GI_TRACE_BINDING_DEPTH)
      .read(rays, Access::StorageRead, gpu::GI_TRACE_BINDING_RAYS)
      .record([&passes, f](VkCommandBuffer cmd, const graph::PassResources& r) {
        passes.trace.record(cmd, r, f.passConstants(false), f.giResolution);
      });

  GiHits h;
  h.hit = graph.createImage("gi.hit", {kRgba32f, f.giSize});
  h.normal = graph.createImage("gi.hit-normal", {kRgba16f, f.giSize});
  h.radiance = graph.createImage("gi.hit-radiance", {kRgba32f, f.giSize});
  h.neeRay = graph.createImage("gi.nee-ray", {kRgba32f, f.giSize});
  h.neeRadiance = graph.createImage("gi.nee-radiance", {kRgba32f, f.giSize});
  h.neeVisibility = graph.createImage("gi.nee-visibility", {VK_FORMAT_R16_SFLOAT, f.giSize});
  graph::PassBuilder pass = graph.addPass("gi-shade-diffuse-hits", QueueKind::Compute);
  if (cache) cache->declareLookup(pass);
  pass.read(f.in.frame.constants, Access::StorageRead)
      .read(f.in.frame.instances, Access::StorageRead)
      .read(f.in.frame.tlas, Access::StorageRead)
      .read(f.in.gbuffer.normals, Access::StorageRead, gpu::GI_SHADE_BINDING_NORMALS)
      .read(f.in.gbuffer.depth.current, Access::StorageRead, gpu::GI_SHADE_BINDING_DEPTH)
      .read(rays, Access::StorageRead, gpu::GI_SHADE_BINDING_RAYS)
      .read(ids, Access::StorageRead, gpu::GI_SHADE_BINDING_HIT_IDS)
      .read(barycentrics, Access::StorageRead, gpu::GI_SHADE_BINDING_HIT_BARYCENTRICS)
      .write(h.hit, Access::StorageWrite, gpu::GI_SHADE_BINDING_HIT)
      .write(h.normal, Access::StorageWrite, gpu::GI_SHADE_BINDING_HIT_NORMAL)
      .write(h.radiance, Access::StorageWrite, gpu::GI_SHADE_BINDING_HIT_RADIANCE)
      .write(h.neeRay, Access::StorageWrite, gpu::GI_SHADE_BINDING_NEE_RAY)
      .write(h.neeRadiance, Access::StorageWrite, gpu::GI_SHADE_BINDING_NEE_RADIANCE)
      .write(h.neeVisibility, Access::StorageWrite, gpu::GI_SHADE_BINDING_NEE_VISIBILITY)
      .write(f.rayLists, Access::StorageReadWrite)
      .record([&passes, f](VkCommandBuffer cmd, const graph::PassResources& r) {
        passes.shade.record(cmd, r, f.rayListConstants(r), f.giResolution);
      });
  // StorageReadWrite: the pass writes the listed GI pixels only and keeps the others' 0.
  graph.addPass("gi-trace-diffuse-nee-rays", QueueKind::Compute)
      .read(f.in.frame.constants, Access::StorageRead)
      .read(f.in.frame.instances, Access::StorageRead)
      .read(f.in.frame.tlas, Access::StorageRead)
      .read(f.rayLists, Access::IndirectRead)
      .read(f.rayLists, Access::StorageRead)
      .read(h.hit, Access::StorageRead, gpu::GI_NEE_BINDING_HIT)
      .read(h.normal, Access::StorageRead, gpu::GI_NEE_BINDING_HIT_NORMAL)
      .read(h.neeRay, Access::StorageRead, gpu::GI_NEE_BINDING_NEE_RAY)
      .write(h.neeVisibility, Access::StorageReadWrite, gpu::GI_NEE_BINDING_VISIBILITY)
      .record([&passes, f](VkCommandBuffer cmd, const graph::PassResources& r) {
        passes.traceNee.recordOverRayList(cmd, r, f.rayListConstants(r), f.rayLists,
                                          gpu::GI_RAY_LIST_NEE);
      });
  return h;
}

// The candidate's estimate is the first image written: the pass's debug view.
Candidates CandidateStage::declareResolve(graph::FrameGraph& graph, const RestirFrame& f,
                                          const ReservoirHistory& history, graph::ImageHandle rays,
                                          const GiHits& hits) {
  Candidates c;
  c.reservoir = createReservoirImages(graph, "gi.candidate.", f.giSize);
  c.estimate = graph.createImage("gi.candidate-estimate", {kRgba16f, f.giSize});
  c.validity = graph.createImage("gi.reservoir-validity", {kRgba16f, f.giSize});
  c.neeVisibility = hits.neeVisibility;
  graph::PassBuilder pass = graph.addPass("gi-resolve-diffuse-rays", QueueKind::Compute);
  pass.read(f.in.frame.constants, Access::StorageRead)
      .read(f.in.gbuffer.normals, Access::StorageRead, gpu::GI_CANDIDATES_BINDING_NORMALS)
      .read(f.in.gbuffer.depth.current, Access::StorageRead, gpu::GI_CANDIDATES_BINDING_DEPTH)
      .read(rays, Access::StorageRead, gpu::GI_CANDIDATES_BINDING_RAYS)
      .read(hits.hit, Access::StorageRead, gpu::GI_CANDIDATES_BINDING_HIT)
      .read(hits.normal, Access::StorageRead, gpu::GI_CANDIDATES_BINDING_HIT_NORMAL)
      .read(hits.radiance, Access::StorageRead, gpu::GI_CANDIDATES_BINDING_HIT_RADIANCE)
      .read(hits.neeRadiance, Access::StorageRead, gpu::GI_CANDIDATES_BINDING_NEE_RADIANCE)
      .read(hits.neeVisibility, Access::StorageRead, gpu::GI_CANDIDATES_BINDING_VISIBILITY)
      .write(c.estimate, Access::StorageWrite, gpu::GI_CANDIDATES_BINDING_ESTIMATE)
      .write(c.reservoir[0], Access::StorageWrite, gpu::GI_CANDIDATES_BINDING_SAMPLE)
      .write(c.reservoir[1], Access::StorageWrite, gpu::GI_CANDIDATES_BINDING_RADIANCE)
      .write(c.reservoir[2], Access::StorageWrite, gpu::GI_CANDIDATES_BINDING_ORIGIN)
      .write(c.reservoir[3], Access::StorageWrite, gpu::GI_CANDIDATES_BINDING_RESERVOIR_NORMALS)
      .write(c.validity, Access::StorageWrite, gpu::GI_CANDIDATES_BINDING_VALIDITY);
  for (uint32_t i = 0; i < 4; ++i)
    pass.read(history[i].previous, Access::StorageRead, gpu::GI_CANDIDATES_BINDING_PREVIOUS + i);
  pass.record([this, f](VkCommandBuffer cmd, const graph::PassResources& r) {
    resolve_.record(cmd, r, f.passConstants(false), f.giResolution);
  });
  return c;
}

}  // namespace bounce
