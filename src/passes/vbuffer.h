// `vbuffer` (DESIGN.md §4): which triangle is seen at each pixel (instance, geometry,
// primitive ids), either rasterised (seed 000; shaders/passes/vbuffer.vert and
// vbuffer_{opaque,alpha_test}.frag, draws culled against the frustum) or traced, one camera ray
// per pixel centre through the BVH (shaders/passes/vbuffer_trace.comp: for GPUs with little
// raster hardware). Both give the same ids.
#pragma once
#include <vector>

#include <glm/glm.hpp>

#include "graph/frame_graph.h"
#include "passes/frame_context.h"
#include "passes/image_pass.h"
#include "scene/scene.h"
#include "vk/graphics_pipeline.h"

namespace bounce {

// How the vbuffer finds the triangle at each pixel: rasterisation (seed 000) or one camera ray
// per pixel centre through the BVH (for GPUs with little raster hardware, e.g. H100/H200).
enum class VBufferMode { Raster, Trace };
std::optional<VBufferMode> vbufferModeFromName(const std::string& name);  // "raster", "trace"

struct VBuffer {
  graph::ImageHandle ids;  // vbuffer.ids: rgba32ui, VBUFFER_NO_HIT where the sky is seen
};

class VBufferPass {
 public:
  VBufferPass(vk::Context& context, const GpuScene& gpuScene, const Scene& scene, VBufferMode mode);
  VBuffer declare(graph::FrameGraph& graph, const FrameContext& frame);

 private:
  struct Draw {
    uint32_t instance;
    uint32_t geometry;  // global
    uint32_t triangles;
    // A deforming mesh's box is known on the GPU only (scene-refit-blas): never culled.
    bool deforms;
  };
  // The draws whose instance box meets the camera's frustum, opaque ones first.
  void cullDraws(const glm::mat4& viewProjection);
  void draw(VkCommandBuffer cmd, VkDeviceAddress frameConstants, const graph::ResolvedImage& ids,
            const graph::ResolvedImage& depth) const;

  const GpuScene& gpuScene_;
  VBufferMode mode_;
  vk::GraphicsPipeline opaque_, alphaTest_;
  ImageComputePass trace_;
  std::vector<Draw> opaqueDraws_, alphaTestedDraws_;  // every (instance, geometry) with triangles
  std::vector<Draw> visibleOpaque_, visibleAlphaTested_;  // this frame's, capacity reserved once
};

}  // namespace bounce
