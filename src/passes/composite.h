// `composite` (DESIGN.md §4 step 7): the frame's radiance before exposure: direct sun x its
// denoised visibility, the KHR punctual and directional lights, diffuse GI x albedo,
// reflections, emission, and the sky where no surface is seen (shaders/passes/composite.comp).
#pragma once
#include "graph/frame_graph.h"
#include "passes/frame_context.h"
#include "passes/gbuffer.h"
#include "passes/image_pass.h"
#include "passes/shadows_denoise.h"
#include "passes/sky.h"

namespace bounce {

// The lit signals composite adds to the direct light.
struct IndirectLight {
  graph::ImageHandle diffuse;      // gi.diffuse: radiance per unit albedo (gi/diffuse_gi.h)
  graph::ImageHandle reflections;  // reflections: specular radiance (zero until traced)
};

struct HdrImage {
  graph::ImageHandle radiance;  // composite.hdr: rgba16f, W/(m^2 sr)
};

class CompositePass {
 public:
  CompositePass(vk::Context& context, const GpuScene& scene);
  HdrImage declare(graph::FrameGraph& graph, const FrameContext& frame, const GBuffer& gbuffer,
                   const Shadows& shadows, const SkyImage& sky, const IndirectLight& indirect);

 private:
  ImageComputePass pass_;
};

}  // namespace bounce
