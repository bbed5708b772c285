// The shape shared by Bounce's compute passes: the scene at set 0 (shaders/rt/scene.glsl),
// optionally storage images at set 1 (bindings named by the pass's constants in the shared
// headers), and a push-constant struct that carries the frame's and the pass's buffer addresses.
// Each pass owns one of these; its descriptor set is rewritten every time it records, because
// history images swap every frame (the frame waits for the previous one, so the set is never in
// flight then).
#pragma once
#include <initializer_list>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "graph/pass_resources.h"
#include "rt/gpu_scene.h"
#include "shared/hybrid_frame_io.h"
#include "vk/pipeline.h"

namespace bounce {

// The mask of ComputePass's `sampledBindings` with these bindings set.
constexpr uint64_t bindingMask(std::initializer_list<uint32_t> bindings) {
  uint64_t mask = 0;
  for (uint32_t b : bindings) mask |= uint64_t(1) << b;
  return mask;
}

class ComputePass {
 public:
  // `shader`: embedded name, e.g. "gi/evolve/cache/cache_build_sh"; bindings 0 .. imageCount - 1 of
  // set 1 are storage images (no set 1 when imageCount is 0). `dispatches`: how many times one
  // frame records the pass (each its own descriptor set of the one pipeline, e.g. the iterations
  // of an à-trous filter), at most 8.
  // `specialization`: the pass's own specialization constants, ids PASS_SPEC_FIRST on
  // (shared/scene_layout.h; the scene's come first).
  // `sampledBindings`: bit b set makes binding b a sampled image (`texture2D`, read with
  // texelFetch; declared with Access::SampledRead) instead of a storage image.
  ComputePass(vk::Context& context, const GpuScene& scene, const std::string& shader,
              uint32_t imageCount, uint32_t pushConstantBytes, uint32_t dispatches = 1,
              std::span<const uint32_t> specialization = {}, uint64_t sampledBindings = 0);

  // Binds the pipeline, the scene and the images the pass declared with bindings
  // (graph::PassBuilder::read/write with a binding: every binding of set 1 exactly once) and
  // pushes `constants`; the caller dispatches.
  // `dispatch`: which of this frame's recordings (0 .. dispatches - 1) this is.
  template <typename T>
  void bind(VkCommandBuffer cmd, const T& constants, const graph::PassResources& resources,
            uint32_t dispatch = 0) {
    bindSets(cmd, resources.boundImages(), dispatch);
    pipeline_.push(cmd, constants);
  }
  // The same for a pass without images (imageCount 0), e.g. outside a frame graph.
  template <typename T>
  void bind(VkCommandBuffer cmd, const T& constants) {
    bindSets(cmd, {});
    pipeline_.push(cmd, constants);
  }
  const vk::ComputePipeline& pipeline() const { return pipeline_; }

 private:
  void bindSets(VkCommandBuffer cmd, std::span<const graph::BoundImage> images,
                uint32_t dispatch = 0);
  void writeImage(VkDescriptorSet set, size_t slot, uint32_t binding,
                  const graph::ResolvedImage& image, uint64_t& seen);

  vk::Context& context_;
  const GpuScene& scene_;
  uint32_t imageCount_;
  uint64_t sampledBindings_;
  std::optional<vk::DescriptorSetLayout> layout_;
  std::optional<vk::DescriptorPool> pool_;
  vk::ComputePipeline pipeline_;
  std::vector<VkDescriptorSet> sets_;         // one per dispatch
  std::vector<VkDescriptorImageInfo> infos_;  // scratch, reused: no per-frame allocation
  std::vector<VkWriteDescriptorSet> writes_;
};

// The hybrid frame's per-pixel passes: gpu::HybridPassConstants, one thread per pixel.
class ImageComputePass : public ComputePass {
 public:
  ImageComputePass(vk::Context& context, const GpuScene& scene, const std::string& shader,
                   uint32_t imageCount, uint64_t sampledBindings = 0)
      : ComputePass(context, scene, shader, imageCount, sizeof(gpu::HybridPassConstants), 1, {},
                    sampledBindings) {}

  // bind() with the pass's declared bindings, then covers `extent` with HYBRID_GROUP_SIZE^2
  // groups.
  void record(VkCommandBuffer cmd, const graph::PassResources& resources,
              const gpu::HybridPassConstants& constants, VkExtent2D extent);
};

}  // namespace bounce
