#include "scene/scene.h"

#include <cmath>

#include "core/error.h"
#include "scene/deformation.h"

namespace bounce {

Aabb Scene::bounds() const {
  std::vector<Aabb> meshBounds(meshes.size());
  for (size_t m = 0; m < meshes.size(); ++m)
    for (const Geometry& g : meshes[m].geometries)
      for (const glm::vec3& p : g.positions) meshBounds[m].extend(p);
  Aabb world;
  for (const Instance& inst : instances) {
    const Aabb& b = meshBounds[inst.mesh];
    if (b.empty()) continue;
    for (int corner = 0; corner < 8; ++corner) {
      glm::vec3 p{corner & 1 ? b.max.x : b.min.x, corner & 2 ? b.max.y : b.min.y,
                  corner & 4 ? b.max.z : b.min.z};
      world.extend(glm::vec3(inst.transform * glm::vec4(p, 1.0f)));
    }
  }
  return world;
}

uint64_t Scene::triangleCount() const {
  uint64_t n = 0;
  for (const Instance& inst : instances)
    for (const Geometry& g : meshes[inst.mesh].geometries) n += g.triangleCount();
  return n;
}

uint64_t Scene::uniqueTriangleCount() const {
  uint64_t n = 0;
  for (const Mesh& m : meshes)
    for (const Geometry& g : m.geometries) n += g.triangleCount();
  return n;
}

bool Scene::deforms() const {
  for (const Mesh& m : meshes)
    if (m.deforms()) return true;
  return false;
}

Camera defaultCamera(const Scene& scene) {
  Aabb b = scene.bounds();
  Camera cam;
  if (b.empty()) return cam;
  glm::vec3 c = b.center();
  float radius = 0.5f * glm::length(b.extent());
  cam.verticalFovDegrees = 45.0f;
  float distance = radius / std::tan(glm::radians(cam.verticalFovDegrees * 0.5f)) * 1.1f;
  glm::vec3 dir = glm::normalize(glm::vec3(0.0f, 0.35f, 1.0f));
  cam.position = c + dir * distance;
  cam.target = c;
  return cam;
}

static bool finite(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

void validateScene(const Scene& scene, const std::string& source) {
  if (scene.materials.empty()) fail("{}: scene has no materials", source);
  for (size_t m = 0; m < scene.meshes.size(); ++m) {
    const Mesh& mesh = scene.meshes[m];
    for (size_t gi = 0; gi < mesh.geometries.size(); ++gi) {
      const Geometry& g = mesh.geometries[gi];
      const std::string where =
          fmt::format("{}: mesh {} ('{}') primitive {}", source, m, mesh.name, gi);
      size_t n = g.positions.size();
      if (g.normals.size() != n)
        fail("{}: {} normals for {} positions", where, g.normals.size(), n);
      if (g.uvs.size() != n) fail("{}: {} uvs for {} positions", where, g.uvs.size(), n);
      if (!g.tangents.empty() && g.tangents.size() != n)
        fail("{}: {} tangents for {} positions", where, g.tangents.size(), n);
      if (!g.colors.empty() && g.colors.size() != n)
        fail("{}: {} colours for {} positions", where, g.colors.size(), n);
      if (g.indices.size() % 3 != 0)
        fail("{}: index count {} is not a multiple of 3", where, g.indices.size());
      for (uint32_t i : g.indices)
        if (i >= n) fail("{}: index {} out of range (vertex count {})", where, i, n);
      for (const glm::vec3& p : g.positions)
        if (!finite(p)) fail("{}: vertex position is NaN or infinite", where);
      if (g.material >= scene.materials.size())
        fail("{}: material {} does not exist ({} materials)", where, g.material,
             scene.materials.size());
    }
  }
  for (size_t i = 0; i < scene.instances.size(); ++i) {
    const Instance& inst = scene.instances[i];
    if (inst.mesh >= scene.meshes.size())
      fail("{}: instance {} refers to mesh {} ({} meshes)", source, i, inst.mesh,
           scene.meshes.size());
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r)
        if (!std::isfinite(inst.transform[c][r]))
          fail("{}: instance {} ('{}') has a non-finite transform", source, i, inst.name);
  }
  auto checkTexture = [&](int t, size_t mat, const char* slot) {
    if (t >= int(scene.images.size()))
      fail("{}: material {} {} refers to image {} ({} images)", source, mat, slot, t,
           scene.images.size());
  };
  for (size_t m = 0; m < scene.materials.size(); ++m) {
    const Material& mat = scene.materials[m];
    checkTexture(mat.baseColorTexture, m, "baseColorTexture");
    checkTexture(mat.metallicRoughnessTexture, m, "metallicRoughnessTexture");
    checkTexture(mat.normalTexture, m, "normalTexture");
    checkTexture(mat.emissiveTexture, m, "emissiveTexture");
  }
  for (size_t i = 0; i < scene.images.size(); ++i) {
    const Image& img = scene.images[i];
    if (img.width <= 0 || img.height <= 0 ||
        img.rgba.size() != size_t(img.width) * size_t(img.height) * 4)
      fail("{}: image {} ('{}') has inconsistent size {}x{}", source, i, img.name, img.width,
           img.height);
  }
  validateDeformation(scene, source);
}

}  // namespace bounce
