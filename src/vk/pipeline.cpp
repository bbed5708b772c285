#include "vk/pipeline.h"

#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "vk/check.h"
#include "vk/pipeline_log.h"
#include "vk/shader_registry.h"

namespace bounce::vk {

DescriptorSetLayout::DescriptorSetLayout(Context& context, const std::vector<Binding>& bindings)
    : context_(&context), bindings_(bindings) {
  std::vector<VkDescriptorSetLayoutBinding> vkBindings;
  for (const Binding& b : bindings)
    vkBindings.push_back({b.binding, b.type, b.count, VK_SHADER_STAGE_ALL, nullptr});
  VkDescriptorSetLayoutCreateInfo ci{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  ci.bindingCount = uint32_t(vkBindings.size());
  ci.pBindings = vkBindings.data();
  VK_CHECK(vkCreateDescriptorSetLayout(context.device(), &ci, nullptr, &layout_));
}

DescriptorSetLayout::~DescriptorSetLayout() {
  if (context_ && layout_) vkDestroyDescriptorSetLayout(context_->device(), layout_, nullptr);
}

DescriptorSetLayout& DescriptorSetLayout::operator=(DescriptorSetLayout&& o) noexcept {
  if (this != &o) {
    if (context_ && layout_) vkDestroyDescriptorSetLayout(context_->device(), layout_, nullptr);
    context_ = std::exchange(o.context_, nullptr);
    layout_ = std::exchange(o.layout_, VK_NULL_HANDLE);
    bindings_ = std::move(o.bindings_);
  }
  return *this;
}

DescriptorPool::DescriptorPool(Context& context, uint32_t maxSets, uint32_t perType)
    : context_(context) {
  std::vector<VkDescriptorPoolSize> sizes = {
      {VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, perType},
      {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, perType},
      {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, perType},
      {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, perType},
      {VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE, perType},
  };
  VkDescriptorPoolCreateInfo ci{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  ci.maxSets = maxSets;
  ci.poolSizeCount = uint32_t(sizes.size());
  ci.pPoolSizes = sizes.data();
  VK_CHECK(vkCreateDescriptorPool(context.device(), &ci, nullptr, &pool_));
}

DescriptorPool::~DescriptorPool() {
  vkDestroyDescriptorPool(context_.device(), pool_, nullptr);
}

VkDescriptorSet DescriptorPool::allocate(const DescriptorSetLayout& layout) {
  VkDescriptorSetLayout l = layout.handle();
  VkDescriptorSetAllocateInfo ai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  ai.descriptorPool = pool_;
  ai.descriptorSetCount = 1;
  ai.pSetLayouts = &l;
  VkDescriptorSet set;
  VK_CHECK(vkAllocateDescriptorSets(context_.device(), &ai, &set));
  return set;
}

VkShaderModule createShaderModule(const Context& context, const std::string& shader) {
  std::span<const uint32_t> spirv = embeddedShader(shader);
  VkShaderModuleCreateInfo mi{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
  mi.codeSize = spirv.size_bytes();
  mi.pCode = spirv.data();
  VkShaderModule module = VK_NULL_HANDLE;
  VK_CHECK(vkCreateShaderModule(context.device(), &mi, nullptr, &module));
  return module;
}

VkPipelineLayout createPipelineLayout(const Context& context,
                                      const std::vector<const DescriptorSetLayout*>& setLayouts,
                                      uint32_t pushConstantBytes,
                                      VkShaderStageFlags pushConstantStages) {
  std::vector<VkDescriptorSetLayout> layouts;
  for (const DescriptorSetLayout* l : setLayouts) layouts.push_back(l->handle());
  VkPushConstantRange range{pushConstantStages, 0, pushConstantBytes};
  VkPipelineLayoutCreateInfo li{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  li.setLayoutCount = uint32_t(layouts.size());
  li.pSetLayouts = layouts.data();
  li.pushConstantRangeCount = pushConstantBytes ? 1 : 0;
  li.pPushConstantRanges = &range;
  VkPipelineLayout layout = VK_NULL_HANDLE;
  VK_CHECK(vkCreatePipelineLayout(context.device(), &li, nullptr, &layout));
  return layout;
}

namespace {

std::string statisticValue(const VkPipelineExecutableStatisticKHR& s) {
  switch (s.format) {
    case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_BOOL32_KHR:
      return s.value.b32 ? "yes" : "no";
    case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_INT64_KHR:
      return std::to_string(s.value.i64);
    case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_UINT64_KHR:
      return std::to_string(s.value.u64);
    case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_FLOAT64_KHR:
      return fmt::format("{:g}", s.value.f64);
    default:
      return "?";
  }
}

}  // namespace

// One line per executable of the pipeline on stderr: the shader, then the driver's statistics
// as name=value (on NVIDIA the register count and spills: what bounds a pass's occupancy).
void printPipelineStatistics(Context& context, VkPipeline pipeline, const std::string& name) {
  auto properties = reinterpret_cast<PFN_vkGetPipelineExecutablePropertiesKHR>(
      vkGetDeviceProcAddr(context.device(), "vkGetPipelineExecutablePropertiesKHR"));
  auto statistics = reinterpret_cast<PFN_vkGetPipelineExecutableStatisticsKHR>(
      vkGetDeviceProcAddr(context.device(), "vkGetPipelineExecutableStatisticsKHR"));
  if (!properties || !statistics) return;
  VkPipelineInfoKHR info{VK_STRUCTURE_TYPE_PIPELINE_INFO_KHR, nullptr, pipeline};
  uint32_t executables = 0;
  if (properties(context.device(), &info, &executables, nullptr) != VK_SUCCESS) return;
  for (uint32_t i = 0; i < executables; ++i) {
    VkPipelineExecutableInfoKHR executable{VK_STRUCTURE_TYPE_PIPELINE_EXECUTABLE_INFO_KHR, nullptr,
                                           pipeline, i};
    uint32_t count = 0;
    if (statistics(context.device(), &executable, &count, nullptr) != VK_SUCCESS) continue;
    std::vector<VkPipelineExecutableStatisticKHR> values(
        count, {VK_STRUCTURE_TYPE_PIPELINE_EXECUTABLE_STATISTIC_KHR});
    if (statistics(context.device(), &executable, &count, values.data()) != VK_SUCCESS) continue;
    std::string line = fmt::format("bounce: pipeline statistics: {}", name);
    for (const VkPipelineExecutableStatisticKHR& v : values)
      line += fmt::format(" | {}={}", v.name, statisticValue(v));
    fmt::print(stderr, "{}\n", line);
  }
}

ComputePipeline::ComputePipeline(Context& context, const std::string& shader,
                                 const std::vector<const DescriptorSetLayout*>& setLayouts,
                                 uint32_t pushConstantBytes,
                                 std::span<const uint32_t> specialization)
    : context_(&context), name_(shader) {
  VkShaderModule module = createShaderModule(context, shader);
  layout_ =
      createPipelineLayout(context, setLayouts, pushConstantBytes, VK_SHADER_STAGE_COMPUTE_BIT);

  VkComputePipelineCreateInfo ci{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
  ci.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
  ci.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
  ci.stage.module = module;
  ci.stage.pName = "main";
  std::vector<VkSpecializationMapEntry> entries;
  for (uint32_t i = 0; i < specialization.size(); ++i)
    entries.push_back({i, uint32_t(i * sizeof(uint32_t)), sizeof(uint32_t)});
  VkSpecializationInfo si{uint32_t(entries.size()), entries.data(), specialization.size_bytes(),
                          specialization.data()};
  if (!specialization.empty()) ci.stage.pSpecializationInfo = &si;
  ci.layout = layout_;
  if (context.pipelineStatistics()) ci.flags |= VK_PIPELINE_CREATE_CAPTURE_STATISTICS_BIT_KHR;
  const HostCost start = HostCost::now();
  VkResult r =
      vkCreateComputePipelines(context.device(), VK_NULL_HANDLE, 1, &ci, nullptr, &pipeline_);
  logIndex_ = logPipelineCreated(shader, HostCost::now() - start);
  vkDestroyShaderModule(context.device(), module, nullptr);
  if (r != VK_SUCCESS) fail("creating compute pipeline '{}' failed: {}", shader, resultName(r));
  if (context.pipelineStatistics()) printPipelineStatistics(context, pipeline_, shader);
  context.setObjectName(uint64_t(pipeline_), VK_OBJECT_TYPE_PIPELINE, shader);
}

ComputePipeline::~ComputePipeline() {
  if (!context_) return;
  vkDestroyPipeline(context_->device(), pipeline_, nullptr);
  vkDestroyPipelineLayout(context_->device(), layout_, nullptr);
}

ComputePipeline& ComputePipeline::operator=(ComputePipeline&& o) noexcept {
  if (this != &o) {
    this->~ComputePipeline();
    context_ = std::exchange(o.context_, nullptr);
    name_ = std::move(o.name_);
    layout_ = std::exchange(o.layout_, VK_NULL_HANDLE);
    pipeline_ = std::exchange(o.pipeline_, VK_NULL_HANDLE);
    logIndex_ = o.logIndex_;
    bound_ = o.bound_;
  }
  return *this;
}

void ComputePipeline::bind(VkCommandBuffer cmd, const std::vector<VkDescriptorSet>& sets) const {
  if (!bound_) markPipelineUsed(logIndex_);
  bound_ = true;
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_);
  if (!sets.empty())
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_, 0, uint32_t(sets.size()),
                            sets.data(), 0, nullptr);
}

void ComputePipeline::dispatchCovering(VkCommandBuffer cmd, uint32_t width, uint32_t height,
                                       uint32_t groupWidth, uint32_t groupHeight) {
  vkCmdDispatch(cmd, (width + groupWidth - 1) / groupWidth,
                (height + groupHeight - 1) / groupHeight, 1);
}

void computeBarrier(VkCommandBuffer cmd) {
  VkMemoryBarrier2 barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
  barrier.srcStageMask = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_COPY_BIT;
  barrier.srcAccessMask = VK_ACCESS_2_SHADER_WRITE_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT;
  barrier.dstStageMask = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_COPY_BIT;
  barrier.dstAccessMask =
      VK_ACCESS_2_SHADER_READ_BIT | VK_ACCESS_2_SHADER_WRITE_BIT | VK_ACCESS_2_TRANSFER_READ_BIT;
  VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  dep.memoryBarrierCount = 1;
  dep.pMemoryBarriers = &barrier;
  vkCmdPipelineBarrier2(cmd, &dep);
}

}  // namespace bounce::vk
