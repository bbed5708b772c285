#include "rt/gpu_deformer.h"

#include <cstring>
#include <numeric>

#include "core/error.h"
#include "shared/deform_io.h"
#include "vk/memory_barrier.h"

namespace bounce {

namespace {

constexpr VkBufferUsageFlags kStorage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;

template <typename T>
vk::Buffer uploadOrPlaceholder(vk::Context& context, std::vector<T> items, const char* name) {
  if (items.empty()) items.emplace_back();
  return vk::uploadVector(context, std::span<const T>(items), kStorage, name);
}

uint32_t packJointPair(uint32_t a, uint32_t b) {
  return a | b << 16;
}

gpu::GpuDeformVertex restVertex(const Geometry& g, size_t v) {
  gpu::GpuDeformVertex r{};
  r.position = g.positions[v];
  r.normal = g.normals[v];
  r.tangent = g.tangents.empty() ? glm::vec4(1.0f, 0.0f, 0.0f, 1.0f) : g.tangents[v];
  if (!g.joints.empty()) {
    r.joints01 = packJointPair(g.joints[v].x, g.joints[v].y);
    r.joints23 = packJointPair(g.joints[v].z, g.joints[v].w);
    r.weights = g.weights[v];
  }
  return r;
}

// Target k's deltas of every vertex of `g`, appended (missing streams are zero).
void appendDeltas(const Geometry& g, std::vector<gpu::GpuMorphDelta>& out) {
  const size_t n = g.positions.size();
  for (const MorphTarget& target : g.morphTargets)
    for (size_t v = 0; v < n; ++v) {
      gpu::GpuMorphDelta d{};
      if (!target.positions.empty()) d.position = target.positions[v];
      if (!target.normals.empty()) d.normal = target.normals[v];
      if (!target.tangents.empty()) d.tangent = target.tangents[v];
      out.push_back(d);
    }
}

uint32_t meshTriangles(const Mesh& mesh) {
  uint32_t n = 0;
  for (const Geometry& g : mesh.geometries) n += g.triangleCount();
  return n;
}

}  // namespace

GpuDeformer::GpuDeformer(vk::Context& context, const Scene& scene, const rt::SceneBvh& bvh,
                         const SceneArrays& arrays)
    : context_(context), arrays_(arrays), layout_(bvh.layout) {
  for (const Skin& skin : scene.skins) {
    if (skin.joints.size() > 0x10000u)
      fail("skin '{}' has {} joints; the GPU skinning packs joint indices in 16 bits", skin.name,
           skin.joints.size());
    jointCount_ += uint32_t(skin.joints.size());
  }
  uploadRest(scene, bvh);
  uploadPlans(scene, bvh);
  const VkDeviceSize poseBytes =
      (3 * jointCount_ + 1) * sizeof(glm::vec4) + (weightCount_ + 1) * sizeof(float);
  pose_ = vk::Buffer(context, poseBytes, kStorage | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                     vk::MemoryUse::DeviceOnly, "scene.deform-pose");
  poseStaging_ = vk::Buffer(context, poseBytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                            vk::MemoryUse::Upload, "scene.deform-pose-staging");
  setPose(restPose(scene));
}

void GpuDeformer::uploadRest(const Scene& scene, const rt::SceneBvh& bvh) {
  std::vector<gpu::GpuDeformGeometry> geometries;
  std::vector<uint32_t> geometryOfVertex;
  std::vector<gpu::GpuDeformVertex> rest;
  std::vector<gpu::GpuMorphDelta> deltas;
  std::vector<uint32_t> jointBase(scene.skins.size());
  std::exclusive_scan(scene.skins.begin(), scene.skins.end(), jointBase.begin(), 0u,
                      [](uint32_t sum, const Skin& s) { return sum + uint32_t(s.joints.size()); });
  for (size_t m = 0; m < scene.meshes.size(); ++m) {
    const Mesh& mesh = scene.meshes[m];
    if (!mesh.deforms()) continue;
    for (size_t gi = 0; gi < mesh.geometries.size(); ++gi) {
      const Geometry& g = mesh.geometries[gi];
      gpu::GpuDeformGeometry d{};
      d.firstVertex = bvh.geometries[bvh.geometryBase[m] + gi].vertexOffset;
      d.vertexCount = uint32_t(g.positions.size());
      d.restBase = uint32_t(rest.size());
      d.jointBase =
          mesh.skin >= 0 && !g.joints.empty() ? jointBase[size_t(mesh.skin)] : gpu::DEFORM_NO_SKIN;
      d.morphBase = uint32_t(deltas.size());
      d.morphCount = uint32_t(g.morphTargets.size());
      d.weightBase = weightCount_;
      for (size_t v = 0; v < g.positions.size(); ++v) {
        rest.push_back(restVertex(g, v));
        geometryOfVertex.push_back(uint32_t(geometries.size()));
      }
      appendDeltas(g, deltas);
      geometries.push_back(d);
    }
    weightCount_ += uint32_t(mesh.morphWeights.size());
  }
  vertexCount_ = uint32_t(rest.size());
  geometries_ = uploadOrPlaceholder(context_, std::move(geometries), "scene.deform-geometries");
  geometryOfVertex_ =
      uploadOrPlaceholder(context_, std::move(geometryOfVertex), "scene.deform-geometry-of-vertex");
  rest_ = uploadOrPlaceholder(context_, std::move(rest), "scene.deform-rest");
  deltas_ = uploadOrPlaceholder(context_, std::move(deltas), "scene.deform-deltas");
}

void GpuDeformer::uploadPlans(const Scene& scene, const rt::SceneBvh& bvh) {
  std::vector<uint32_t> plan;
  for (uint32_t m = 0; m < scene.meshes.size(); ++m) {
    const Mesh& mesh = scene.meshes[m];
    const uint32_t triangles = meshTriangles(mesh);
    if (!mesh.deforms() || triangles == 0) continue;
    const uint32_t root = bvh.blasRoot[m];
    rt::RefitPlan meshPlan = layout_ == rt::BvhLayout::Wide
                                 ? rt::planWideRefit(bvh.blasWideNodes, root)
                                 : rt::planBinaryRefit(bvh.blasNodes, root);
    gpu::GpuRefitBlas r{};
    r.triangleFirst = bvh.blasTriangleBase[m];
    r.triangleCount = triangles;
    r.geometryBase = bvh.geometryBase[m];
    r.mesh = m;
    r.root = root;
    r.planFirst = uint32_t(plan.size());
    r.levelStart = r.planFirst + uint32_t(meshPlan.nodes.size());
    r.levels = meshPlan.levels();
    plan.insert(plan.end(), meshPlan.nodes.begin(), meshPlan.nodes.end());
    plan.insert(plan.end(), meshPlan.levelStart.begin(), meshPlan.levelStart.end());
    meshes_.push_back(r);
  }
  refitMeshes_ = uploadOrPlaceholder(context_, meshes_, "scene.deform-refit-meshes");
  plan_ = uploadOrPlaceholder(context_, std::move(plan), "scene.deform-refit-plan");
  if (layout_ == rt::BvhLayout::Wide)
    wideBoxes_ = vk::Buffer(context_, 2 * sizeof(glm::vec4) * (bvh.blasWideNodes.size() + 1),
                            kStorage, vk::MemoryUse::DeviceOnly, "scene.deform-wide-boxes");
}

void GpuDeformer::setPose(const DeformationPose& pose) {
  if (pose.jointMatrices.size() != jointCount_)
    fail("GpuDeformer::setPose: {} joint matrices for {} joints", pose.jointMatrices.size(),
         jointCount_);
  auto* rows = poseStaging_.mappedAs<glm::vec4>();
  for (const glm::mat4& j : pose.jointMatrices)
    for (int r = 0; r < 3; ++r) *rows++ = glm::vec4(j[0][r], j[1][r], j[2][r], j[3][r]);
  auto* weights =
      reinterpret_cast<float*>(poseStaging_.mappedAs<glm::vec4>() + 3 * jointCount_ + 1);
  for (const std::vector<float>& meshWeights : pose.morphWeights)
    for (float w : meshWeights) *weights++ = w;
  posePending_ = true;
}

bool GpuDeformer::record(VkCommandBuffer cmd) {
  if (vertexCount_ == 0 || (!posePending_ && !previousDiffers_)) return false;
  // The frame before read the streams this rewrites.
  vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_NONE,
                    VK_PIPELINE_STAGE_2_COPY_BIT | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                    VK_ACCESS_2_NONE);
  const bool newPose = posePending_;
  if (newPose) {
    VkBufferCopy copy{0, 0, pose_.size()};
    vkCmdCopyBuffer(cmd, poseStaging_.handle(), pose_.handle(), 1, &copy);
    vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                      VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
  }
  // The first pose replaces the bind pose without motion; a settling frame re-poses the same
  // pose so that the previous positions catch up.
  recordDeform(cmd, posed_);
  if (newPose) {
    vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                      VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                      VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    recordRefit(cmd);
  }
  vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                    VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
                    VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT);
  previousDiffers_ = newPose && posed_;
  posed_ = true;
  posePending_ = false;
  return newPose;
}

void GpuDeformer::recordDeform(VkCommandBuffer cmd, bool keepPrevious) {
  if (!deformPipeline_.handle())
    deformPipeline_ =
        vk::ComputePipeline(context_, "rt/scene_deform", {}, sizeof(gpu::DeformConstants));
  gpu::DeformConstants pc{};
  pc.geometries = geometries_.address();
  pc.geometryOfVertex = geometryOfVertex_.address();
  pc.rest = rest_.address();
  pc.deltas = deltas_.address();
  pc.jointRows = pose_.address();
  pc.morphWeights = pose_.address() + (3 * jointCount_ + 1) * sizeof(glm::vec4);
  pc.positions = arrays_.positions;
  pc.previousPositions = arrays_.previousPositions;
  pc.normals = arrays_.normals;
  pc.tangents = arrays_.tangents;
  pc.vertexCount = vertexCount_;
  pc.keepPrevious = keepPrevious ? 1u : 0u;
  deformPipeline_.bind(cmd, {});
  deformPipeline_.push(cmd, pc);
  vkCmdDispatch(cmd, (vertexCount_ + gpu::DEFORM_GROUP_SIZE - 1) / gpu::DEFORM_GROUP_SIZE, 1, 1);
}

void GpuDeformer::recordRefit(VkCommandBuffer cmd) {
  if (meshes_.empty()) return;
  if (!refitPipeline_.handle())
    refitPipeline_ =
        vk::ComputePipeline(context_, "rt/scene_refit_blas", {}, sizeof(gpu::BlasRefitConstants));
  gpu::BlasRefitConstants pc{};
  pc.meshes = refitMeshes_.address();
  pc.plan = plan_.address();
  pc.blasNodes = arrays_.blasNodes;
  pc.wideBoxes = wideBoxes_ ? wideBoxes_.address() : 0;
  pc.triangles = arrays_.triangles;
  pc.geometries = arrays_.geometries;
  pc.indices = arrays_.indices;
  pc.positions = arrays_.positions;
  pc.meshBounds = arrays_.meshBounds;
  pc.blasLayout = uint32_t(layout_);
  refitPipeline_.bind(cmd, {});
  refitPipeline_.push(cmd, pc);
  vkCmdDispatch(cmd, uint32_t(meshes_.size()), 1, 1);
}

}  // namespace bounce
