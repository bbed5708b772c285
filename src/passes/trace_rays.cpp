#include "passes/trace_rays.h"

namespace bounce {

TraceRaysPass::TraceRaysPass(vk::Context& context, const GpuScene& scene)
    : context_(context),
      scene_(scene),
      pipeline_(context, "rt/trace_rays", {&scene.setLayout()}, sizeof(gpu::TraceRaysConstants),
                scene.specialization()) {}

std::vector<gpu::GpuHit> TraceRaysPass::trace(std::span<const gpu::GpuRay> rays, bool alphaTest) {
  std::vector<gpu::GpuHit> hits(rays.size());
  if (rays.empty()) return hits;
  vk::Buffer rayBuffer =
      vk::uploadVector(context_, rays, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "trace-rays.rays");
  vk::Buffer hitBuffer(context_, hits.size() * sizeof(gpu::GpuHit),
                       VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                       vk::MemoryUse::DeviceOnly, "trace-rays.hits");
  gpu::TraceRaysConstants pc{};
  pc.rays = rayBuffer.address();
  pc.hits = hitBuffer.address();
  pc.rayCount = uint32_t(rays.size());
  pc.flags = alphaTest ? gpu::TRACE_ALPHA_TEST : 0u;
  context_.submitAndWait([&](VkCommandBuffer cmd) {
    pipeline_.bind(cmd, {scene_.descriptorSet()});
    pipeline_.push(cmd, pc);
    vk::ComputePipeline::dispatchCovering(cmd, pc.rayCount, 1, gpu::TRACE_RAYS_GROUP_SIZE, 1);
  });
  vk::downloadBuffer(context_, hitBuffer, std::as_writable_bytes(std::span(hits)));
  return hits;
}

}  // namespace bounce
