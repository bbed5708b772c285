// The shape shared by the hybrid frame's compute passes: the scene at set 0, storage images at
// set 1 (bindings named by the pass's constants in shared/hybrid_frame_io.h), the frame
// constants' address in push constants, one thread per pixel of an image. Each pass owns one
// of these; its descriptor set is rewritten every time it records, because history images swap
// every frame (the frame waits for the previous one, so the set is never in flight then).
#pragma once
#include <string>
#include <utility>
#include <vector>

#include "graph/pass_resources.h"
#include "render/gpu_scene.h"
#include "shared/hybrid_frame_io.h"
#include "vk/pipeline.h"

namespace bounce {

using ImageBinding = std::pair<uint32_t, graph::ResolvedImage>;

class ImageComputePass {
 public:
  // `shader`: embedded name, e.g. "passes/composite"; bindings 0 .. imageCount - 1 are storage
  // images.
  ImageComputePass(vk::Context& context, const GpuScene& scene, const std::string& shader,
                   uint32_t imageCount);

  // Binds every image (each binding exactly once), pushes the constants and covers `extent`
  // with HYBRID_GROUP_SIZE^2 groups.
  void record(VkCommandBuffer cmd, const std::vector<ImageBinding>& images,
              const gpu::HybridPassConstants& constants, VkExtent2D extent);

 private:
  vk::Context& context_;
  const GpuScene& scene_;
  uint32_t imageCount_;
  vk::DescriptorSetLayout layout_;
  vk::DescriptorPool pool_;
  vk::ComputePipeline pipeline_;
  VkDescriptorSet set_ = VK_NULL_HANDLE;
  std::vector<VkDescriptorImageInfo> infos_;  // scratch, reused
  std::vector<VkWriteDescriptorSet> writes_;
};

}  // namespace bounce
