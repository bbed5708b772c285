#include "passes/vbuffer.h"

#include "rt/gpu_scene.h"
#include "rt/scene_bvh.h"

namespace bounce {

namespace {

using graph::Access;

constexpr VkFormat kIdsFormat = VK_FORMAT_R32G32B32A32_UINT;
constexpr VkFormat kZBufferFormat = VK_FORMAT_D32_SFLOAT;

vk::GraphicsPipelineDesc rasterPipeline(const GpuScene& gpuScene, const char* fragmentShader) {
  return {.vertexShader = "passes/vbuffer.vert",
          .fragmentShader = fragmentShader,
          .setLayouts = {&gpuScene.setLayout()},
          .pushConstantBytes = sizeof(gpu::VBufferDrawConstants),
          .colorFormats = {kIdsFormat},
          .depthFormat = kZBufferFormat};
}

bool alphaTested(const Scene& scene, uint32_t material) {
  return material < scene.materials.size() &&
         scene.materials[material].alphaMode != AlphaMode::Opaque;
}

// Whether the box is entirely outside one of the frustum's planes, the planes taken from the
// clip-space conditions -w <= x <= w, -w <= y <= w, z <= w (Gribb and Hartmann 2001); with
// reversed Z and an infinite far plane there is no far plane to test.
bool outsideFrustum(const glm::mat4& viewProjection, const Aabb& box) {
  const glm::mat4 rows = glm::transpose(viewProjection);
  const glm::vec4 planes[5] = {rows[3] + rows[0], rows[3] - rows[0], rows[3] + rows[1],
                               rows[3] - rows[1], rows[3] - rows[2]};
  for (const glm::vec4& plane : planes) {
    // The box corner furthest along the plane's normal.
    glm::vec3 corner(plane.x >= 0.0f ? box.max.x : box.min.x,
                     plane.y >= 0.0f ? box.max.y : box.min.y,
                     plane.z >= 0.0f ? box.max.z : box.min.z);
    if (glm::dot(glm::vec3(plane), corner) + plane.w < 0.0f) return true;
  }
  return false;
}

}  // namespace

std::optional<VBufferMode> vbufferModeFromName(const std::string& name) {
  if (name == "raster") return VBufferMode::Raster;
  if (name == "trace") return VBufferMode::Trace;
  return std::nullopt;
}

VBufferPass::VBufferPass(vk::Context& context, const GpuScene& gpuScene, const Scene& scene,
                         VBufferMode mode)
    : gpuScene_(gpuScene),
      mode_(mode),
      opaque_(context, rasterPipeline(gpuScene, "passes/vbuffer_opaque.frag")),
      alphaTest_(context, rasterPipeline(gpuScene, "passes/vbuffer_alpha_test.frag")),
      trace_(context, gpuScene, "passes/vbuffer_trace", gpu::VBUFFER_TRACE_BINDING_COUNT) {
  const rt::SceneBvh& bvh = gpuScene.bvh();
  for (uint32_t i = 0; i < bvh.instances.size(); ++i) {
    const gpu::GpuInstance& instance = bvh.instances[i];
    uint32_t geometryCount = uint32_t(scene.meshes[instance.mesh].geometries.size());
    for (uint32_t g = instance.geometryBase; g < instance.geometryBase + geometryCount; ++g)
      if (bvh.geometries[g].triangleCount > 0)
        (alphaTested(scene, bvh.geometries[g].material) ? alphaTestedDraws_ : opaqueDraws_)
            .push_back(
                {i, g, bvh.geometries[g].triangleCount, scene.meshes[instance.mesh].deforms()});
  }
  visibleOpaque_.reserve(opaqueDraws_.size());
  visibleAlphaTested_.reserve(alphaTestedDraws_.size());
}

VBuffer VBufferPass::declare(graph::FrameGraph& graph, const FrameContext& frame) {
  VBuffer v{graph.createImage("vbuffer.ids", {kIdsFormat})};
  if (mode_ == VBufferMode::Trace) {
    graph.addPass("vbuffer", graph::QueueKind::Compute)
        .read(frame.constants, Access::StorageRead)
        .read(frame.instances, Access::StorageRead)
        .read(frame.tlas, Access::StorageRead)
        .write(v.ids, Access::StorageWrite, gpu::VBUFFER_TRACE_BINDING_IDS)
        .record([this, frame](VkCommandBuffer cmd, const graph::PassResources& r) {
          trace_.record(cmd, r, frame.passConstants(), frame.resolution);
        });
    return v;
  }
  cullDraws(frame.hostConstants->viewProjection);
  graph::ImageHandle zbuffer = graph.createImage("vbuffer.depth", {kZBufferFormat});
  graph.addPass("vbuffer", graph::QueueKind::Graphics)
      .read(frame.constants, Access::StorageRead)
      .read(frame.instances, Access::StorageRead)
      .write(v.ids, Access::ColorAttachmentWrite)
      .write(zbuffer, Access::DepthAttachmentWrite)
      .record([this, frame, v, zbuffer](VkCommandBuffer cmd, const graph::PassResources& r) {
        draw(cmd, frame.constantsAddress, r.image(v.ids), r.image(zbuffer));
      });
  return v;
}

void VBufferPass::draw(VkCommandBuffer cmd, VkDeviceAddress frameConstants,
                       const graph::ResolvedImage& ids, const graph::ResolvedImage& depth) const {
  VkRenderingAttachmentInfo color{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
  color.imageView = ids.view;
  color.imageLayout = ids.layout;
  color.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
  color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  color.clearValue.color.uint32[0] = gpu::VBUFFER_NO_HIT;
  VkRenderingAttachmentInfo zbuffer{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
  zbuffer.imageView = depth.view;
  zbuffer.imageLayout = depth.layout;
  zbuffer.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
  zbuffer.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  zbuffer.clearValue.depthStencil = {0.0f, 0};  // reversed Z: 0 is infinitely far
  VkRenderingInfo info{VK_STRUCTURE_TYPE_RENDERING_INFO};
  info.renderArea = {{0, 0}, ids.extent};
  info.layerCount = 1;
  info.colorAttachmentCount = 1;
  info.pColorAttachments = &color;
  info.pDepthAttachment = &zbuffer;
  vkCmdBeginRendering(cmd, &info);
  for (const auto& [pipeline, draws] :
       {std::pair{&opaque_, &visibleOpaque_}, std::pair{&alphaTest_, &visibleAlphaTested_}}) {
    if (draws->empty()) continue;
    pipeline->bind(cmd, {gpuScene_.descriptorSet()}, ids.extent);
    for (const Draw& d : *draws) {
      pipeline->push(cmd, gpu::VBufferDrawConstants{frameConstants, d.instance, d.geometry});
      vkCmdDraw(cmd, 3 * d.triangles, 1, 0, 0);
    }
  }
  vkCmdEndRendering(cmd);
}

void VBufferPass::cullDraws(const glm::mat4& viewProjection) {
  const rt::SceneBvh& bvh = gpuScene_.bvh();
  for (auto [all, visible] : {std::pair{&opaqueDraws_, &visibleOpaque_},
                              std::pair{&alphaTestedDraws_, &visibleAlphaTested_}}) {
    visible->clear();  // keeps the capacity: no allocation per frame
    for (const Draw& d : *all) {
      const gpu::GpuInstance& instance = bvh.instances[d.instance];
      if (d.deforms ||
          !outsideFrustum(viewProjection,
                          rt::instanceWorldBounds(instance, bvh.meshBounds[instance.mesh])))
        visible->push_back(d);
    }
  }
}

}  // namespace bounce
