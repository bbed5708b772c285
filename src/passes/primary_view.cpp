#include "passes/primary_view.h"

#include <cmath>
#include <cstring>

#include "shared/primary_view_io.h"

namespace bounce {

std::optional<PrimaryViewKind> primaryViewFromName(const std::string& name) {
  if (name == "primary-albedo") return PrimaryViewKind::Albedo;
  if (name == "primary-normal") return PrimaryViewKind::Normal;
  if (name == "primary-depth") return PrimaryViewKind::Depth;
  if (name == "primary-instance") return PrimaryViewKind::Instance;
  if (name == "primary-geometry") return PrimaryViewKind::Geometry;
  return std::nullopt;
}

const char* primaryViewNames() {
  return "primary-albedo, primary-normal, primary-depth, primary-instance, primary-geometry";
}

gpu::GpuCamera makeGpuCamera(const Camera& camera, uint32_t width, uint32_t height,
                             const Aabb& sceneBounds) {
  gpu::GpuCamera g{};
  glm::vec3 forward = glm::normalize(camera.target - camera.position);
  glm::vec3 right = glm::normalize(glm::cross(forward, camera.up));
  glm::vec3 up = glm::cross(right, forward);
  float tanHalf = std::tan(glm::radians(camera.verticalFovDegrees) * 0.5f);
  float aspect = float(width) / float(height);
  g.position = camera.position;
  g.forward = forward;
  g.right = right * tanHalf * aspect;
  g.up = up * tanHalf;
  // Depth range for visualisation: the scene's bounding sphere as seen along `forward`.
  glm::vec3 c = sceneBounds.empty() ? camera.target : sceneBounds.center();
  float radius = sceneBounds.empty() ? 1.0f : 0.5f * glm::length(sceneBounds.extent());
  float centerDepth = glm::dot(c - camera.position, forward);
  g.nearDepth = std::max(0.0f, centerDepth - radius);
  g.farDepth = centerDepth + radius;
  return g;
}

PrimaryViewPass::PrimaryViewPass(vk::Context& context, const GpuScene& scene)
    : context_(context),
      scene_(scene),
      pipeline_(context, "passes/primary_view", {&scene.setLayout()},
                sizeof(gpu::PrimaryViewConstants), scene.specialization()) {}

ImageRGBA32F PrimaryViewPass::render(const Camera& camera, uint32_t width, uint32_t height,
                                     PrimaryViewKind view, vk::GpuTimer* timer) {
  size_t bytes = size_t(width) * height * sizeof(glm::vec4);
  vk::Buffer output(context_, bytes,
                    VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                    vk::MemoryUse::DeviceOnly, "primary-view.output");
  gpu::PrimaryViewConstants pc{};
  pc.camera = makeGpuCamera(camera, width, height, scene_.bounds());
  pc.outputImage = output.address();
  pc.resolution = {width, height};
  pc.view = uint32_t(view);
  pc.alphaTest = 1;
  context_.submitAndWait([&](VkCommandBuffer cmd) {
    if (timer) {
      timer->reset(cmd);
      timer->begin(cmd, "primary-view");
    }
    pipeline_.bind(cmd, {scene_.descriptorSet()});
    pipeline_.push(cmd, pc);
    vk::ComputePipeline::dispatchCovering(cmd, width, height, gpu::PRIMARY_VIEW_GROUP_SIZE,
                                          gpu::PRIMARY_VIEW_GROUP_SIZE);
    if (timer) timer->end(cmd);
  });
  ImageRGBA32F image{int(width), int(height)};
  vk::downloadBuffer(context_, output, std::as_writable_bytes(std::span(image.pixels)));
  return image;
}

}  // namespace bounce
