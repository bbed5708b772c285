#include "gi/evolve/restir/resolve.h"

namespace bounce {

using graph::Access;

namespace {

// The reservoirs and the GBuffer, which the three passes read, are sampled images (texelFetch:
// faster than a storage image's imageLoad on an H100; docs/architecture.md, "Sampled inputs").
constexpr uint64_t kSharedSampled = bindingMask(
    {gpu::GI_RESOLVE_BINDING_NORMALS, gpu::GI_RESOLVE_BINDING_DEPTH, gpu::GI_RESOLVE_BINDING_FLAGS,
     gpu::GI_RESOLVE_BINDING_RESERVOIR + 0, gpu::GI_RESOLVE_BINDING_RESERVOIR + 1,
     gpu::GI_RESOLVE_BINDING_RESERVOIR + 2, gpu::GI_RESOLVE_BINDING_RESERVOIR + 3});

}  // namespace

ResolveStage::ResolveStage(vk::Context& context, const GpuScene& scene,
                           const RestirGiSettings& settings)
    : settings_(settings),
      findOccluders_(context, scene, "gi/evolve/restir/gi_resolve_find_occluders",
                     gpu::GI_RESOLVE_VISIBILITY_BINDING_COUNT, {}, kSharedSampled),
      visibility_(context, scene, "gi/evolve/restir/gi_trace_resolve_visibility",
                  gpu::GI_RESOLVE_VISIBILITY_BINDING_COUNT, {}, kSharedSampled),
      resolve_(context, scene, "gi/evolve/restir/gi_restir_resolve", gpu::GI_RESOLVE_BINDING_COUNT,
               {}, kSharedSampled | bindingMask({gpu::GI_RESOLVE_BINDING_OCCLUSION})) {}

ResolvedGi ResolveStage::declare(graph::FrameGraph& graph, const RestirFrame& f,
                                 const Reservoirs& reservoirs, graph::ImageHandle target) {
  ResolvedGi out{target, std::nullopt};
  if (settings_.occluderVisibility) {
    out.occlusion = graph.createImage("gi.resolve-occlusion", {VK_FORMAT_R32_UINT});
    declarePass(graph, f, "gi-resolve-find-occluders", findOccluders_, reservoirs,
                gpu::GI_RESOLVE_VISIBILITY_BINDING_OUTPUT, *out.occlusion, RayListUse::Fills);
    declarePass(graph, f, "gi-trace-resolve-visibility", visibility_, reservoirs,
                gpu::GI_RESOLVE_VISIBILITY_BINDING_OUTPUT, *out.occlusion, RayListUse::Walks);
  }
  graph::PassBuilder resolve =
      declarePass(graph, f, "gi-restir-resolve", resolve_, reservoirs,
                  gpu::GI_RESOLVE_BINDING_OUTPUT, target, RayListUse::None);
  if (out.occlusion)
    resolve.read(*out.occlusion, Access::SampledRead, gpu::GI_RESOLVE_BINDING_OCCLUSION);
  else  // the shader ignores the binding without gi-trace-resolve-visibility
    resolve.readPlaceholder(f.in.gbuffer.flags, gpu::GI_RESOLVE_BINDING_OCCLUSION,
                            Access::SampledRead);
  return out;
}

// The three passes read the same reservoir and GBuffer images (the resolve's bindings) and write
// one image each. gi-resolve-find-occluders fills GI_RAY_LIST_RESOLVE and writes every pixel;
// gi-trace-resolve-visibility walks the list, traces, and writes the listed pixels only
// (StorageReadWrite: the others keep their values).
graph::PassBuilder ResolveStage::declarePass(graph::FrameGraph& graph, const RestirFrame& f,
                                             const char* name, RestirGiPass& pass,
                                             const Reservoirs& reservoirs, uint32_t outputBinding,
                                             graph::ImageHandle output, RayListUse rayList) {
  const GBuffer& g = f.in.gbuffer;
  graph::PassBuilder b = graph.addPass(name, graph::QueueKind::Compute);
  const Access outputAccess =
      rayList == RayListUse::Walks ? Access::StorageReadWrite : Access::StorageWrite;
  b.read(f.in.frame.constants, Access::StorageRead)
      .write(output, outputAccess, outputBinding)
      .read(g.normals, Access::SampledRead, gpu::GI_RESOLVE_BINDING_NORMALS)
      .read(g.depth.current, Access::SampledRead, gpu::GI_RESOLVE_BINDING_DEPTH)
      .read(g.flags, Access::SampledRead, gpu::GI_RESOLVE_BINDING_FLAGS);
  for (uint32_t i = 0; i < 4; ++i)
    b.read(reservoirs.reservoir[i], Access::SampledRead, gpu::GI_RESOLVE_BINDING_RESERVOIR + i);
  if (rayList == RayListUse::Fills) b.write(f.rayLists, Access::StorageReadWrite);
  if (rayList == RayListUse::Walks)
    b.read(f.in.frame.instances, Access::StorageRead)
        .read(f.in.frame.tlas, Access::StorageRead)
        .read(f.rayLists, Access::IndirectRead)
        .read(f.rayLists, Access::StorageRead);
  b.record([f, &pass, rayList](VkCommandBuffer cmd, const graph::PassResources& r) {
    if (rayList == RayListUse::Walks)
      pass.recordOverRayList(cmd, r, f.rayListConstants(r), f.rayLists, gpu::GI_RAY_LIST_RESOLVE);
    else if (rayList == RayListUse::Fills)
      pass.record(cmd, r, f.rayListConstants(r), f.in.frame.resolution);
    else
      pass.record(cmd, r, f.passConstants(false), f.in.frame.resolution);
  });
  return b;
}

}  // namespace bounce
