// `shadows-trace` (DESIGN.md §4): one sun shadow ray per pixel of the shadow resolution
// (render resolution / ShadowSettings::divisor), its direction sampled in the sun's cone so
// that penumbrae are soft after `shadows-denoise` (shaders/passes/shadows_trace.comp).
#pragma once
#include "graph/frame_graph.h"
#include "graph/resource_desc.h"
#include "passes/frame_context.h"
#include "passes/gbuffer.h"
#include "passes/image_pass.h"

namespace bounce {

// How the sun's shadows are traced and filtered.
struct ShadowSettings {
  // Shadow rays are traced at render resolution / divisor (2 = half res on both presets, as
  // seed 000 does; 1 = full res, 4x the rays, no upsampling blur on thin features). 1 to 16.
  uint32_t divisor = 2;
  // The shadow denoiser's running mean spans at most this many frames: more smooths the soft
  // penumbra (one cone sample per pixel per frame) further but lets moving shadows lag. >= 1.
  float maxHistory = 16.0f;

  // The shadow image's size for a render resolution (as the graph sizes shadows.raw).
  VkExtent2D resolution(VkExtent2D render) const {
    return graph::ImageSize::dividedRes(divisor).resolve(render);
  }
};

// The raw, noisy sun visibility at shadow resolution (one sample per pixel).
struct RawShadows {
  // shadows.raw: rg16f, r the visibility, 0 (shadowed) to 1 (lit); g 1 where the blocker moved
  // this frame (gpu::FRAME_FLAG_SCENE_MOVED and its instance placed elsewhere than last frame)
  graph::ImageHandle visibility;
};

class ShadowsTracePass {
 public:
  ShadowsTracePass(vk::Context& context, const GpuScene& scene, const ShadowSettings& settings);
  RawShadows declare(graph::FrameGraph& graph, const FrameContext& frame, const GBuffer& gbuffer);

 private:
  ShadowSettings settings_;
  ImageComputePass pass_;
};

}  // namespace bounce
