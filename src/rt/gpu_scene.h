// A Scene on the GPU: BVHs built on the CPU (src/rt/scene_bvh.h), textures packed into arrays
// (src/scene/texture_pack.h), everything uploaded once, and the descriptor set (set 0) that
// every tracing shader binds (shaders/rt/scene.glsl). The CPU copies stay available for the
// CPU reference tracer and tests.
#pragma once
#include <array>
#include <memory>
#include <span>
#include <vector>

#include "rt/gpu_deformer.h"
#include "rt/scene_bvh.h"
#include "scene/scene.h"
#include "scene/texture_pack.h"
#include "vk/pipeline.h"
#include "vk/resources.h"

namespace bounce {

// How the TLAS follows moving instances (docs/ray-tracing.md, "Moving instances").
enum class TlasUpdate {
  // The tree built at load is kept and its boxes are refitted on the GPU by scene-refit-tlas
  // (shaders/rt/scene_refit_tlas.comp) in the frame's scene-update pass: no CPU work per frame
  // beyond the instances' matrices, unless the tree has degraded (tlasRebuildRatio below).
  GpuRefit,
  // The TLAS is rebuilt on the CPU (binned SAH) at every setInstanceTransforms and uploaded.
  CpuRebuild,
};

struct GpuSceneOptions {
  // Node layout of the BLAS (`--bvh binary|wide`); the shaders read it from GpuSceneRefs.
  rt::BvhLayout bvhLayout = rt::BvhLayout::Binary;
  TlasUpdate tlasUpdate = TlasUpdate::GpuRefit;
  // GpuRefit: when the refitted tree's SAH cost (rt::tlasSahCost, relative to its root's area)
  // exceeds this many times its cost right after its last build, setInstanceTransforms
  // rebuilds it over the current placement (binned SAH on the CPU) and the next
  // recordInstanceUpload uploads it. The ratio stands in for the traversal work the refit has
  // added (a fresh build's cost, the exact reference, would need the build it avoids); it also
  // follows how costly the placement itself is for any tree. Checking costs a CPU refit and a pass
  // over the nodes at every setInstanceTransforms (docs/ray-tracing.md, "Moving instances", has the
  // timings and why 1.5). 0 = never rebuild (no CPU work per move).
  double tlasRebuildRatio = 1.5;
  // Threads of the BVH build, the calling thread included; 0 = every core
  // (rt::BvhBuildOptions::threadCount). The tree does not depend on it.
  uint32_t bvhBuildThreads = 0;
};

struct GpuSceneStats {
  rt::BvhLayout bvhLayout = rt::BvhLayout::Binary;
  double bvhBuildSeconds = 0.0;
  double uploadSeconds = 0.0;
  uint64_t triangles = 0;        // as seen by rays (instanced)
  uint64_t uniqueTriangles = 0;  // in BLASes
  uint64_t bvhNodeBytes = 0;     // BLAS + TLAS nodes
  uint64_t bvhBytes = 0;         // BLAS + TLAS nodes + triangles
  uint64_t textureBytes = 0;
  uint64_t totalBytes = 0;
};

// The CPU half of GpuScene's constructor: the scene BVH (deforming meshes in their rest pose)
// and, with TlasUpdate::GpuRefit, the refittable TLAS with its plan in `refit`. `bounds`, when
// given, receives the bounds of the scene as built. GpuSceneStats::bvhBuildSeconds times
// exactly this; `bounce bench-rays --build-only` runs it without a device.
rt::SceneBvh buildGpuSceneBvh(const Scene& scene, const GpuSceneOptions& options,
                              rt::TlasRefitState& refit, Aabb* bounds = nullptr);

class GpuScene {
 public:
  GpuScene(vk::Context& context, const Scene& scene, const GpuSceneOptions& options = {});
  ~GpuScene();
  GpuScene(const GpuScene&) = delete;
  GpuScene& operator=(const GpuScene&) = delete;

  const vk::DescriptorSetLayout& setLayout() const { return setLayout_; }
  // The specialization constants of a pipeline that traces this scene (BVH_SPEC_BLAS_LAYOUT:
  // its BLAS layout), for vk::ComputePipeline.
  std::span<const uint32_t> specialization() const { return specialization_; }
  VkDescriptorSet descriptorSet() const { return set_; }
  // The CPU copies of the arrays. With TlasUpdate::GpuRefit the TLAS nodes here are refitted at
  // every setInstanceTransforms while tlasRebuildRatio > 0 (the rebuild check); with 0 they keep
  // the boxes of the last refitCpuTlas() (or of the load) while the GPU's follow every move.
  const rt::SceneBvh& bvh() const { return bvh_; }
  // GpuRefit: refits the CPU copy of the TLAS to the instances' current placement, the same
  // arithmetic as the GPU's (rt::refitTlas), so that a CPU traversal of bvh() answers as the
  // GPU's does. O(instances); nothing to do for CpuRebuild.
  void refitCpuTlas();
  TlasUpdate tlasUpdate() const { return tlasUpdate_; }
  // GpuRefit: TLAS rebuilds since load, and the cost ratio of the last check (refitted tree /
  // tree at its last build; 1 right after a build).
  uint32_t tlasRebuildCount() const { return tlasRefit_.rebuilds; }
  double tlasCostRatio() const { return tlasRefit_.costRatio; }
  const Aabb& bounds() const { return bounds_; }
  const PackedTextures& textures() const { return textures_; }
  // The image bound at texture slot `slot` (0 .. 2 * TEXTURE_SIZE_CLASSES - 1, as in
  // shaders/rt/scene.glsl): a packed array, or a placeholder where the scene has none.
  const vk::Image& textureImage(uint32_t slot) const { return textureImages_.at(slot); }
  const GpuSceneStats& stats() const { return stats_; }
  // Accepts or rejects an alpha-tested candidate hit exactly as the GPU alpha test does.
  bool alphaAccepts(uint32_t globalGeometry, uint32_t primitive, float b1, float b2) const;

  // ---- moving instances ----
  // Places every instance (objectToWorld, one per Scene::instances entry), rebuilds the TLAS on
  // the CPU (CpuRebuild, or GpuRefit when the refitted tree has degraded) and stages both, with the
  // placement before this call as the "previous" one, in a mapped upload buffer made at
  // construction. Nothing reaches the GPU until recordInstanceUpload(). No Vulkan allocation. The
  // caller must not call it while a recorded upload is still executing (the hybrid frame submits
  // and waits). Returns whether any instance now stands elsewhere than before the call.
  bool setInstanceTransforms(std::span<const glm::mat4> objectToWorld);
  // Deforming meshes (rt/gpu_deformer.h): stages their pose for the next recordInstanceUpload.
  // Throws bounce::Error in a scene where nothing deforms.
  void setDeformation(const DeformationPose& pose);
  bool deforms() const { return deformer_ != nullptr; }
  // Copies the staged instances, previous instances and TLAS into the device buffers below
  // (transfer writes; the caller declares them, e.g. on the frame graph), after posing the
  // deforming meshes and refitting their BLAS when a pose was staged (their streams are then
  // made visible to every later command by a barrier of its own). Call once per frame: in the
  // first frame without a new placement or pose it sets previous = current, so motion vectors
  // of objects that stopped return to zero.
  void recordInstanceUpload(VkCommandBuffer cmd);
  // GpuInstance[] as the tracer reads them (refs.instances), last placement's GpuInstance[]
  // (for object motion vectors), and the TLAS nodes (refs.tlasNodes).
  const vk::Buffer& instanceBuffer() const { return buffers_[instanceBufferIndex_]; }
  const vk::Buffer& previousInstanceBuffer() const { return previousInstances_; }
  const vk::Buffer& tlasBuffer() const { return buffers_[tlasBufferIndex_]; }

  // ---- ray counting ----
  // On: every ray traced through shaders/rt/trace.glsl adds one to rayCounter() (a uint).
  // Rewrites the scene's refs and waits for the device; call between frames. Off by default:
  // a counted ray costs a subgroup ballot and, per subgroup, one atomic.
  void setRayCounting(bool on);
  bool rayCounting() const { return refsHost_.rayCounting != 0u; }
  const vk::Buffer& rayCounter() const { return rayCounter_; }

 private:
  void uploadArrays(const Scene& scene);
  void uploadTextures();
  void writeDescriptors();
  void prepareTlasRefit();
  void stageTlasRebuild();
  void recordTlasRebuildUpload(VkCommandBuffer cmd);
  void recordTlasRefit(VkCommandBuffer cmd);
  size_t tlasStagingOffset() const;
  size_t planStagingOffset() const;

  vk::Context& context_;
  TlasUpdate tlasUpdate_ = TlasUpdate::GpuRefit;
  rt::SceneBvh bvh_;
  rt::TlasRefitState tlasRefit_;  // plan and rebuild policy of bvh_.tlasNodes (GpuRefit)
  vk::Buffer refitPlanBuffer_;    // the plan's nodes, then its level starts; planCapacity_ uints
  uint32_t planCapacity_ = 0;     // room for any rebuild's plan (tlasCapacity_ + levels + 1)
  double tlasRebuildRatio_ = 0.0;
  bool tlasRebuildPending_ = false;    // staged nodes and plan wait for recordInstanceUpload
  vk::Buffer meshBoundsBuffer_;        // vec4 min, max per mesh
  vk::ComputePipeline refitPipeline_;  // made at the first refit
  Aabb bounds_;
  PackedTextures textures_;
  GpuSceneStats stats_;
  std::vector<vk::Buffer> buffers_;
  size_t instanceBufferIndex_ = 0;  // in buffers_
  size_t tlasBufferIndex_ = 0;      // in buffers_, room for tlasCapacity_ nodes
  vk::Buffer previousInstances_;
  vk::Buffer previousPositions_;           // only when something deforms
  std::unique_ptr<GpuDeformer> deformer_;  // only when something deforms
  // [instances | previous instances | TLAS nodes | refit plan (GpuRefit)], mapped
  vk::Buffer instanceStaging_;
  uint32_t tlasCapacity_ = 0;
  bool uploadPending_ = false;
  bool previousDiffers_ = false;  // the device's previous instances differ from the current
  vk::Buffer refs_;
  gpu::GpuSceneRefs refsHost_{};              // what refs_ holds
  vk::Buffer rayCounter_;                     // one uint, storage and transfer source/destination
  std::array<uint32_t, 1> specialization_{};  // [BVH_SPEC_BLAS_LAYOUT]
  std::vector<vk::Image> textureImages_;      // one per binding slot (placeholder when unused)
  VkSampler sampler_ = VK_NULL_HANDLE;
  vk::DescriptorSetLayout setLayout_;
  std::unique_ptr<vk::DescriptorPool> pool_;
  VkDescriptorSet set_ = VK_NULL_HANDLE;
};

}  // namespace bounce
