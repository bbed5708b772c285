// The light tables the GI techniques' next-event estimation samples: the scene's light table
// (lighting/light_table.h: emissive triangles and KHR punctual lights picked by power through
// an alias table, KHR directional lights) uploaded once, behind one gpu::LightTables block
// (shared/lighting_io.h) whose address the shaders load into `lightTables`
// (shaders/lighting/light_tables.glsl) and sample with shaders/lighting/lights.glsl. The sun is
// left out of the distant lights: it moves, so the shaders take it from the frame constants.
//
// Emitters are split once, per material, between the two ways light reaches a point: small
// emitters (a lamp) by next-event estimation only, large ones (emissive walls, a furnace) by
// rays hitting them only, because NEE towards a large emitter close by is very noisy and rays
// find it easily. A material is *large* when its emissive area exceeds kLargeEmitterFraction of
// the surface area of the scene's bounding box; its triangles leave the light tables (their
// area pdf is 0, so shaders count hits on them in full and never sample them). The split
// depends on the light only, not on the point, so the two estimators add up exactly: this is
// multiple importance sampling with weights 0 and 1, which stays unbiased where consumers
// evaluate from different points (the clipmap cache's cells vs the points that look them up).
//
// Updatable tables (ReSTIR DI's) follow light animation without any GPU allocation: update()
// rewrites the CPU table in place (lighting/light_table.h, updateLightTable: every light keeps
// its index) into a staging buffer made at init, and recordUpload() copies it over the one
// device buffer that holds every array, which the frame graph imports (buffer()).
#pragma once
#include <span>
#include <vector>

#include "lighting/light_table.h"
#include "vk/resources.h"

namespace bounce {

class GpuScene;
struct Aabb;
struct PunctualLight;
struct Scene;

// Emitters larger than this fraction of the bounding box's surface area are reached by rays only.
inline constexpr double kLargeEmitterFraction = 0.1;

// Per Scene::materials entry: whether its emitters are large (reached by rays only, see above)
// in a scene of these lights and bounds.
std::vector<bool> largeEmitterMaterials(const LightTable& lights, const Aabb& bounds);

class GpuLightTables {
 public:
  // `updatable`: keep the CPU table and a staging buffer for update() (ReSTIR DI's tables).
  GpuLightTables(vk::Context& context, const GpuScene& gpuScene, const Scene& scene,
                 bool updatable = false);

  // The gpu::LightTables block (shared/lighting_io.h).
  VkDeviceAddress address() const { return tables_.address(); }
  // The emissive hit map (light_table.h, buildEmissiveHitMap): uint[].
  VkDeviceAddress emissiveHitMap() const { return tables_.address() + hitMapOffset_; }
  // The one buffer holding the block and every array (for the frame graph).
  const vk::Buffer& buffer() const { return tables_; }
  const LightTable& table() const { return table_; }
  // Emissive triangles and punctual lights; distant lights without the sun.
  uint32_t localLightCount() const { return localLightCount_; }
  uint32_t distantLightCount() const { return distantLightCount_; }

  // Updatable tables only: the lights' state from now on (the scene's lights, moved, dimmed or
  // switched; emissive triangles follow their instances' current transforms in the GpuScene's
  // BVH). Takes effect with the next recordUpload(). No GPU allocation.
  void update(std::span<const PunctualLight> lights);
  bool uploadPending() const { return uploadPending_; }
  // Copies the staging buffer over the tables (a transfer write: the caller orders it before
  // the shaders that read them). Nothing when no update is pending.
  void recordUpload(VkCommandBuffer cmd);

 private:
  void pack(std::vector<std::byte>& bytes) const;
  void recordCopy(VkCommandBuffer cmd) const;

  const GpuScene& gpuScene_;
  const Scene& scene_;
  // Updatable tables only (else emptied after the first upload): the CPU table, the hit map
  // and the packed bytes (kept to reuse their allocation).
  LightTable table_;
  std::vector<uint32_t> hitMap_;
  std::vector<std::byte> packed_;
  VkDeviceSize hitMapOffset_ = 0;
  vk::Buffer tables_;
  vk::Buffer staging_;  // updatable tables only
  bool uploadPending_ = false;
  uint32_t localLightCount_ = 0, distantLightCount_ = 0;
};

}  // namespace bounce
