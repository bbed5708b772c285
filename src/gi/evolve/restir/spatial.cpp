#include "gi/evolve/restir/spatial.h"

namespace bounce {

using graph::Access;
using graph::QueueKind;

namespace {

constexpr VkFormat kRgba16f = VK_FORMAT_R16G16B16A16_SFLOAT;
// The reservoir-to-reservoir passes read their input reservoirs and the GBuffer as sampled
// images (docs/architecture.md, "Sampled inputs").
constexpr uint64_t kReservoirPassSampled =
    bindingMask({gpu::GI_SPATIAL_BINDING_INPUT + 0, gpu::GI_SPATIAL_BINDING_INPUT + 1,
                 gpu::GI_SPATIAL_BINDING_INPUT + 2, gpu::GI_SPATIAL_BINDING_INPUT + 3,
                 gpu::GI_SPATIAL_BINDING_NORMALS, gpu::GI_SPATIAL_BINDING_DEPTH});

}  // namespace

SpatialStage::SpatialStage(vk::Context& context, const GpuScene& scene,
                           const RestirGiSettings& settings)
    : settings_(settings),
      spatial0_(context, scene, "gi/evolve/restir/gi_restir_spatial", gpu::GI_SPATIAL_BINDING_COUNT,
                {}, kReservoirPassSampled),
      spatial1_(context, scene, "gi/evolve/restir/gi_restir_spatial", gpu::GI_SPATIAL_BINDING_COUNT,
                {}, kReservoirPassSampled),
      validation_(context, scene, "gi/evolve/restir/gi_trace_spatial_validation_rays",
                  gpu::GI_VALIDATION_BINDING_COUNT),
      patch_(context, scene, "gi/evolve/restir/gi_restir_patch_reservoir",
             gpu::GI_SPATIAL_BINDING_COUNT, {}, kReservoirPassSampled) {}

Reservoirs SpatialStage::declare(graph::FrameGraph& graph, const RestirFrame& f,
                                 const Reservoirs& temporal,
                                 const std::optional<graph::HistoryImage>& occlusionValidity) {
  if (!settings_.spatialReuse) return temporal;
  Reservoirs spatial[2];
  spatial[0].reservoir = createReservoirImages(graph, "gi.spatial-0.", f.giSize);
  spatial[1].reservoir = createReservoirImages(graph, "gi.spatial-1.", f.giSize);
  spatial[0].estimate = graph.createImage("gi.spatial-0-estimate", {kRgba16f, f.giSize});
  declareReservoirPass(graph, f, "gi-restir-spatial-0", spatial0_, 0, temporal.reservoir,
                       spatial[0]);
  spatial[1].estimate = graph.createImage("gi.spatial-1-estimate", {kRgba16f, f.giSize});
  declareReservoirPass(graph, f, "gi-restir-spatial-1", spatial1_, 1, spatial[0].reservoir,
                       spatial[1]);
  if (!settings_.spatialValidation) return spatial[1];

  Reservoirs validated = declareValidation(graph, f, temporal, spatial[1], *occlusionValidity);
  if (!settings_.patchReservoir) return validated;
  Reservoirs patched;
  patched.reservoir = createReservoirImages(graph, "gi.patched.", f.giSize);
  patched.estimate = graph.createImage("gi.patched-estimate", {kRgba16f, f.giSize});
  return declareReservoirPass(graph, f, "gi-restir-patch-reservoir", patch_, 0, validated.reservoir,
                              patched);
}

// A reservoir-to-reservoir pass at GI resolution (gi-restir-spatial-0/1, patch): the estimate
// first, so that it is the pass's debug view.
Reservoirs SpatialStage::declareReservoirPass(graph::FrameGraph& graph, const RestirFrame& f,
                                              const char* name, RestirGiPass& pass,
                                              uint32_t variant, const ReservoirImages& input,
                                              const Reservoirs& output) {
  graph::PassBuilder b = graph.addPass(name, QueueKind::Compute);
  b.write(output.estimate, Access::StorageWrite, gpu::GI_SPATIAL_BINDING_ESTIMATE)
      .read(f.in.frame.constants, Access::StorageRead)
      .read(f.in.gbuffer.normals, Access::SampledRead, gpu::GI_SPATIAL_BINDING_NORMALS)
      .read(f.in.gbuffer.depth.current, Access::SampledRead, gpu::GI_SPATIAL_BINDING_DEPTH);
  for (uint32_t i = 0; i < 4; ++i)
    b.read(input[i], Access::SampledRead, gpu::GI_SPATIAL_BINDING_INPUT + i)
        .write(output.reservoir[i], Access::StorageWrite, gpu::GI_SPATIAL_BINDING_OUTPUT + i);
  b.record([f, variant, &pass](VkCommandBuffer cmd, const graph::PassResources& r) {
    pass.record(cmd, r, f.passConstants(false, variant), f.giResolution);
  });
  return output;
}

// gi-trace-spatial-validation-rays: the spatial reservoir with its sample's W zeroed where the
// sample is occluded (gi.validated.sample; the other images are spatial-1's).
Reservoirs SpatialStage::declareValidation(graph::FrameGraph& graph, const RestirFrame& f,
                                           const Reservoirs& temporal, const Reservoirs& spatial,
                                           const graph::HistoryImage& validity) {
  Reservoirs validated = spatial;
  validated.reservoir[0] =
      graph.createImage("gi.validated.sample", {VK_FORMAT_R32G32B32A32_SFLOAT, f.giSize});
  validated.estimate = graph.createImage("gi.validated-estimate", {kRgba16f, f.giSize});
  const GBuffer& g = f.in.gbuffer;
  graph::PassBuilder b = graph.addPass("gi-trace-spatial-validation-rays", QueueKind::Compute);
  b.write(validated.estimate, Access::StorageWrite, gpu::GI_VALIDATION_BINDING_ESTIMATE)
      .read(f.in.frame.constants, Access::StorageRead)
      .read(f.in.frame.instances, Access::StorageRead)
      .read(f.in.frame.tlas, Access::StorageRead)
      .read(g.normals, Access::StorageRead, gpu::GI_VALIDATION_BINDING_NORMALS)
      .read(g.depth.current, Access::StorageRead, gpu::GI_VALIDATION_BINDING_DEPTH)
      .read(g.velocity, Access::StorageRead, gpu::GI_VALIDATION_BINDING_VELOCITY)
      .read(temporal.reservoir[0], Access::StorageRead, gpu::GI_VALIDATION_BINDING_TEMPORAL_SAMPLE)
      .read(validity.previous, Access::StorageRead, gpu::GI_VALIDATION_BINDING_VALIDITY_PREVIOUS)
      .write(validity.current, Access::StorageWrite, gpu::GI_VALIDATION_BINDING_VALIDITY_CURRENT)
      .write(validated.reservoir[0], Access::StorageWrite, gpu::GI_VALIDATION_BINDING_SAMPLE_OUT);
  for (uint32_t i = 0; i < 4; ++i)
    b.read(spatial.reservoir[i], Access::StorageRead, gpu::GI_VALIDATION_BINDING_INPUT + i);
  b.record([this, f, validity](VkCommandBuffer cmd, const graph::PassResources& r) {
    validation_.record(cmd, r, f.passConstants(r.historyValid(validity)), f.giResolution,
                       gpu::GI_VALIDATION_GROUP_SIDE);
  });
  return validated;
}

}  // namespace bounce
