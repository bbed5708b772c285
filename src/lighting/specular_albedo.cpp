#include "lighting/specular_albedo.h"

#include "shared/specular_albedo_io.h"
#include "vk/pipeline.h"

namespace bounce {

SpecularAlbedoTable::SpecularAlbedoTable(vk::Context& context)
    : table_(
          context,
          VkDeviceSize(gpu::SPECULAR_ALBEDO_SIZE) * gpu::SPECULAR_ALBEDO_SIZE * 4 * sizeof(float),
          VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
          vk::MemoryUse::DeviceOnly, "specular-albedo-table") {
  vk::ComputePipeline pipeline(context, "lighting/specular_albedo_table", {},
                               sizeof(gpu::SpecularAlbedoTableConstants));
  const gpu::SpecularAlbedoTableConstants push{table_.address()};
  context.submitAndWait([&](VkCommandBuffer cmd) {
    pipeline.bind(cmd, {});
    pipeline.push(cmd, push);
    vk::ComputePipeline::dispatchCovering(cmd, gpu::SPECULAR_ALBEDO_SIZE, gpu::SPECULAR_ALBEDO_SIZE,
                                          gpu::SPECULAR_ALBEDO_GROUP_SIZE,
                                          gpu::SPECULAR_ALBEDO_GROUP_SIZE);
    // Makes the table visible to every later submission's shaders.
    vk::computeBarrier(cmd);
  });
}

}  // namespace bounce
