// A Scene on the GPU: BVHs built on the CPU (src/rt/scene_bvh.h), textures packed into arrays
// (src/scene/texture_pack.h), everything uploaded once, and the descriptor set (set 0) that
// every tracing shader binds (shaders/rt/scene.glsl). The CPU copies stay available for the
// CPU reference tracer and tests.
#pragma once
#include <memory>
#include <vector>

#include "rt/scene_bvh.h"
#include "scene/scene.h"
#include "scene/texture_pack.h"
#include "vk/pipeline.h"
#include "vk/resources.h"

namespace bounce {

struct GpuSceneStats {
  double bvhBuildSeconds = 0.0;
  double uploadSeconds = 0.0;
  uint64_t triangles = 0;        // as seen by rays (instanced)
  uint64_t uniqueTriangles = 0;  // in BLASes
  uint64_t bvhBytes = 0;         // BLAS + TLAS nodes + triangles
  uint64_t textureBytes = 0;
  uint64_t totalBytes = 0;
};

class GpuScene {
 public:
  GpuScene(vk::Context& context, const Scene& scene);
  ~GpuScene();
  GpuScene(const GpuScene&) = delete;
  GpuScene& operator=(const GpuScene&) = delete;

  const vk::DescriptorSetLayout& setLayout() const { return setLayout_; }
  VkDescriptorSet descriptorSet() const { return set_; }
  const rt::SceneBvh& bvh() const { return bvh_; }
  const Aabb& bounds() const { return bounds_; }
  const PackedTextures& textures() const { return textures_; }
  const GpuSceneStats& stats() const { return stats_; }
  // Accepts or rejects an alpha-tested candidate hit exactly as the GPU alpha test does.
  bool alphaAccepts(uint32_t globalGeometry, uint32_t primitive, float b1, float b2) const;

 private:
  void uploadArrays();
  void uploadTextures();
  void writeDescriptors();

  vk::Context& context_;
  rt::SceneBvh bvh_;
  Aabb bounds_;
  PackedTextures textures_;
  GpuSceneStats stats_;
  std::vector<vk::Buffer> buffers_;
  vk::Buffer refs_;
  std::vector<vk::Image> textureImages_;  // one per binding slot (1x1 placeholder when unused)
  VkSampler sampler_ = VK_NULL_HANDLE;
  vk::DescriptorSetLayout setLayout_;
  std::unique_ptr<vk::DescriptorPool> pool_;
  VkDescriptorSet set_ = VK_NULL_HANDLE;
};

}  // namespace bounce
