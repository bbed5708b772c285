// `gbuffer-import` (issue 17, bring your own G-buffer): the host's depth, normal, albedo and
// motion images, imported into the frame graph, turned into Bounce's GBuffer in the encodings
// `gbuffer` writes (shaders/passes/gbuffer_import.comp), so that everything after it (shadows,
// the GI system) runs unchanged. One thread per pixel. The host's contract is
// include/bounce/host_gbuffer.h (formats, layout, extent) and shared/hybrid_frame_io.h.
#pragma once
#include "graph/frame_graph.h"
#include "passes/frame_context.h"
#include "passes/gbuffer.h"
#include "passes/image_pass.h"

namespace bounce {

// The host's images, each in VK_IMAGE_LAYOUT_GENERAL at render resolution with
// VK_IMAGE_USAGE_STORAGE_BIT; `layout` and `externalWrites` are set by the pass.
struct HostGBufferImages {
  graph::ImportedImage depth;   // R32_SFLOAT: view depth, 0 = no surface
  graph::ImportedImage normal;  // R16G16B16A16_SFLOAT: world-space unit normal
  graph::ImportedImage albedo;  // R8G8B8A8_UNORM: linear diffuse albedo
  graph::ImportedImage motion;  // R16G16_SFLOAT: as gbuffer.velocity
};

// Throws bounce::Error naming the image (and `where`) whose format or extent breaks the
// contract, or that has no image or view.
void checkHostGBuffer(const HostGBufferImages& host, VkExtent2D resolution, const char* where);

class GBufferImportPass {
 public:
  GBufferImportPass(vk::Context& context, const GpuScene& scene);
  // Imports the host's images (host.depth, host.normal, host.albedo, host.motion) and declares
  // the pass; returns the GBuffer as GBufferPass::declare does.
  GBuffer declare(graph::FrameGraph& graph, const FrameContext& frame,
                  const HostGBufferImages& host);

 private:
  ImageComputePass pass_;
};

}  // namespace bounce
