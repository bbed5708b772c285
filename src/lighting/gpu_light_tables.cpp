#include "lighting/gpu_light_tables.h"

#include <algorithm>
#include <cstring>
#include <span>
#include <string>

#include "core/error.h"
#include "lighting/light_table.h"
#include "rt/gpu_scene.h"
#include "scene/scene.h"
#include "shared/lighting_io.h"

namespace bounce {

namespace {

constexpr VkDeviceSize kAlignment = 16;

VkDeviceSize alignUp(VkDeviceSize n) {
  return (n + kAlignment - 1) / kAlignment * kAlignment;
}

// Where each part of the tables lies in the one buffer: the block first, then the arrays.
struct Layout {
  VkDeviceSize emissive, punctual, alias, distant, materialPdf, hitMap, size;
};

std::span<const gpu::GpuDistantLight> distantWithoutSun(const LightTable& t, const Scene& scene) {
  std::span<const gpu::GpuDistantLight> distant(t.distantLights);
  if (scene.sun.irradiance > 0.0f && !distant.empty()) distant = distant.subspan(1);
  return distant;
}

Layout layoutOf(const LightTable& t, size_t distantCount, size_t hitMapCount) {
  Layout l{};
  VkDeviceSize at = alignUp(sizeof(gpu::LightTables));
  auto place = [&](VkDeviceSize bytes) {
    VkDeviceSize offset = at;
    at = alignUp(at + bytes);
    return offset;
  };
  l.emissive = place(t.emissiveTriangles.size() * sizeof(gpu::GpuEmissiveTriangle));
  l.punctual = place(t.punctualLights.size() * sizeof(gpu::GpuPunctualLight));
  l.alias = place(t.alias.size() * sizeof(gpu::GpuLightAlias));
  l.distant = place(distantCount * sizeof(gpu::GpuDistantLight));
  l.materialPdf = place(t.materialLightAreaPdf.size() * sizeof(float));
  l.hitMap = place(hitMapCount * sizeof(uint32_t));
  l.size = std::max<VkDeviceSize>(at, kAlignment);
  return l;
}

template <typename T>
void put(std::vector<std::byte>& bytes, VkDeviceSize offset, std::span<const T> items) {
  if (!items.empty()) std::memcpy(bytes.data() + offset, items.data(), items.size_bytes());
}

}  // namespace

std::vector<bool> largeEmitterMaterials(const LightTable& lights, const Aabb& bounds) {
  glm::dvec3 e = glm::max(glm::dvec3(bounds.max - bounds.min), glm::dvec3(0.0));
  double boxArea = 2.0 * (e.x * e.y + e.y * e.z + e.z * e.x);
  std::vector<bool> large(lights.materialEmissiveArea.size(), false);
  for (size_t m = 0; m < large.size(); ++m)
    large[m] = lights.materialEmissiveArea[m] > kLargeEmitterFraction * boxArea;
  return large;
}

GpuLightTables::GpuLightTables(vk::Context& context, const GpuScene& gpuScene, const Scene& scene,
                               bool updatable)
    : gpuScene_(gpuScene), scene_(scene) {
  table_ = buildLightTable(scene, gpuScene.bvh());
  std::vector<bool> large = largeEmitterMaterials(table_, gpuScene.bounds());
  if (std::find(large.begin(), large.end(), true) != large.end())
    table_ = buildLightTable(scene, gpuScene.bvh(), large);
  hitMap_ = buildEmissiveHitMap(table_, gpuScene.bvh());
  const Layout layout = layoutOf(table_, distantWithoutSun(table_, scene).size(), hitMap_.size());
  hitMapOffset_ = layout.hitMap;
  localLightCount_ = table_.localLightCount();
  distantLightCount_ = uint32_t(distantWithoutSun(table_, scene).size());
  tables_ = vk::Buffer(context, layout.size,
                       VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                       vk::MemoryUse::DeviceOnly, "gi.lights");
  pack(packed_);
  staging_ = vk::Buffer(context, layout.size, VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                        vk::MemoryUse::Upload, "gi.lights-staging");
  std::memcpy(staging_.mapped(), packed_.data(), packed_.size());
  context.submitAndWait([&](VkCommandBuffer cmd) { recordCopy(cmd); });
  if (!updatable) {  // what only update() needs
    staging_ = vk::Buffer();
    table_ = LightTable{};
    hitMap_ = {};
    packed_ = {};
  }
}

void GpuLightTables::pack(std::vector<std::byte>& bytes) const {
  const std::span<const gpu::GpuDistantLight> distant = distantWithoutSun(table_, scene_);
  const Layout l = layoutOf(table_, distant.size(), hitMap_.size());
  bytes.assign(l.size, std::byte{0});
  const VkDeviceAddress base = tables_.address();
  gpu::LightTables block{};
  block.emissiveTriangles = base + l.emissive;
  block.punctualLights = base + l.punctual;
  block.lightAlias = base + l.alias;
  block.distantLights = base + l.distant;
  block.materialLightAreaPdf = base + l.materialPdf;
  block.emissiveTriangleCount = uint32_t(table_.emissiveTriangles.size());
  block.localLightCount = table_.localLightCount();
  block.distantLightCount = uint32_t(distant.size());
  put(bytes, 0, std::span<const gpu::LightTables>(&block, 1));
  put(bytes, l.emissive, std::span<const gpu::GpuEmissiveTriangle>(table_.emissiveTriangles));
  put(bytes, l.punctual, std::span<const gpu::GpuPunctualLight>(table_.punctualLights));
  put(bytes, l.alias, std::span<const gpu::GpuLightAlias>(table_.alias));
  put(bytes, l.distant, distant);
  put(bytes, l.materialPdf, std::span<const float>(table_.materialLightAreaPdf));
  put(bytes, l.hitMap, std::span<const uint32_t>(hitMap_));
}

void GpuLightTables::update(std::span<const PunctualLight> lights) {
  if (!staging_.mapped()) fail("GpuLightTables::update: the tables were not made updatable");
  if (lights.size() != scene_.lights.size())
    fail("GpuLightTables::update: {} lights for a scene of {}", lights.size(),
         scene_.lights.size());
  updateLightTable(table_, lights, gpuScene_.bvh());
  pack(packed_);
  std::memcpy(staging_.mapped(), packed_.data(), packed_.size());
  uploadPending_ = true;
}

void GpuLightTables::recordUpload(VkCommandBuffer cmd) {
  if (!uploadPending_) return;
  recordCopy(cmd);
  uploadPending_ = false;
}

void GpuLightTables::recordCopy(VkCommandBuffer cmd) const {
  VkBufferCopy all{0, 0, tables_.size()};
  vkCmdCopyBuffer(cmd, staging_.handle(), tables_.handle(), 1, &all);
}

}  // namespace bounce
