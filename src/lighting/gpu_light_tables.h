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
#pragma once
#include <vector>

#include "vk/resources.h"

namespace bounce {

class GpuScene;
struct Aabb;
struct LightTable;
struct Scene;

// Emitters larger than this fraction of the bounding box's surface area are reached by rays only.
inline constexpr double kLargeEmitterFraction = 0.1;

// Per Scene::materials entry: whether its emitters are large (reached by rays only, see above)
// in a scene of these lights and bounds.
std::vector<bool> largeEmitterMaterials(const LightTable& lights, const Aabb& bounds);

class GpuLightTables {
 public:
  GpuLightTables(vk::Context& context, const GpuScene& gpuScene, const Scene& scene);

  // The gpu::LightTables block (shared/lighting_io.h).
  VkDeviceAddress address() const { return block_.address(); }
  // Emissive triangles and punctual lights; distant lights without the sun.
  uint32_t localLightCount() const { return localLightCount_; }
  uint32_t distantLightCount() const { return distantLightCount_; }

 private:
  uint32_t localLightCount_ = 0, distantLightCount_ = 0;
  vk::Buffer emissiveTriangles_, punctualLights_, lightAlias_, distantLights_,
      materialLightAreaPdf_;
  vk::Buffer block_;
};

}  // namespace bounce
