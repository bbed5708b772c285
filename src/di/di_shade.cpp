#include "di/di_shade.h"

namespace bounce {

using graph::Access;

DiShadePass::DiShadePass(vk::Context& context, const GpuScene& scene)
    : pass_(context, scene, "di/di_shade", gpu::DI_SHADE_BINDING_COUNT) {}

DirectLight DiShadePass::declare(graph::FrameGraph& graph, const DiFrame& f,
                                 graph::ImageHandle reservoirs, graph::ImageHandle temporal) {
  DirectLight out;
  out.radiance = graph.createImage("di.radiance", {VK_FORMAT_R16G16B16A16_SFLOAT});
  out.info = graph.createImage("di.reservoir-info", {VK_FORMAT_R32G32B32A32_SFLOAT});
  out.reflectance = graph.createImage("di.reflectance", {VK_FORMAT_R16G16B16A16_SFLOAT});
  graph::PassBuilder pass = graph.addPass("di-shade", graph::QueueKind::Compute);
  // The radiance is the first image written: the pass's debug view.
  pass.write(out.radiance, Access::StorageWrite, gpu::DI_SHADE_BINDING_RADIANCE);
  readDiGBuffer(pass, f)
      .write(out.info, Access::StorageWrite, gpu::DI_SHADE_BINDING_INFO)
      .write(out.reflectance, Access::StorageWrite, gpu::DI_SHADE_BINDING_REFLECTANCE)
      .read(reservoirs, Access::StorageRead, gpu::DI_SHADE_BINDING_RESERVOIR)
      .write(f.finalReservoirs ? f.finalReservoirs->current
                               : graph.createImage("di.reservoir-final", {kDiReservoirFormat}),
             Access::StorageWrite, gpu::DI_SHADE_BINDING_FINAL_RESERVOIR);
  // Without spatial reuse the shaded reservoir is di-temporal's.
  if (temporal.index == reservoirs.index)
    pass.readPlaceholder(reservoirs, gpu::DI_SHADE_BINDING_TEMPORAL_RESERVOIR);
  else
    pass.read(temporal, Access::StorageRead, gpu::DI_SHADE_BINDING_TEMPORAL_RESERVOIR);
  pass.record([this, f](VkCommandBuffer cmd, const graph::PassResources& r) {
    pass_.record(cmd, r, f.passConstants(), f.frame.resolution);
  });
  return out;
}

}  // namespace bounce
