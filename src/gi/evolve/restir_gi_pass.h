// One compute pass of the ReSTIR GI chain: the shared ComputePass shape (scene at set 0, storage
// images at set 1 with bindings named in shared/restir_gi_io.h) with gpu::RestirGiPassConstants
// in push constants (the frame's and the chain's constants by address), one thread per pixel
// of `extent` in RESTIR_GI_GROUP_SIZE^2 groups.
#pragma once
#include <string>
#include <vector>

#include "passes/image_pass.h"
#include "shared/restir_gi_io.h"

namespace bounce {

class RestirGiPass : public ComputePass {
 public:
  RestirGiPass(vk::Context& context, const GpuScene& scene, const std::string& shader,
               uint32_t imageCount)
      : ComputePass(context, scene, shader, imageCount, sizeof(gpu::RestirGiPassConstants)) {}

  // Binds every image (each binding exactly once), pushes the constants, covers `extent`.
  void record(VkCommandBuffer cmd, const std::vector<ImageBinding>& images,
              const gpu::RestirGiPassConstants& constants, VkExtent2D extent) {
    bind(cmd, constants, images);
    vk::ComputePipeline::dispatchCovering(cmd, extent.width, extent.height,
                                          gpu::RESTIR_GI_GROUP_SIZE, gpu::RESTIR_GI_GROUP_SIZE);
  }
};

}  // namespace bounce
