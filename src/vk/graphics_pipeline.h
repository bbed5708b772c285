// Graphics pipelines for dynamic rendering (Vulkan 1.3, no render-pass objects) from embedded
// SPIR-V vertex and fragment shaders. Geometry comes from buffers through device addresses, so
// there is no vertex input state; viewport and scissor are dynamic, so a resize needs no new
// pipeline.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "vk/pipeline.h"

namespace bounce::vk {

struct GraphicsPipelineDesc {
  std::string vertexShader;    // embedded name, e.g. "passes/vbuffer.vert"
  std::string fragmentShader;  // e.g. "passes/vbuffer.frag"
  std::vector<const DescriptorSetLayout*> setLayouts;
  uint32_t pushConstantBytes = 0;  // visible to both stages
  std::vector<VkFormat> colorFormats;
  VkFormat depthFormat = VK_FORMAT_UNDEFINED;
  // Bounce rasterises with reversed Z (near = 1, infinitely far = 0): the nearer fragment has
  // the greater depth.
  VkCompareOp depthCompare = VK_COMPARE_OP_GREATER;
  VkCullModeFlags cullMode = VK_CULL_MODE_NONE;  // rays see both faces; so does the raster
};

class GraphicsPipeline {
 public:
  GraphicsPipeline() = default;
  GraphicsPipeline(Context& context, const GraphicsPipelineDesc& desc);
  ~GraphicsPipeline();
  GraphicsPipeline(GraphicsPipeline&& o) noexcept { *this = std::move(o); }
  GraphicsPipeline& operator=(GraphicsPipeline&& o) noexcept;

  VkPipeline handle() const { return pipeline_; }
  VkPipelineLayout layout() const { return layout_; }

  // Binds the pipeline and `sets` (from set 0), and sets viewport and scissor to `extent`.
  void bind(VkCommandBuffer cmd, const std::vector<VkDescriptorSet>& sets, VkExtent2D extent) const;
  template <typename T>
  void push(VkCommandBuffer cmd, const T& constants) const {
    vkCmdPushConstants(cmd, layout_, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                       sizeof(T), &constants);
  }

 private:
  Context* context_ = nullptr;
  VkPipelineLayout layout_ = VK_NULL_HANDLE;
  VkPipeline pipeline_ = VK_NULL_HANDLE;
  uint32_t logIndex_ = 0;       // its entry in the pipeline log (vk/pipeline_log.h)
  mutable bool bound_ = false;  // logged as used once bound
};

}  // namespace bounce::vk
