#include "vk/graphics_pipeline.h"

#include <utility>

#include "core/error.h"
#include "vk/check.h"
#include "vk/pipeline_log.h"

namespace bounce::vk {

GraphicsPipeline::GraphicsPipeline(Context& context, const GraphicsPipelineDesc& desc)
    : context_(&context) {
  layout_ = createPipelineLayout(context, desc.setLayouts, desc.pushConstantBytes,
                                 VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT);
  VkShaderModule vertex = createShaderModule(context, desc.vertexShader);
  VkShaderModule fragment = createShaderModule(context, desc.fragmentShader);
  VkPipelineShaderStageCreateInfo stages[2] = {
      {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0, VK_SHADER_STAGE_VERTEX_BIT,
       vertex, "main", nullptr},
      {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0,
       VK_SHADER_STAGE_FRAGMENT_BIT, fragment, "main", nullptr}};

  VkPipelineVertexInputStateCreateInfo vertexInput{
      VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
  VkPipelineInputAssemblyStateCreateInfo assembly{
      VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
  assembly.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
  VkPipelineViewportStateCreateInfo viewport{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
  viewport.viewportCount = 1;
  viewport.scissorCount = 1;
  VkPipelineRasterizationStateCreateInfo raster{
      VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
  raster.polygonMode = VK_POLYGON_MODE_FILL;
  raster.cullMode = desc.cullMode;
  raster.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
  raster.lineWidth = 1.0f;
  VkPipelineMultisampleStateCreateInfo multisample{
      VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
  multisample.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
  VkPipelineDepthStencilStateCreateInfo depth{
      VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
  bool hasDepth = desc.depthFormat != VK_FORMAT_UNDEFINED;
  depth.depthTestEnable = hasDepth;
  depth.depthWriteEnable = hasDepth;
  depth.depthCompareOp = desc.depthCompare;
  std::vector<VkPipelineColorBlendAttachmentState> blends(desc.colorFormats.size());
  for (auto& b : blends)
    b.colorWriteMask = VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT |
                       VK_COLOR_COMPONENT_B_BIT | VK_COLOR_COMPONENT_A_BIT;
  VkPipelineColorBlendStateCreateInfo blend{
      VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
  blend.attachmentCount = uint32_t(blends.size());
  blend.pAttachments = blends.data();
  VkDynamicState dynamicStates[] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
  VkPipelineDynamicStateCreateInfo dynamic{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
  dynamic.dynamicStateCount = 2;
  dynamic.pDynamicStates = dynamicStates;
  VkPipelineRenderingCreateInfo rendering{VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO};
  rendering.colorAttachmentCount = uint32_t(desc.colorFormats.size());
  rendering.pColorAttachmentFormats = desc.colorFormats.data();
  rendering.depthAttachmentFormat = desc.depthFormat;

  VkGraphicsPipelineCreateInfo ci{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO, &rendering};
  ci.stageCount = 2;
  ci.pStages = stages;
  ci.pVertexInputState = &vertexInput;
  ci.pInputAssemblyState = &assembly;
  ci.pViewportState = &viewport;
  ci.pRasterizationState = &raster;
  ci.pMultisampleState = &multisample;
  ci.pDepthStencilState = &depth;
  ci.pColorBlendState = &blend;
  ci.pDynamicState = &dynamic;
  ci.layout = layout_;
  const HostCost start = HostCost::now();
  VkResult r =
      vkCreateGraphicsPipelines(context.device(), VK_NULL_HANDLE, 1, &ci, nullptr, &pipeline_);
  logIndex_ =
      logPipelineCreated(desc.vertexShader + " + " + desc.fragmentShader, HostCost::now() - start);
  vkDestroyShaderModule(context.device(), vertex, nullptr);
  vkDestroyShaderModule(context.device(), fragment, nullptr);
  if (r != VK_SUCCESS)
    fail("creating graphics pipeline '{}' + '{}' failed: {}", desc.vertexShader,
         desc.fragmentShader, resultName(r));
  context.setObjectName(uint64_t(pipeline_), VK_OBJECT_TYPE_PIPELINE, desc.vertexShader);
}

GraphicsPipeline::~GraphicsPipeline() {
  if (!context_) return;
  vkDestroyPipeline(context_->device(), pipeline_, nullptr);
  vkDestroyPipelineLayout(context_->device(), layout_, nullptr);
}

GraphicsPipeline& GraphicsPipeline::operator=(GraphicsPipeline&& o) noexcept {
  if (this != &o) {
    this->~GraphicsPipeline();
    context_ = std::exchange(o.context_, nullptr);
    layout_ = std::exchange(o.layout_, VK_NULL_HANDLE);
    pipeline_ = std::exchange(o.pipeline_, VK_NULL_HANDLE);
    logIndex_ = o.logIndex_;
    bound_ = o.bound_;
  }
  return *this;
}

void GraphicsPipeline::bind(VkCommandBuffer cmd, const std::vector<VkDescriptorSet>& sets,
                            VkExtent2D extent) const {
  if (!bound_) markPipelineUsed(logIndex_);
  bound_ = true;
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_);
  if (!sets.empty())
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout_, 0, uint32_t(sets.size()),
                            sets.data(), 0, nullptr);
  VkViewport viewport{0.0f, 0.0f, float(extent.width), float(extent.height), 0.0f, 1.0f};
  VkRect2D scissor{{0, 0}, extent};
  vkCmdSetViewport(cmd, 0, 1, &viewport);
  vkCmdSetScissor(cmd, 0, 1, &scissor);
}

}  // namespace bounce::vk
