#include "di/di_pass.h"

namespace bounce {

using graph::Access;

graph::PassBuilder& readDiGBuffer(graph::PassBuilder& pass, const DiFrame& f) {
  const GBuffer& g = f.gbuffer;
  return pass.read(f.frame.constants, Access::StorageRead)
      .read(f.frame.instances, Access::StorageRead)
      .read(f.frame.tlas, Access::StorageRead)
      .read(f.lights, Access::StorageRead)
      .read(g.baseColor, Access::StorageRead, gpu::DI_BINDING_BASE_COLOR)
      .read(g.normals, Access::StorageRead, gpu::DI_BINDING_NORMALS)
      .read(g.depth.current, Access::StorageRead, gpu::DI_BINDING_DEPTH)
      .read(g.emissive, Access::StorageRead, gpu::DI_BINDING_EMISSIVE)
      .read(g.flags, Access::StorageRead, gpu::DI_BINDING_FLAGS);
}

}  // namespace bounce
