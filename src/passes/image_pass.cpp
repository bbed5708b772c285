#include "passes/image_pass.h"

#include "core/error.h"

namespace bounce {

namespace {

VkDescriptorType imageDescriptorType(uint64_t sampledBindings, uint32_t binding) {
  return (sampledBindings >> binding) & 1u ? VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE
                                           : VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
}

std::vector<vk::Binding> imageBindings(uint32_t count, uint64_t sampledBindings) {
  std::vector<vk::Binding> bindings;
  for (uint32_t i = 0; i < count; ++i)
    bindings.push_back({i, imageDescriptorType(sampledBindings, i)});
  return bindings;
}

std::vector<const vk::DescriptorSetLayout*> setLayouts(
    const GpuScene& scene, const std::optional<vk::DescriptorSetLayout>& images) {
  std::vector<const vk::DescriptorSetLayout*> layouts{&scene.setLayout()};
  if (images) layouts.push_back(&*images);
  return layouts;
}

}  // namespace

ComputePass::ComputePass(vk::Context& context, const GpuScene& scene, const std::string& shader,
                         uint32_t imageCount, uint32_t pushConstantBytes, uint32_t dispatches,
                         std::span<const uint32_t> specialization, uint64_t sampledBindings)
    : context_(context), scene_(scene), imageCount_(imageCount), sampledBindings_(sampledBindings) {
  if (imageCount > 64) fail("pass '{}': {} images, at most 64", shader, imageCount);
  if (imageCount < 64 && (sampledBindings >> imageCount) != 0)
    fail("pass '{}': a sampled binding at or above its {} images", shader, imageCount);
  if (dispatches < 1 || dispatches > 8)
    fail("pass '{}': {} dispatches per frame, expected 1 to 8", shader, dispatches);
  if (imageCount > 0) {
    layout_.emplace(context, imageBindings(imageCount, sampledBindings));
    pool_.emplace(context, dispatches, imageCount * dispatches);
    for (uint32_t i = 0; i < dispatches; ++i) sets_.push_back(pool_->allocate(*layout_));
  }
  std::vector<uint32_t> constants(scene.specialization().begin(), scene.specialization().end());
  if (!specialization.empty()) {
    constants.resize(gpu::PASS_SPEC_FIRST, gpu::BVH_LAYOUT_ANY);
    constants.insert(constants.end(), specialization.begin(), specialization.end());
  }
  pipeline_ = vk::ComputePipeline(context, shader, setLayouts(scene, layout_), pushConstantBytes,
                                  constants);
  infos_.resize(imageCount);
  writes_.resize(imageCount);
}

void ComputePass::bindSets(VkCommandBuffer cmd, std::span<const graph::BoundImage> images,
                           uint32_t dispatch) {
  if (images.size() != imageCount_)
    fail("pass '{}': {} images bound, the shader has {} (its *_BINDING_COUNT)", pipeline_.name(),
         images.size(), imageCount_);
  if (imageCount_ == 0) {
    pipeline_.bind(cmd, {scene_.descriptorSet()});
    return;
  }
  if (dispatch >= sets_.size())
    fail("pass '{}': dispatch {} of a pass made for {}", pipeline_.name(), dispatch, sets_.size());
  VkDescriptorSet set = sets_[dispatch];
  uint64_t seen = 0;  // bit per binding (a pass has far fewer than 64 images)
  for (size_t i = 0; i < images.size(); ++i)
    writeImage(set, i, images[i].binding, images[i].image, seen);
  vkUpdateDescriptorSets(context_.device(), uint32_t(writes_.size()), writes_.data(), 0, nullptr);
  pipeline_.bind(cmd, {scene_.descriptorSet(), set});
}

void ComputePass::writeImage(VkDescriptorSet set, size_t slot, uint32_t binding,
                             const graph::ResolvedImage& image, uint64_t& seen) {
  if (binding >= imageCount_ || (seen >> binding) & 1u)
    fail("pass '{}': binding {} out of range (the shader has {}) or bound twice", pipeline_.name(),
         binding, imageCount_);
  seen |= uint64_t(1) << binding;
  const VkDescriptorType type = imageDescriptorType(sampledBindings_, binding);
  const bool sampledLayout = image.layout == VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
  if ((type == VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE) != sampledLayout)
    fail(
        "pass '{}': binding {} is a {} image of the pass (its sampledBindings) but declared "
        "with {} in the frame graph",
        pipeline_.name(), binding, type == VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE ? "sampled" : "storage",
        sampledLayout ? "Access::SampledRead" : "a storage access");
  infos_[slot] = {VK_NULL_HANDLE, image.view, image.layout};
  VkWriteDescriptorSet& w = writes_[slot];
  w = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
  w.dstSet = set;
  w.dstBinding = binding;
  w.descriptorCount = 1;
  w.descriptorType = type;
  w.pImageInfo = &infos_[slot];
}

void ImageComputePass::record(VkCommandBuffer cmd, const graph::PassResources& resources,
                              const gpu::HybridPassConstants& constants, VkExtent2D extent) {
  bind(cmd, constants, resources);
  vk::ComputePipeline::dispatchCovering(cmd, extent.width, extent.height, gpu::HYBRID_GROUP_SIZE,
                                        gpu::HYBRID_GROUP_SIZE);
}

}  // namespace bounce
