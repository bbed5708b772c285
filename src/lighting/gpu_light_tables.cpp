#include "lighting/gpu_light_tables.h"

#include <algorithm>
#include <span>
#include <string>

#include "lighting/light_table.h"
#include "rt/gpu_scene.h"
#include "scene/scene.h"
#include "shared/lighting_io.h"

namespace bounce {

namespace {

template <typename T>
vk::Buffer upload(vk::Context& context, std::span<const T> items, const std::string& name) {
  return vk::uploadBuffer(context, std::as_bytes(items), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, name);
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

GpuLightTables::GpuLightTables(vk::Context& context, const GpuScene& gpuScene, const Scene& scene) {
  LightTable lights = buildLightTable(scene, gpuScene.bvh());
  std::vector<bool> large = largeEmitterMaterials(lights, gpuScene.bounds());
  if (std::find(large.begin(), large.end(), true) != large.end())
    lights = buildLightTable(scene, gpuScene.bvh(), large);
  std::span<const gpu::GpuDistantLight> distant(lights.distantLights);
  if (scene.sun.irradiance > 0.0f && !distant.empty()) distant = distant.subspan(1);
  emissiveTriangles_ =
      upload(context, std::span<const gpu::GpuEmissiveTriangle>(lights.emissiveTriangles),
             "gi.emissive-triangles");
  punctualLights_ = upload(context, std::span<const gpu::GpuPunctualLight>(lights.punctualLights),
                           "gi.punctual-lights");
  lightAlias_ =
      upload(context, std::span<const gpu::GpuLightAlias>(lights.alias), "gi.light-alias");
  distantLights_ = upload(context, distant, "gi.distant-lights");
  materialLightAreaPdf_ = upload(context, std::span<const float>(lights.materialLightAreaPdf),
                                 "gi.material-light-area-pdf");
  gpu::LightTables block{};
  block.emissiveTriangles = emissiveTriangles_.address();
  block.punctualLights = punctualLights_.address();
  block.lightAlias = lightAlias_.address();
  block.distantLights = distantLights_.address();
  block.materialLightAreaPdf = materialLightAreaPdf_.address();
  block.emissiveTriangleCount = uint32_t(lights.emissiveTriangles.size());
  block.localLightCount = lights.localLightCount();
  block.distantLightCount = uint32_t(distant.size());
  block_ = upload(context, std::span<const gpu::LightTables>(&block, 1), "gi.lights");
  localLightCount_ = block.localLightCount;
  distantLightCount_ = block.distantLightCount;
}

}  // namespace bounce
