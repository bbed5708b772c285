// Compute pipelines from embedded SPIR-V, their descriptor-set layouts, and a descriptor pool.
// Bindings are named by constants from the shared headers (shaders/shared/*), never by the
// order of calls.
#pragma once
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "vk/context.h"

namespace bounce::vk {

struct Binding {
  uint32_t binding;
  VkDescriptorType type;
  uint32_t count = 1;
};

class DescriptorSetLayout {
 public:
  DescriptorSetLayout() = default;
  DescriptorSetLayout(Context& context, const std::vector<Binding>& bindings);
  ~DescriptorSetLayout();
  DescriptorSetLayout(DescriptorSetLayout&& o) noexcept { *this = std::move(o); }
  DescriptorSetLayout& operator=(DescriptorSetLayout&& o) noexcept;
  VkDescriptorSetLayout handle() const { return layout_; }
  const std::vector<Binding>& bindings() const { return bindings_; }

 private:
  Context* context_ = nullptr;
  VkDescriptorSetLayout layout_ = VK_NULL_HANDLE;
  std::vector<Binding> bindings_;
};

// A pool sized for a fixed number of sets, allocated at initialisation.
class DescriptorPool {
 public:
  DescriptorPool(Context& context, uint32_t maxSets, uint32_t descriptorsPerType);
  ~DescriptorPool();
  DescriptorPool(const DescriptorPool&) = delete;
  DescriptorPool& operator=(const DescriptorPool&) = delete;
  VkDescriptorSet allocate(const DescriptorSetLayout& layout);

 private:
  Context& context_;
  VkDescriptorPool pool_ = VK_NULL_HANDLE;
};

// A shader module of the embedded shader `shader` (e.g. "rt/trace_rays"); the caller destroys it
// once its pipeline is created.
VkShaderModule createShaderModule(const Context& context, const std::string& shader);

// A pipeline layout of `setLayouts` (set i = setLayouts[i]) and, when pushConstantBytes is not 0,
// one push-constant range of that many bytes seen by `pushConstantStages`.
VkPipelineLayout createPipelineLayout(const Context& context,
                                      const std::vector<const DescriptorSetLayout*>& setLayouts,
                                      uint32_t pushConstantBytes,
                                      VkShaderStageFlags pushConstantStages);

// Prints the driver's statistics of `pipeline` (created with
// VK_PIPELINE_CREATE_CAPTURE_STATISTICS_BIT_KHR; Context::pipelineStatistics) to stderr.
void printPipelineStatistics(Context& context, VkPipeline pipeline, const std::string& name);

class ComputePipeline {
 public:
  ComputePipeline() = default;
  // `shader` names an embedded shader, e.g. "rt/trace_rays". `specialization[i]` is the value of
  // specialization constant i (a shader without constant i ignores it).
  ComputePipeline(Context& context, const std::string& shader,
                  const std::vector<const DescriptorSetLayout*>& setLayouts,
                  uint32_t pushConstantBytes, std::span<const uint32_t> specialization = {});
  ~ComputePipeline();
  ComputePipeline(ComputePipeline&& o) noexcept { *this = std::move(o); }
  ComputePipeline& operator=(ComputePipeline&& o) noexcept;

  VkPipeline handle() const { return pipeline_; }
  VkPipelineLayout layout() const { return layout_; }
  const std::string& name() const { return name_; }

  void bind(VkCommandBuffer cmd, const std::vector<VkDescriptorSet>& sets) const;
  template <typename T>
  void push(VkCommandBuffer cmd, const T& constants) const {
    vkCmdPushConstants(cmd, layout_, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(T), &constants);
  }
  // Dispatches enough groups of `groupSize` to cover width x height (x depth) items.
  static void dispatchCovering(VkCommandBuffer cmd, uint32_t width, uint32_t height,
                               uint32_t groupWidth, uint32_t groupHeight);

 private:
  Context* context_ = nullptr;
  std::string name_;
  VkPipelineLayout layout_ = VK_NULL_HANDLE;
  VkPipeline pipeline_ = VK_NULL_HANDLE;
  uint32_t logIndex_ = 0;       // its entry in the pipeline log (vk/pipeline_log.h)
  mutable bool bound_ = false;  // logged as used once bound
};

// A full memory barrier between compute dispatches (and transfers). The frame graph derives
// precise barriers; tests and tools use this.
void computeBarrier(VkCommandBuffer cmd);

}  // namespace bounce::vk
