#include "gi/evolve/restir/resolve.h"

namespace bounce {

using graph::Access;

ResolveStage::ResolveStage(vk::Context& context, const GpuScene& scene,
                           const RestirGiSettings& settings)
    : settings_(settings),
      visibility_(context, scene, "gi/evolve/restir/gi_trace_resolve_visibility",
                  gpu::GI_RESOLVE_VISIBILITY_BINDING_COUNT),
      resolve_(context, scene, "gi/evolve/restir/gi_restir_resolve",
               gpu::GI_RESOLVE_BINDING_COUNT) {}

ResolvedGi ResolveStage::declare(graph::FrameGraph& graph, const RestirFrame& f,
                                 const Reservoirs& reservoirs, graph::ImageHandle target) {
  ResolvedGi out{target, std::nullopt};
  if (settings_.occluderVisibility) {
    out.occlusion = graph.createImage("gi.resolve-occlusion", {VK_FORMAT_R32_UINT});
    declarePass(graph, f, "gi-trace-resolve-visibility", visibility_, reservoirs,
                gpu::GI_RESOLVE_VISIBILITY_BINDING_OUTPUT, *out.occlusion);
  }
  graph::PassBuilder resolve = declarePass(graph, f, "gi-restir-resolve", resolve_, reservoirs,
                                           gpu::GI_RESOLVE_BINDING_OUTPUT, target);
  if (out.occlusion)
    resolve.read(*out.occlusion, Access::StorageRead, gpu::GI_RESOLVE_BINDING_OCCLUSION);
  else  // the shader ignores the binding without gi-trace-resolve-visibility
    resolve.readPlaceholder(f.in.gbuffer.flags, gpu::GI_RESOLVE_BINDING_OCCLUSION);
  return out;
}

// Both passes read the same reservoir and GBuffer images (the resolve's bindings) and write one
// image each.
graph::PassBuilder ResolveStage::declarePass(graph::FrameGraph& graph, const RestirFrame& f,
                                             const char* name, RestirGiPass& pass,
                                             const Reservoirs& reservoirs, uint32_t outputBinding,
                                             graph::ImageHandle output) {
  const GBuffer& g = f.in.gbuffer;
  graph::PassBuilder b = graph.addPass(name, graph::QueueKind::Compute);
  b.read(f.in.frame.constants, Access::StorageRead)
      .write(output, Access::StorageWrite, outputBinding)
      .read(g.normals, Access::StorageRead, gpu::GI_RESOLVE_BINDING_NORMALS)
      .read(g.depth.current, Access::StorageRead, gpu::GI_RESOLVE_BINDING_DEPTH)
      .read(g.flags, Access::StorageRead, gpu::GI_RESOLVE_BINDING_FLAGS);
  for (uint32_t i = 0; i < 4; ++i)
    b.read(reservoirs.reservoir[i], Access::StorageRead, gpu::GI_RESOLVE_BINDING_RESERVOIR + i);
  b.record([f, &pass](VkCommandBuffer cmd, const graph::PassResources& r) {
    pass.record(cmd, r, f.passConstants(false), f.in.frame.resolution);
  });
  return b;
}

}  // namespace bounce
