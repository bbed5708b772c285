// Deforming meshes on the GPU (docs/ray-tracing.md, "Deforming meshes"). At load it uploads the
// rest (bind-pose) vertices of every skinned or morphed mesh, their joints, weights and morph
// deltas, and the refit plan of each one's BLAS. Per frame it stages the pose (joint matrices
// and morph weights, scene/deformation.h) and records, in the frame's scene-update:
//   scene-deform      poses every deforming vertex into the scene's vertex streams and keeps
//                     the pose before it in the previous positions (motion vectors);
//   scene-refit-blas  copies the posed positions into those meshes' triangles, refits their
//                     BLAS (either layout) and writes their new object-space boxes, which the
//                     TLAS refit that follows reads.
// Nothing is rebuilt and nothing allocated per frame; the trees keep the topology they were
// built with for the rest pose.
#pragma once
#include <vector>

#include <vulkan/vulkan.h>

#include "rt/scene_bvh.h"
#include "scene/deformation.h"
#include "scene/scene.h"
#include "shared/deform_io.h"
#include "vk/pipeline.h"
#include "vk/resources.h"

namespace bounce {

class GpuDeformer {
 public:
  // The device arrays of the scene that deformation rewrites (GpuScene's).
  struct SceneArrays {
    VkDeviceAddress positions = 0;
    VkDeviceAddress previousPositions = 0;
    VkDeviceAddress normals = 0;
    VkDeviceAddress tangents = 0;
    VkDeviceAddress triangles = 0;
    VkDeviceAddress blasNodes = 0;
    VkDeviceAddress geometries = 0;
    VkDeviceAddress indices = 0;
    VkDeviceAddress meshBounds = 0;  // vec4[2 * meshes], read by the TLAS refit
  };

  // `scene` holds the rest streams (Scene::meshes as loaded); `bvh` was built over the same
  // meshes posed in their rest pose. Throws bounce::Error for a skin of more than 65,536 joints.
  GpuDeformer(vk::Context& context, const Scene& scene, const rt::SceneBvh& bvh,
              const SceneArrays& arrays);
  GpuDeformer(const GpuDeformer&) = delete;
  GpuDeformer& operator=(const GpuDeformer&) = delete;

  // Stages the pose for the next record(); nothing reaches the GPU before it. The caller must
  // not call it while a recorded frame still executes (the hybrid frame submits and waits).
  void setPose(const DeformationPose& pose);
  // Records the staged pose's upload, scene-deform and scene-refit-blas, and a barrier that
  // makes their writes visible to every later command. In the first frame after a pose without
  // a new one, it re-poses the same pose so that the previous positions catch up (a mesh that
  // stopped has no motion vectors). Returns true when the meshes' boxes changed (the TLAS must
  // then be refitted).
  bool record(VkCommandBuffer cmd);

  uint32_t vertexCount() const { return vertexCount_; }
  uint32_t meshCount() const { return uint32_t(meshes_.size()); }

 private:
  void uploadRest(const Scene& scene, const rt::SceneBvh& bvh);
  void uploadPlans(const Scene& scene, const rt::SceneBvh& bvh);
  void recordDeform(VkCommandBuffer cmd, bool keepPrevious);
  void recordRefit(VkCommandBuffer cmd);

  vk::Context& context_;
  SceneArrays arrays_;
  rt::BvhLayout layout_ = rt::BvhLayout::Binary;
  uint32_t vertexCount_ = 0;
  uint32_t jointCount_ = 0;
  uint32_t weightCount_ = 0;
  std::vector<gpu::GpuRefitBlas> meshes_;
  vk::Buffer geometries_;        // GpuDeformGeometry[]
  vk::Buffer geometryOfVertex_;  // uint[]
  vk::Buffer rest_;              // GpuDeformVertex[]
  vk::Buffer deltas_;            // GpuMorphDelta[]
  vk::Buffer refitMeshes_;       // GpuRefitBlas[]
  vk::Buffer plan_;              // uint[]
  vk::Buffer wideBoxes_;         // vec4[2 * BLAS nodes] (wide layout)
  vk::Buffer pose_;              // [joint rows | morph weights], device
  vk::Buffer poseStaging_;       // the same, mapped
  vk::ComputePipeline deformPipeline_;
  vk::ComputePipeline refitPipeline_;
  bool posePending_ = false;
  bool posed_ = false;            // a pose has reached the GPU
  bool previousDiffers_ = false;  // the previous positions hold an older pose than the current
};

}  // namespace bounce
