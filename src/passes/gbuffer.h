// `gbuffer` (DESIGN.md §4): from the vbuffer's triangle ids to the surface at each pixel (base
// colour, normals, view depth, UVs, motion, emission, flags), one thread per pixel
// (shaders/passes/gbuffer.comp).
#pragma once
#include "graph/frame_graph.h"
#include "passes/frame_context.h"
#include "passes/image_pass.h"
#include "passes/vbuffer.h"

namespace bounce {

// The surface at each pixel, at render resolution; what the lighting and GI passes read.
struct GBuffer {
  graph::ImageHandle baseColor;  // gbuffer.base-color: rgb base colour, a metallic
  graph::ImageHandle normals;    // gbuffer.normals: xy shading, zw geometric (octahedral)
  graph::HistoryImage depth;     // gbuffer.depth: view depth (0: sky), current and previous
  graph::ImageHandle uv;         // gbuffer.uv
  graph::ImageHandle velocity;   // gbuffer.velocity: pixels moved since last frame
  graph::ImageHandle emissive;   // gbuffer.emissive: rgb emission, a roughness
  graph::ImageHandle flags;      // gbuffer.flags: GBUFFER_FLAG_*

  // The images, declared on the graph; the pass that fills them writes every one.
  static GBuffer create(graph::FrameGraph& graph);
};

class GBufferPass {
 public:
  GBufferPass(vk::Context& context, const GpuScene& scene);
  GBuffer declare(graph::FrameGraph& graph, const FrameContext& frame, const VBuffer& vbuffer);

 private:
  ImageComputePass pass_;
};

}  // namespace bounce
