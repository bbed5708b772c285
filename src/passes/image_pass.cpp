#include "passes/image_pass.h"

#include "core/error.h"

namespace bounce {

namespace {

std::vector<vk::Binding> storageImageBindings(uint32_t count) {
  std::vector<vk::Binding> bindings;
  for (uint32_t i = 0; i < count; ++i) bindings.push_back({i, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE});
  return bindings;
}

}  // namespace

ImageComputePass::ImageComputePass(vk::Context& context, const GpuScene& scene,
                                   const std::string& shader, uint32_t imageCount)
    : context_(context),
      scene_(scene),
      imageCount_(imageCount),
      layout_(context, storageImageBindings(imageCount)),
      pool_(context, 1, imageCount),
      pipeline_(context, shader, {&scene.setLayout(), &layout_}, sizeof(gpu::HybridPassConstants)),
      set_(pool_.allocate(layout_)) {
  infos_.resize(imageCount);
  writes_.resize(imageCount);
}

void ImageComputePass::record(VkCommandBuffer cmd, const std::vector<ImageBinding>& images,
                              const gpu::HybridPassConstants& constants, VkExtent2D extent) {
  if (images.size() != imageCount_)
    fail("pass '{}': {} images bound, {} expected", pipeline_.name(), images.size(), imageCount_);
  std::vector<bool> seen(imageCount_, false);
  for (size_t i = 0; i < images.size(); ++i) {
    auto [binding, image] = images[i];
    if (binding >= imageCount_ || seen[binding])
      fail("pass '{}': binding {} out of range or bound twice", pipeline_.name(), binding);
    seen[binding] = true;
    infos_[i] = {VK_NULL_HANDLE, image.view, image.layout};
    VkWriteDescriptorSet& w = writes_[i];
    w = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    w.dstSet = set_;
    w.dstBinding = binding;
    w.descriptorCount = 1;
    w.descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
    w.pImageInfo = &infos_[i];
  }
  vkUpdateDescriptorSets(context_.device(), uint32_t(writes_.size()), writes_.data(), 0, nullptr);
  pipeline_.bind(cmd, {scene_.descriptorSet(), set_});
  pipeline_.push(cmd, constants);
  vk::ComputePipeline::dispatchCovering(cmd, extent.width, extent.height, gpu::HYBRID_GROUP_SIZE,
                                        gpu::HYBRID_GROUP_SIZE);
}

}  // namespace bounce
