#include "rt/gpu_scene.h"

#include <algorithm>
#include <chrono>
#include <cstring>
#include <type_traits>

#include <glm/gtc/packing.hpp>

#include "core/error.h"
#include "scene/deformation.h"
#include "shared/tlas_refit_io.h"

#include "vk/check.h"
#include "vk/memory_barrier.h"

namespace bounce {

namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

template <typename T>
size_t bytesOf(const std::vector<T>& v) {
  return v.size() * sizeof(T);
}

constexpr uint32_t kTextureSlots = 2 * gpu::TEXTURE_SIZE_CLASSES;

// Binding slot of (class, encoding), as in shaders/rt/scene.glsl.
uint32_t textureSlot(uint32_t sizeClass, bool srgb) {
  return sizeClass + (srgb ? gpu::TEXTURE_SIZE_CLASSES : 0u);
}

}  // namespace

rt::SceneBvh buildGpuSceneBvh(const Scene& scene, const GpuSceneOptions& options,
                              rt::TlasRefitState& refit, Aabb* bounds) {
  rt::SceneBvhOptions bvhOptions;
  bvhOptions.layout = options.bvhLayout;
  bvhOptions.blas.threadCount = options.bvhBuildThreads;
  bvhOptions.tlas.threadCount = options.bvhBuildThreads;
  rt::SceneBvh bvh;
  if (scene.deforms()) {
    // Deforming meshes start in their rest pose (a skinned mesh's bind-pose streams are not
    // where its skeleton places it), and their boxes move on the GPU.
    if (options.tlasUpdate != TlasUpdate::GpuRefit)
      fail("{}: deforming meshes need the TLAS refitted on the GPU (TlasUpdate::GpuRefit)",
           scene.name.empty() ? std::string("scene") : scene.name);
    const Scene rest = posedScene(scene, restPose(scene));
    bvh = rt::buildSceneBvh(rest, bvhOptions);
    if (bounds) *bounds = rest.bounds();
  } else {
    bvh = rt::buildSceneBvh(scene, bvhOptions);
    if (bounds) *bounds = scene.bounds();
  }
  // A refitted tree needs a leaf for every instance that may ever show (scene_bvh.h).
  if (options.tlasUpdate == TlasUpdate::GpuRefit)
    rt::buildRefittedTlas(bvh.tlasNodes, refit, bvh.instances, bvh.meshBounds);
  return bvh;
}

GpuScene::GpuScene(vk::Context& context, const Scene& scene, const GpuSceneOptions& options)
    : context_(context),
      tlasUpdate_(options.tlasUpdate),
      tlasRebuildRatio_(options.tlasRebuildRatio) {
  auto start = Clock::now();
  bvh_ = buildGpuSceneBvh(scene, options, tlasRefit_, &bounds_);
  stats_.bvhBuildSeconds = secondsSince(start);
  textures_ = packSceneTextures(scene);
  stats_.triangles = scene.triangleCount();
  stats_.uniqueTriangles = scene.uniqueTriangleCount();

  auto uploadStart = Clock::now();
  uploadArrays(scene);
  uploadTextures();
  writeDescriptors();
  if (tlasUpdate_ == TlasUpdate::GpuRefit) prepareTlasRefit();
  if (scene.deforms()) {
    GpuDeformer::SceneArrays arrays{.positions = refsHost_.positions,
                                    .previousPositions = refsHost_.previousPositions,
                                    .normals = refsHost_.normals,
                                    .tangents = refsHost_.tangents,
                                    .triangles = refsHost_.triangles,
                                    .blasNodes = refsHost_.blasNodes,
                                    .geometries = refsHost_.geometries,
                                    .indices = refsHost_.indices,
                                    .meshBounds = meshBoundsBuffer_.address()};
    deformer_ = std::make_unique<GpuDeformer>(context_, scene, bvh_, arrays);
  }
  stats_.uploadSeconds = secondsSince(uploadStart);
  stats_.totalBytes = context.liveAllocationBytes();
}

GpuScene::~GpuScene() {
  if (sampler_) vkDestroySampler(context_.device(), sampler_, nullptr);
}

void GpuScene::uploadArrays(const Scene& scene) {
  // Storage buffers are limited to 128 MiB per binding on lavapipe (DESIGN.md §1); buffer
  // device addresses have no such per-binding limit but keep each array under it anyway.
  // Transfer source too: tests read arrays back (the refitted TLAS).
  const VkBufferUsageFlags usage =
      VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT;
  // A scene may have no triangles at all (a file whose only geometry was degenerate renders as
  // sky): an empty array still gets a buffer of one zeroed element, never read since every
  // count in the refs is 0, so that every address is valid.
  auto upload = [&](const auto& vec, const char* name) {
    using T = typename std::decay_t<decltype(vec)>::value_type;
    static const T placeholder{};
    std::span<const T> items = vec.empty() ? std::span<const T>(&placeholder, 1) : std::span(vec);
    buffers_.push_back(vk::uploadVector(context_, items, usage, std::string("scene.") + name));
    return buffers_.back().address();
  };
  // A TLAS over n instance leaves has at most max(1, n - 1) nodes; room for n so that any
  // later placement's rebuild fits the buffer made now.
  tlasCapacity_ = std::max<uint32_t>(1, uint32_t(bvh_.instances.size()));
  std::vector<gpu::GpuBvhNode> tlasRoom = bvh_.tlasNodes;
  tlasRoom.resize(std::max<size_t>(tlasRoom.size(), tlasCapacity_));
  gpu::GpuSceneRefs refs{};
  refs.blasNodes = bvh_.layout == rt::BvhLayout::Wide ? upload(bvh_.blasWideNodes, "blas-nodes")
                                                      : upload(bvh_.blasNodes, "blas-nodes");
  refs.blasLayout = uint32_t(bvh_.layout);
  specialization_[gpu::BVH_SPEC_BLAS_LAYOUT] = refs.blasLayout;
  refs.triangles = upload(bvh_.triangles, "triangles");
  refs.tlasNodes = upload(tlasRoom, "tlas-nodes");
  tlasBufferIndex_ = buffers_.size() - 1;
  refs.instances = upload(bvh_.instances, "instances");
  instanceBufferIndex_ = buffers_.size() - 1;
  std::vector<gpu::GpuInstance> previous = bvh_.instances;
  if (previous.empty()) previous.emplace_back();
  previousInstances_ = vk::uploadVector(context_, std::span<const gpu::GpuInstance>(previous),
                                        usage, "scene.previous-instances");
  // A refit plan lists the interior nodes (fewer than tlasCapacity_) and the start of each of
  // at most maxDepth levels, plus the end.
  planCapacity_ = tlasCapacity_ + gpu::BVH_STACK_SIZE / 2 + 1;
  const size_t planBytes =
      tlasUpdate_ == TlasUpdate::GpuRefit ? planCapacity_ * sizeof(uint32_t) : 0;
  instanceStaging_ =
      vk::Buffer(context_, planStagingOffset() + planBytes + 16, VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                 vk::MemoryUse::Upload, "scene.instance-staging");
  refs.geometries = upload(bvh_.geometries, "geometries");
  refs.materials = upload(textures_.materials, "materials");
  refs.indices = upload(bvh_.indices, "indices");
  refs.positions = upload(bvh_.positions, "positions");
  refs.previousPositions = refs.positions;
  if (scene.deforms()) {
    previousPositions_ = vk::uploadVector(context_, std::span<const glm::vec3>(bvh_.positions),
                                          usage, "scene.previous-positions");
    refs.previousPositions = previousPositions_.address();
  }
  refs.normals = upload(bvh_.normals, "normals");
  refs.uvs = upload(bvh_.uvs, "uvs");
  refs.tangents = upload(bvh_.tangents, "tangents");
  refs.colors = bvh_.colors.empty() ? 0 : upload(bvh_.colors, "colors");
  refs.instanceCount = uint32_t(bvh_.instances.size());
  refs.geometryCount = uint32_t(bvh_.geometries.size());
  refs.materialCount = uint32_t(textures_.materials.size());
  refs.triangleCount = uint32_t(bvh_.triangles.size());
  refs.boundsMin = bounds_.empty() ? glm::vec3(0.0f) : bounds_.min;
  refs.boundsMax = bounds_.empty() ? glm::vec3(0.0f) : bounds_.max;
  rayCounter_ = vk::Buffer(context_, 16,
                           VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT |
                               VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                           vk::MemoryUse::DeviceOnly, "scene.ray-counter");
  refs.rayCounter = rayCounter_.address();
  refs.rayCounting = 0u;
  refsHost_ = refs;
  refs_ = vk::uploadBuffer(context_, std::as_bytes(std::span(&refs, 1)),
                           VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, "scene.refs");
  stats_.bvhLayout = bvh_.layout;
  stats_.bvhNodeBytes =
      bytesOf(bvh_.blasNodes) + bytesOf(bvh_.blasWideNodes) + bytesOf(bvh_.tlasNodes);
  stats_.bvhBytes = stats_.bvhNodeBytes + bytesOf(bvh_.triangles);
}

void GpuScene::setRayCounting(bool on) {
  if (rayCounting() == on) return;
  refsHost_.rayCounting = on ? 1u : 0u;
  context_.submitAndWait([&](VkCommandBuffer cmd) {
    vkCmdUpdateBuffer(cmd, refs_.handle(), 0, sizeof(refsHost_), &refsHost_);
    // Later submissions' shaders read the new refs.
    vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                      VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_READ_BIT);
  });
}

void GpuScene::uploadTextures() {
  textureImages_.resize(kTextureSlots);
  const VkImageUsageFlags usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  for (const PackedTextureArray& a : textures_.arrays) {
    VkFormat format = a.srgb ? VK_FORMAT_R8G8B8A8_SRGB : VK_FORMAT_R8G8B8A8_UNORM;
    vk::Image image(context_, format, a.side, a.side, a.layers, a.mipCount, usage,
                    fmt::format("scene.textures.{}.{}", a.srgb ? "srgb" : "linear", a.side));
    vk::uploadImage(context_, image, a.texels, 4);
    stats_.textureBytes += a.texels.size();
    textureImages_[textureSlot(a.sizeClass, a.srgb)] = std::move(image);
  }
  // Unused slots still need a valid image: a white placeholder, never sampled (no material
  // refers to the slot). It has two mips, like every real array (64 x 64 and up, full chains):
  // llvmpipe compiles a shader per "static" texture state, and a single-mip view is a
  // different state (level_zero_only), so 1-mip placeholders made each scene's set of used
  // slots a different compile, missing Mesa's shader cache for every new scene
  // (docs/startup.md).
  const std::vector<uint8_t> white((2 * 2 + 1) * 4, 255);
  for (uint32_t slot = 0; slot < kTextureSlots; ++slot) {
    if (textureImages_[slot].handle()) continue;
    bool srgb = slot >= gpu::TEXTURE_SIZE_CLASSES;
    vk::Image image(context_, srgb ? VK_FORMAT_R8G8B8A8_SRGB : VK_FORMAT_R8G8B8A8_UNORM, 2, 2, 1, 2,
                    usage, "scene.textures.placeholder");
    vk::uploadImage(context_, image, white, 4);
    textureImages_[slot] = std::move(image);
  }

  VkSamplerCreateInfo si{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  si.magFilter = VK_FILTER_LINEAR;
  si.minFilter = VK_FILTER_LINEAR;
  si.mipmapMode = VK_SAMPLER_MIPMAP_MODE_LINEAR;
  si.addressModeU = VK_SAMPLER_ADDRESS_MODE_REPEAT;
  si.addressModeV = VK_SAMPLER_ADDRESS_MODE_REPEAT;
  si.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  si.maxLod = VK_LOD_CLAMP_NONE;
  VK_CHECK(vkCreateSampler(context_.device(), &si, nullptr, &sampler_));
}

void GpuScene::writeDescriptors() {
  std::vector<vk::Binding> bindings = {
      {gpu::SCENE_BINDING_REFS, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER}};
  for (uint32_t slot = 0; slot < kTextureSlots; ++slot)
    bindings.push_back(
        {gpu::SCENE_BINDING_TEXTURES + slot, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER});
  setLayout_ = vk::DescriptorSetLayout(context_, bindings);
  pool_ = std::make_unique<vk::DescriptorPool>(context_, 1, kTextureSlots + 1);
  set_ = pool_->allocate(setLayout_);

  VkDescriptorBufferInfo refsInfo{refs_.handle(), 0, VK_WHOLE_SIZE};
  std::vector<VkDescriptorImageInfo> imageInfos(kTextureSlots);
  std::vector<VkWriteDescriptorSet> writes;
  VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
  w.dstSet = set_;
  w.dstBinding = gpu::SCENE_BINDING_REFS;
  w.descriptorCount = 1;
  w.descriptorType = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
  w.pBufferInfo = &refsInfo;
  writes.push_back(w);
  for (uint32_t slot = 0; slot < kTextureSlots; ++slot) {
    imageInfos[slot] = {sampler_, textureImages_[slot].view(),
                        VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
    VkWriteDescriptorSet t{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    t.dstSet = set_;
    t.dstBinding = gpu::SCENE_BINDING_TEXTURES + slot;
    t.descriptorCount = 1;
    t.descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    t.pImageInfo = &imageInfos[slot];
    writes.push_back(t);
  }
  vkUpdateDescriptorSets(context_.device(), uint32_t(writes.size()), writes.data(), 0, nullptr);
}

size_t GpuScene::tlasStagingOffset() const {
  return 2 * bytesOf(bvh_.instances);
}

size_t GpuScene::planStagingOffset() const {
  return tlasStagingOffset() + tlasCapacity_ * sizeof(gpu::GpuBvhNode);
}

void GpuScene::prepareTlasRefit() {
  // Room for any later rebuild's plan, so that a rebuild allocates nothing.
  const rt::TlasRefitPlan& refitPlan = tlasRefit_.plan;
  std::vector<uint32_t> plan = refitPlan.nodes;
  plan.insert(plan.end(), refitPlan.levelStart.begin(), refitPlan.levelStart.end());
  plan.resize(std::max<size_t>(plan.size(), planCapacity_), 0u);
  refitPlanBuffer_ = vk::uploadVector(context_, std::span<const uint32_t>(plan),
                                      VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "scene.tlas-refit-plan");
  std::vector<glm::vec4> bounds;
  for (const Aabb& b : bvh_.meshBounds) {
    bounds.emplace_back(b.min, 0.0f);
    bounds.emplace_back(b.max, 0.0f);
  }
  if (bounds.empty()) bounds.resize(2);
  meshBoundsBuffer_ = vk::uploadVector(context_, std::span<const glm::vec4>(bounds),
                                       VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "scene.mesh-bounds");
}

void GpuScene::refitCpuTlas() {
  if (tlasUpdate_ == TlasUpdate::GpuRefit)
    rt::refitTlas(bvh_.tlasNodes, tlasRefit_.plan, bvh_.instances, bvh_.meshBounds);
}

bool GpuScene::setInstanceTransforms(std::span<const glm::mat4> objectToWorld) {
  if (objectToWorld.size() != bvh_.instances.size())
    fail("setInstanceTransforms: {} transforms for {} instances", objectToWorld.size(),
         bvh_.instances.size());
  if (bvh_.instances.empty()) return false;
  std::byte* staging = static_cast<std::byte*>(instanceStaging_.mapped());
  const size_t instanceBytes = bytesOf(bvh_.instances);
  std::memcpy(staging + instanceBytes, bvh_.instances.data(), instanceBytes);  // previous
  for (size_t i = 0; i < objectToWorld.size(); ++i)
    rt::setInstanceTransform(bvh_.instances[i], objectToWorld[i]);
  // The previous placement is the staging copy made above.
  const bool moved =
      std::memcmp(staging + instanceBytes, bvh_.instances.data(), instanceBytes) != 0;
  std::memcpy(staging, bvh_.instances.data(), instanceBytes);
  uploadPending_ = true;
  if (tlasUpdate_ == TlasUpdate::GpuRefit) {
    // The rebuild policy (GpuSceneOptions::tlasRebuildRatio); recordInstanceUpload refits.
    if (tlasRebuildRatio_ > 0.0 &&
        rt::updateRefittedTlas(bvh_.tlasNodes, tlasRefit_, bvh_.instances, bvh_.meshBounds,
                               tlasRebuildRatio_))
      stageTlasRebuild();
    return moved;
  }
  bvh_.tlasNodes = rt::buildTlas(bvh_.instances, bvh_.meshBounds);
  if (bvh_.tlasNodes.size() > tlasCapacity_)
    fail("setInstanceTransforms: TLAS of {} nodes exceeds the {} allocated", bvh_.tlasNodes.size(),
         tlasCapacity_);
  std::memcpy(staging + 2 * instanceBytes, bvh_.tlasNodes.data(), bytesOf(bvh_.tlasNodes));
  return moved;
}

// Stages a rebuilt tree's nodes and plan behind the instances, for recordInstanceUpload to
// copy into the buffers made at load.
void GpuScene::stageTlasRebuild() {
  const rt::TlasRefitPlan& plan = tlasRefit_.plan;
  const size_t planSize = plan.nodes.size() + plan.levelStart.size();
  // The same instances give the same leaf count, so the same node count as at load.
  if (bvh_.tlasNodes.size() > tlasCapacity_ || planSize > planCapacity_)
    fail("TLAS rebuild: {} nodes and a plan of {} exceed the {} and {} allocated",
         bvh_.tlasNodes.size(), planSize, tlasCapacity_, planCapacity_);
  std::byte* staging = static_cast<std::byte*>(instanceStaging_.mapped());
  std::memcpy(staging + tlasStagingOffset(), bvh_.tlasNodes.data(), bytesOf(bvh_.tlasNodes));
  std::byte* planBytes = staging + planStagingOffset();
  std::memcpy(planBytes, plan.nodes.data(), bytesOf(plan.nodes));
  std::memcpy(planBytes + bytesOf(plan.nodes), plan.levelStart.data(), bytesOf(plan.levelStart));
  tlasRebuildPending_ = true;
}

void GpuScene::recordTlasRebuildUpload(VkCommandBuffer cmd) {
  // Earlier frames' traversals and refits read the old nodes and plan: the copies wait for
  // them. Only in a rebuild's frame, so a full barrier costs nothing that matters.
  vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_NONE,
                    VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
  VkBufferCopy nodes{tlasStagingOffset(), 0, bytesOf(bvh_.tlasNodes)};
  vkCmdCopyBuffer(cmd, instanceStaging_.handle(), tlasBuffer().handle(), 1, &nodes);
  VkBufferCopy plan{planStagingOffset(), 0,
                    bytesOf(tlasRefit_.plan.nodes) + bytesOf(tlasRefit_.plan.levelStart)};
  vkCmdCopyBuffer(cmd, instanceStaging_.handle(), refitPlanBuffer_.handle(), 1, &plan);
  tlasRebuildPending_ = false;
}

void GpuScene::recordTlasRefit(VkCommandBuffer cmd) {
  // Made at the first move: a scene that never moves never compiles it.
  if (!refitPipeline_.handle())
    refitPipeline_ =
        vk::ComputePipeline(context_, "rt/scene_refit_tlas", {}, sizeof(gpu::TlasRefitConstants));
  // The copies above (instances; a rebuild's nodes and plan) are read by the refit, which
  // overwrites the copied nodes' boxes.
  vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                    VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                    VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  gpu::TlasRefitConstants pc{};
  pc.tlasNodes = tlasBuffer().address();
  pc.instances = instanceBuffer().address();
  pc.meshBounds = meshBoundsBuffer_.address();
  pc.plan = refitPlanBuffer_.address();
  pc.levels = tlasRefit_.plan.levels();
  pc.levelStartOffset = uint32_t(tlasRefit_.plan.nodes.size());
  refitPipeline_.bind(cmd, {});
  refitPipeline_.push(cmd, pc);
  vkCmdDispatch(cmd, 1, 1, 1);
}

void GpuScene::setDeformation(const DeformationPose& pose) {
  if (!deformer_) fail("setDeformation: nothing in the scene deforms");
  deformer_->setPose(pose);
}

void GpuScene::recordInstanceUpload(VkCommandBuffer cmd) {
  const VkDeviceSize instanceBytes = bytesOf(bvh_.instances);
  // Deforming meshes first: their new boxes are what the TLAS refit below reads.
  const bool meshesMoved = deformer_ && deformer_->record(cmd);
  if (!uploadPending_) {
    // Nothing moved since the last upload: the previous placement becomes the current one
    // (still in the staging buffer), so a stopped object has no motion vectors.
    if (previousDiffers_) {
      VkBufferCopy settle{0, 0, instanceBytes};
      vkCmdCopyBuffer(cmd, instanceStaging_.handle(), previousInstances_.handle(), 1, &settle);
      previousDiffers_ = false;
    }
    if (meshesMoved) recordTlasRefit(cmd);
    return;
  }
  VkBufferCopy current{0, 0, instanceBytes};
  VkBufferCopy previous{instanceBytes, 0, instanceBytes};
  vkCmdCopyBuffer(cmd, instanceStaging_.handle(), instanceBuffer().handle(), 1, &current);
  vkCmdCopyBuffer(cmd, instanceStaging_.handle(), previousInstances_.handle(), 1, &previous);
  if (tlasUpdate_ == TlasUpdate::GpuRefit) {
    if (tlasRebuildPending_) recordTlasRebuildUpload(cmd);
    recordTlasRefit(cmd);
  } else {
    VkBufferCopy tlas{2 * instanceBytes, 0, bytesOf(bvh_.tlasNodes)};
    vkCmdCopyBuffer(cmd, instanceStaging_.handle(), tlasBuffer().handle(), 1, &tlas);
  }
  uploadPending_ = false;
  previousDiffers_ = true;
}

bool GpuScene::alphaAccepts(uint32_t globalGeometry, uint32_t primitive, float b1, float b2) const {
  const gpu::GpuGeometry& g = bvh_.geometries.at(globalGeometry);
  const gpu::GpuMaterial& m = textures_.materials.at(g.material);
  uint32_t base = g.firstIndex + 3 * primitive;
  glm::vec2 uv0 = bvh_.uvs[bvh_.indices[base] + g.vertexOffset];
  glm::vec2 uv1 = bvh_.uvs[bvh_.indices[base + 1] + g.vertexOffset];
  glm::vec2 uv2 = bvh_.uvs[bvh_.indices[base + 2] + g.vertexOffset];
  // Same expression order as interpolateUv in shaders/rt/scene.glsl.
  glm::vec2 uv = uv0 * (1.0f - b1 - b2) + uv1 * b1 + uv2 * b2;
  float cutoff = (m.flags & gpu::MATERIAL_ALPHA_BLEND) ? 0.5f : m.alphaCutoff;
  float alpha = materialAlpha(textures_, m, uv);
  if (!bvh_.colors.empty()) {  // as interpolateVertexColor in shaders/rt/scene.glsl
    auto vertexAlpha = [&](uint32_t k) {
      return glm::unpackUnorm4x8(bvh_.colors[bvh_.indices[base + k] + g.vertexOffset]).w;
    };
    alpha *= vertexAlpha(0) * (1.0f - b1 - b2) + vertexAlpha(1) * b1 + vertexAlpha(2) * b2;
  }
  return alpha >= cutoff;
}

}  // namespace bounce
