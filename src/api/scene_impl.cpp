#include <bounce/scene.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>

#include "api/convert.h"
#include "api/scene_impl.h"
#include "core/error.h"
#include "scene/default_light.h"
#include "scene/load.h"
#include "scene/scene_options.h"

namespace bounce::api {

namespace {

// Area-weighted vertex normals: each triangle adds its unnormalised cross product (twice its
// area along its normal) to its corners. Vertices of degenerate triangles only get +Y.
std::vector<glm::vec3> smoothNormals(const std::vector<glm::vec3>& positions,
                                     const std::vector<uint32_t>& indices) {
  std::vector<glm::vec3> normals(positions.size(), glm::vec3(0.0f));
  for (size_t t = 0; t + 2 < indices.size(); t += 3) {
    const glm::vec3& a = positions[indices[t]];
    glm::vec3 n = glm::cross(positions[indices[t + 1]] - a, positions[indices[t + 2]] - a);
    for (size_t k = 0; k < 3; ++k) normals[indices[t + k]] += n;
  }
  for (glm::vec3& n : normals) {
    float length = glm::length(n);
    n = length > 0.0f && std::isfinite(length) ? n / length : glm::vec3(0.0f, 1.0f, 0.0f);
  }
  return normals;
}

}  // namespace

Scene::Scene() : impl_(std::make_unique<Impl>()) {}
Scene::~Scene() = default;
Scene::Scene(const Scene& other) : impl_(std::make_unique<Impl>(*other.impl_)) {}
Scene::Scene(Scene&& other) noexcept = default;
Scene& Scene::operator=(const Scene& other) {
  if (this != &other) impl_ = std::make_unique<Impl>(*other.impl_);
  return *this;
}
Scene& Scene::operator=(Scene&& other) noexcept = default;

Scene Scene::load(const std::string& nameOrPath) {
  Scene result;
  if (isGltfPath(nameOrPath)) {
    result.impl_->scene = loadGltf(nameOrPath);  // errors name the path
    // As the command line does without --sun and --sky (scene/default_light.h); setSun and
    // setSky replace it.
    applyDefaultLight(result.impl_->scene, {}, nameOrPath);
    return result;
  }
  if (std::optional<bounce::Scene> builtin = makeBuiltinScene(nameOrPath)) {
    result.impl_->scene = std::move(*builtin);
    return result;
  }
  std::string names;
  for (const std::string& n : builtinSceneNames()) names += (names.empty() ? "" : ", ") + n;
  fail("bounce::Scene::load('{}'): not a built-in scene ({}) nor a path ending in .gltf or .glb",
       nameOrPath, names);
}

std::vector<std::string> Scene::builtinNames() {
  return builtinSceneNames();
}

MaterialId Scene::addMaterial(const Material& material) {
  constexpr const char* where = "bounce::Scene::addMaterial";
  auto check = [&](float v, const char* field, float lo, float hi) {
    if (!(v >= lo && v <= hi)) fail("{}: {} {}: expected [{}, {}]", where, field, v, lo, hi);
  };
  check(material.baseColor.x, "baseColor.x", 0.0f, 1.0f);
  check(material.baseColor.y, "baseColor.y", 0.0f, 1.0f);
  check(material.baseColor.z, "baseColor.z", 0.0f, 1.0f);
  check(material.roughness, "roughness", 0.0f, 1.0f);
  check(material.metallic, "metallic", 0.0f, 1.0f);
  const float kMaxEmission = 1e30f;
  check(material.emission.x, "emission.x", 0.0f, kMaxEmission);
  check(material.emission.y, "emission.y", 0.0f, kMaxEmission);
  check(material.emission.z, "emission.z", 0.0f, kMaxEmission);

  bounce::Scene& scene = impl_->scene;
  bounce::Material m;
  m.name = "material " + std::to_string(scene.materials.size());
  m.baseColor = glm::vec4(toGlm(material.baseColor), 1.0f);
  m.roughness = material.roughness;
  m.metallic = material.metallic;
  m.emissive = toGlm(material.emission);
  m.doubleSided = material.doubleSided;
  scene.materials.push_back(std::move(m));
  return {uint32_t(scene.materials.size() - 1)};
}

MeshId Scene::addMesh(std::span<const Vec3> positions, std::span<const Vec3> normals,
                      std::span<const uint32_t> indices, MaterialId material) {
  constexpr const char* where = "bounce::Scene::addMesh";
  bounce::Scene& scene = impl_->scene;
  if (material.index >= scene.materials.size())
    fail("{}: material {} does not exist ({} materials)", where, material.index,
         scene.materials.size());
  if (indices.size() % 3 != 0)
    fail("{}: index count {} is not a multiple of 3", where, indices.size());
  if (!normals.empty() && normals.size() != positions.size())
    fail("{}: {} normals for {} positions: expected one per position, or none", where,
         normals.size(), positions.size());
  for (uint32_t i : indices)
    if (i >= positions.size())
      fail("{}: index {} out of range ({} positions)", where, i, positions.size());

  Geometry g;
  g.material = material.index;
  g.positions.reserve(positions.size());
  for (const Vec3& p : positions) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      fail("{}: a position is NaN or infinite", where);
    g.positions.push_back(toGlm(p));
  }
  g.indices.assign(indices.begin(), indices.end());
  if (normals.empty()) {
    g.normals = smoothNormals(g.positions, g.indices);
  } else {
    for (const Vec3& n : normals) {
      glm::vec3 v = toGlm(n);
      float length = glm::length(v);
      if (!(length > 0.0f && std::isfinite(length)))
        fail("{}: a normal is zero, NaN or infinite", where);
      g.normals.push_back(v / length);
    }
  }
  g.uvs.assign(g.positions.size(), glm::vec2(0.0f));

  bounce::Mesh mesh;
  mesh.name = "mesh " + std::to_string(scene.meshes.size());
  mesh.geometries.push_back(std::move(g));
  scene.meshes.push_back(std::move(mesh));
  return {uint32_t(scene.meshes.size() - 1)};
}

void Scene::addInstance(MeshId mesh, const Mat4& objectToWorld) {
  constexpr const char* where = "bounce::Scene::addInstance";
  bounce::Scene& scene = impl_->scene;
  if (mesh.index >= scene.meshes.size())
    fail("{}: mesh {} does not exist ({} meshes)", where, mesh.index, scene.meshes.size());
  for (float v : objectToWorld.m)
    if (!std::isfinite(v)) fail("{}: the transform has a NaN or infinite entry", where);
  bounce::Instance instance;
  instance.mesh = mesh.index;
  instance.transform = toGlm(objectToWorld);
  instance.name = "instance " + std::to_string(scene.instances.size());
  scene.instances.push_back(std::move(instance));
}

void Scene::setSun(const Sun& sun) {
  impl_->scene.sun = toInternal(sun, "bounce::Scene::setSun");
}

void Scene::setSky(const Sky& sky) {
  impl_->scene.sky = toInternal(sky, "bounce::Scene::setSky");
}

Sun Scene::sun() const {
  return fromInternal(impl_->scene.sun);
}

Sky Scene::sky() const {
  return fromInternal(impl_->scene.sky);
}

Camera Scene::camera() const {
  return fromInternal(effectiveCamera(impl_->scene));
}

std::string Scene::name() const {
  return impl_->scene.name;
}

uint64_t Scene::triangleCount() const {
  return impl_->scene.triangleCount();
}

}  // namespace bounce::api
