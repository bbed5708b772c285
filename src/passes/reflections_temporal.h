// `reflections-temporal` (reflections_reuse.h; shaders/passes/reflections_temporal.comp): each
// traced pixel's fresh reflection sample merged with last frame's reservoir of the same surface
// and lobe, history M capped at ReflectionSettings::temporalMaxM. Writes this frame's
// reservoir, reflections.reservoir.* (history, fed back next frame), and
// reflections.reservoir.lobe (history: the roughness test's other side and the chosen sample's
// target, for the history's confidence under motion).
#pragma once
#include "passes/reflections_trace.h"
#include "shared/reflections_reuse_io.h"

namespace bounce {

// What each reuse pass records with: its constants, the traced images' size and extent.
struct ReflectionReuseFrame {
  gpu::ReflectionReuseConstants constants{};
  graph::ImageSize size;
  VkExtent2D extent{};
};

// Creates the four images of a reflection reservoir, `<prefix>.{sample,radiance,origin,normals}`.
ReflectionReservoirImages createReflectionReservoir(graph::FrameGraph& graph,
                                                    const std::string& prefix,
                                                    graph::ImageSize size);

// Binds the pass's images, pushes the constants, covers the traced extent.
void recordReflectionReuse(ComputePass& pass, VkCommandBuffer cmd,
                           const graph::PassResources& resources,
                           const gpu::ReflectionReuseConstants& constants, VkExtent2D extent);

class ReflectionsTemporalPass {
 public:
  ReflectionsTemporalPass(vk::Context& context, const GpuScene& gpuScene);
  ReflectionReservoirImages declare(graph::FrameGraph& graph, const FrameContext& frame,
                                    const GBuffer& gbuffer,
                                    const ReflectionReservoirImages& candidate,
                                    const ReflectionReuseFrame& f);

 private:
  ComputePass pass_;
};

}  // namespace bounce
