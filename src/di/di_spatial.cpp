#include "di/di_spatial.h"

namespace bounce {

using graph::Access;

namespace {

std::array<uint32_t, 1> correctionSpecialization(bool tracedCorrection) {
  return {tracedCorrection ? 1u : 0u};
}

}  // namespace

DiSpatialPass::DiSpatialPass(vk::Context& context, const GpuScene& scene, bool tracedCorrection)
    : pass_(context, scene, "di/di_spatial", gpu::DI_SPATIAL_BINDING_COUNT,
            correctionSpecialization(tracedCorrection)) {}

graph::ImageHandle DiSpatialPass::declare(graph::FrameGraph& graph, const DiFrame& f,
                                          graph::ImageHandle reservoirs) {
  graph::ImageHandle spatial = graph.createImage("di.spatial", {kDiReservoirFormat});
  graph::PassBuilder pass = graph.addPass("di-spatial", graph::QueueKind::Compute);
  readDiGBuffer(pass, f)
      .write(spatial, Access::StorageWrite, gpu::DI_SPATIAL_BINDING_OUTPUT)
      .read(reservoirs, Access::StorageRead, gpu::DI_SPATIAL_BINDING_INPUT)
      .record([this, f](VkCommandBuffer cmd, const graph::PassResources& r) {
        pass_.record(cmd, r, f.passConstants(), f.frame.resolution);
      });
  return spatial;
}

}  // namespace bounce
