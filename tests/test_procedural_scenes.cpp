// The built-in procedural scenes: every one builds, validates and is deterministic, and each
// has the property it exists for (a watertight furnace, the Cornell data of the shared file, a
// sunroom whose only opening is its window, a mostly shaded forest floor, 64 lights, a city of
// over a million triangles).
#include <gtest/gtest.h>
#include <algorithm>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <map>
#include <optional>
#include <set>
#include <tuple>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "harness.h"
#include "lighting/gpu_light_tables.h"
#include "lighting/light_table.h"
#include "rt/scene_bvh.h"
#include "scene/load.h"
#include "scene/procedural/builtin_scenes.h"
#include "scene/procedural/furnace.h"
#include "scene/procedural/random.h"
#include "scene/procedural/sunroom.h"

namespace bounce {
namespace {

using procedural::Pcg32;

Scene buildBuiltin(const std::string& name) {
  std::optional<Scene> scene = makeBuiltinScene(name);
  if (!scene) throw std::runtime_error("no built-in scene '" + name + "'");
  return std::move(*scene);
}

glm::vec3 randomDirection(Pcg32& rng) {
  float z = rng.uniform(-1.0f, 1.0f);
  float phi = rng.uniform(0.0f, 6.2831853f);
  float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
  return {r * std::cos(phi), r * std::sin(phi), z};
}

// ---- a brute-force CPU ray caster over the scene's instanced triangles -------------------------

struct WorldTriangle {
  glm::vec3 v[3];
  glm::vec2 uv[3];
  uint32_t material;
};

std::vector<WorldTriangle> worldTriangles(const Scene& scene) {
  std::vector<WorldTriangle> triangles;
  for (const Instance& instance : scene.instances)
    for (const Geometry& g : scene.meshes[instance.mesh].geometries)
      for (size_t i = 0; i < g.indices.size(); i += 3) {
        WorldTriangle t;
        for (int k = 0; k < 3; ++k) {
          uint32_t index = g.indices[i + k];
          t.v[k] = glm::vec3(instance.transform * glm::vec4(g.positions[index], 1.0f));
          t.uv[k] = g.uvs[index];
        }
        t.material = g.material;
        triangles.push_back(t);
      }
  return triangles;
}

// Alpha of the nearest texel of the material's base colour texture (1 without one).
bool passesAlphaTest(const Scene& scene, const WorldTriangle& t, float b1, float b2) {
  const Material& m = scene.materials[t.material];
  if (m.alphaMode != AlphaMode::Mask || m.baseColorTexture < 0) return true;
  const Image& image = scene.images[size_t(m.baseColorTexture)];
  glm::vec2 uv = (1.0f - b1 - b2) * t.uv[0] + b1 * t.uv[1] + b2 * t.uv[2];
  uv -= glm::floor(uv);
  int x = std::min(int(uv.x * float(image.width)), image.width - 1);
  int y = std::min(int(uv.y * float(image.height)), image.height - 1);
  float alpha = image.rgba[(size_t(y) * size_t(image.width) + size_t(x)) * 4 + 3] / 255.0f;
  return alpha >= m.alphaCutoff;
}

struct RayHit {
  float t;
  size_t triangle;
  bool frontFacing;  // the ray sees the counter-clockwise side
};

// Möller-Trumbore against every triangle. The barycentric tests accept a hair outside each
// triangle so a ray can never slip between two triangles sharing an edge: a leak found here is
// a real gap in the geometry, not rounding.
std::optional<RayHit> closestHit(const Scene& scene, const std::vector<WorldTriangle>& triangles,
                                 const glm::vec3& origin, const glm::vec3& direction,
                                 bool alphaTest, bool anyHit = false) {
  constexpr float kEdgeSlack = 1e-5f;
  std::optional<RayHit> best;
  for (size_t i = 0; i < triangles.size(); ++i) {
    const WorldTriangle& tri = triangles[i];
    glm::vec3 e1 = tri.v[1] - tri.v[0], e2 = tri.v[2] - tri.v[0];
    glm::vec3 p = glm::cross(direction, e2);
    float det = glm::dot(e1, p);
    if (std::abs(det) < 1e-14f) continue;
    float inverse = 1.0f / det;
    glm::vec3 s = origin - tri.v[0];
    float b1 = glm::dot(s, p) * inverse;
    if (b1 < -kEdgeSlack || b1 > 1.0f + kEdgeSlack) continue;
    glm::vec3 q = glm::cross(s, e1);
    float b2 = glm::dot(direction, q) * inverse;
    if (b2 < -kEdgeSlack || b1 + b2 > 1.0f + kEdgeSlack) continue;
    float t = glm::dot(e2, q) * inverse;
    if (t <= 1e-4f || (best && t >= best->t)) continue;
    if (alphaTest && !passesAlphaTest(scene, tri, b1, b2)) continue;
    best = RayHit{t, i, det > 0.0f};  // det = -dot(direction, cross(e1, e2))
    if (anyHit) break;
  }
  return best;
}

// World-space bounds of one instance.
Aabb instanceBounds(const Scene& scene, const Instance& instance) {
  Aabb local;
  for (const Geometry& g : scene.meshes[instance.mesh].geometries)
    for (const glm::vec3& p : g.positions) local.extend(p);
  Aabb world;
  for (int corner = 0; corner < 8; ++corner) {
    glm::vec3 p{corner & 1 ? local.max.x : local.min.x, corner & 2 ? local.max.y : local.min.y,
                corner & 4 ? local.max.z : local.min.z};
    world.extend(glm::vec3(instance.transform * glm::vec4(p, 1.0f)));
  }
  return world;
}

bool contains(const Aabb& box, const glm::vec3& p, float margin = 0.0f) {
  return glm::all(glm::greaterThan(p, box.min - margin)) &&
         glm::all(glm::lessThan(p, box.max + margin));
}

// ---- every built-in scene ----------------------------------------------------------------------

TEST(ProceduralScenes, ListsTheElevenBuiltins) {
  std::vector<std::string> names = builtinSceneNames();
  std::set<std::string> unique(names.begin(), names.end());
  EXPECT_EQ(names.size(), 11u);
  EXPECT_EQ(unique, (std::set<std::string>{"cornell", "sunroom", "sunroom-glossy", "foliage",
                                           "manylights", "furnace", "city", "city-10k", "spheres",
                                           "skinned", "skinned-crowd"}));
}

TEST(ProceduralScenes, UnknownNameGivesNothing) {
  EXPECT_FALSE(makeBuiltinScene("no-such-scene").has_value());
  EXPECT_FALSE(makeBuiltinScene("").has_value());
  EXPECT_FALSE(makeBuiltinScene("Cornell").has_value());
}

class EveryBuiltinScene : public testing::TestWithParam<std::string> {};

TEST_P(EveryBuiltinScene, BuildsValidSceneWithCameraSunAndSky) {
  Scene scene = buildBuiltin(GetParam());
  EXPECT_NO_THROW(validateScene(scene, GetParam()));
  EXPECT_EQ(scene.name, GetParam());
  EXPECT_FALSE(scene.meshes.empty());
  EXPECT_FALSE(scene.instances.empty());
  ASSERT_TRUE(scene.camera.has_value());
  EXPECT_GT(glm::distance(scene.camera->position, scene.camera->target), 0.1f);
  EXPECT_GT(scene.camera->verticalFovDegrees, 10.0f);
  EXPECT_LT(scene.camera->verticalFovDegrees, 120.0f);
  EXPECT_TRUE(contains(scene.bounds(), scene.camera->position, 1.0f))
      << "the camera should look at the scene from within or near it";
  EXPECT_GE(scene.sun.irradiance, 0.0f);
  if (scene.sun.irradiance > 0.0f) {
    EXPECT_NEAR(glm::length(scene.sun.direction), 1.0f, 1e-4f);
    EXPECT_LT(scene.sun.direction.y, 0.0f) << "the sun shines down";
  }
  EXPECT_TRUE(glm::all(glm::greaterThanEqual(scene.sky.radiance, glm::vec3(0.0f))));
  for (const Material& m : scene.materials) EXPECT_FALSE(m.name.empty());
  for (const Mesh& m : scene.meshes) EXPECT_FALSE(m.name.empty());
}

// glTF conventions: unit normals on the counter-clockwise side, no zero-area triangles.
TEST_P(EveryBuiltinScene, NormalsAgreeWithWinding) {
  Scene scene = buildBuiltin(GetParam());
  size_t disagreeing = 0, degenerate = 0, unnormalised = 0;
  for (const Mesh& mesh : scene.meshes)
    for (const Geometry& g : mesh.geometries) {
      for (const glm::vec3& n : g.normals) unnormalised += std::abs(glm::length(n) - 1.0f) > 1e-3f;
      for (size_t i = 0; i < g.indices.size(); i += 3) {
        const glm::vec3& a = g.positions[g.indices[i]];
        glm::vec3 cross =
            glm::cross(g.positions[g.indices[i + 1]] - a, g.positions[g.indices[i + 2]] - a);
        if (glm::length(cross) < 1e-12f) {
          ++degenerate;
          continue;
        }
        for (int k = 0; k < 3; ++k)
          disagreeing += glm::dot(cross, g.normals[g.indices[i + k]]) <= 0.0f;
      }
    }
  EXPECT_EQ(disagreeing, 0u);
  EXPECT_EQ(degenerate, 0u);
  EXPECT_EQ(unnormalised, 0u);
}

TEST_P(EveryBuiltinScene, IsDeterministic) {
  Scene a = buildBuiltin(GetParam());
  Scene b = buildBuiltin(GetParam());
  ASSERT_EQ(a.meshes.size(), b.meshes.size());
  for (size_t m = 0; m < a.meshes.size(); ++m) {
    ASSERT_EQ(a.meshes[m].geometries.size(), b.meshes[m].geometries.size());
    for (size_t g = 0; g < a.meshes[m].geometries.size(); ++g) {
      const Geometry& ga = a.meshes[m].geometries[g];
      const Geometry& gb = b.meshes[m].geometries[g];
      EXPECT_TRUE(ga.positions == gb.positions) << a.meshes[m].name;
      EXPECT_TRUE(ga.normals == gb.normals) << a.meshes[m].name;
      EXPECT_TRUE(ga.uvs == gb.uvs) << a.meshes[m].name;
      EXPECT_TRUE(ga.indices == gb.indices) << a.meshes[m].name;
      EXPECT_EQ(ga.material, gb.material);
    }
  }
  ASSERT_EQ(a.instances.size(), b.instances.size());
  for (size_t i = 0; i < a.instances.size(); ++i) {
    EXPECT_EQ(a.instances[i].mesh, b.instances[i].mesh);
    EXPECT_TRUE(a.instances[i].transform == b.instances[i].transform);
  }
  ASSERT_EQ(a.lights.size(), b.lights.size());
  for (size_t i = 0; i < a.lights.size(); ++i) {
    EXPECT_TRUE(a.lights[i].position == b.lights[i].position);
    EXPECT_EQ(a.lights[i].intensity, b.lights[i].intensity);
  }
  ASSERT_EQ(a.images.size(), b.images.size());
  for (size_t i = 0; i < a.images.size(); ++i) EXPECT_TRUE(a.images[i].rgba == b.images[i].rgba);
}

INSTANTIATE_TEST_SUITE_P(Builtins, EveryBuiltinScene, testing::ValuesIn(builtinSceneNames()),
                         [](const testing::TestParamInfo<std::string>& info) {
                           // GoogleTest names allow letters, digits and '_' only.
                           std::string name = info.param;
                           std::replace(name.begin(), name.end(), '-', '_');
                           return name;
                         });

// ---- furnace -----------------------------------------------------------------------------------

// Undirected edges between welded vertices, and how often each direction is walked.
struct EdgeUse {
  int forward = 0;  // from the lower to the higher vertex id
  int backward = 0;
};

std::map<std::pair<uint32_t, uint32_t>, EdgeUse> edgeUses(const Scene& scene) {
  std::map<std::tuple<float, float, float>, uint32_t> welded;
  auto weld = [&](const glm::vec3& p) {
    auto [it, inserted] = welded.try_emplace({p.x, p.y, p.z}, uint32_t(welded.size()));
    return it->second;
  };
  std::map<std::pair<uint32_t, uint32_t>, EdgeUse> edges;
  for (const Instance& instance : scene.instances)
    for (const Geometry& g : scene.meshes[instance.mesh].geometries)
      for (size_t i = 0; i < g.indices.size(); i += 3)
        for (int k = 0; k < 3; ++k) {
          uint32_t a =
              weld(glm::vec3(instance.transform * glm::vec4(g.positions[g.indices[i + k]], 1.0f)));
          uint32_t b = weld(glm::vec3(instance.transform *
                                      glm::vec4(g.positions[g.indices[i + (k + 1) % 3]], 1.0f)));
          EdgeUse& use = edges[{std::min(a, b), std::max(a, b)}];
          (a < b ? use.forward : use.backward)++;
        }
  return edges;
}

TEST(FurnaceScene, IsWatertightAndConsistentlyWound) {
  Scene scene = buildBuiltin("furnace");
  auto edges = edgeUses(scene);
  ASSERT_FALSE(edges.empty());
  size_t open = 0, inconsistent = 0;
  for (const auto& [edge, use] : edges) {
    open += use.forward + use.backward != 2;
    // Two neighbours walk their shared edge in opposite directions when both face inward.
    inconsistent += use.forward != 1 || use.backward != 1;
  }
  EXPECT_EQ(open, 0u) << "edges not shared by exactly two triangles";
  EXPECT_EQ(inconsistent, 0u);
}

TEST(FurnaceScene, NormalsFaceInwardAndCameraIsInside) {
  Scene scene = buildBuiltin("furnace");
  const Aabb bounds = scene.bounds();
  const glm::vec3 centroid = bounds.center();
  size_t outward = 0;
  for (const Instance& instance : scene.instances)
    for (const Geometry& g : scene.meshes[instance.mesh].geometries)
      for (size_t i = 0; i < g.indices.size(); i += 3) {
        glm::vec3 p[3];
        for (int k = 0; k < 3; ++k)
          p[k] = glm::vec3(instance.transform * glm::vec4(g.positions[g.indices[i + k]], 1.0f));
        glm::vec3 towardsCentroid = centroid - (p[0] + p[1] + p[2]) / 3.0f;
        outward += glm::dot(glm::cross(p[1] - p[0], p[2] - p[0]), towardsCentroid) <= 0.0f;
        for (int k = 0; k < 3; ++k)
          outward += glm::dot(g.normals[g.indices[i + k]], towardsCentroid) <= 0.0f;
      }
  EXPECT_EQ(outward, 0u);
  ASSERT_TRUE(scene.camera.has_value());
  EXPECT_TRUE(contains(bounds, scene.camera->position, -0.05f));
  EXPECT_TRUE(contains(bounds, scene.camera->target, -0.05f));
}

TEST(FurnaceScene, EverySurfaceHasTheGivenAlbedoAndEmission) {
  const float albedo = 0.8f;
  const glm::vec3 emission{2.0f, 1.0f, 0.5f};
  Scene scene = makeFurnaceScene(albedo, emission);
  EXPECT_NO_THROW(validateScene(scene, "furnace"));
  for (const Mesh& mesh : scene.meshes)
    for (const Geometry& g : mesh.geometries) {
      const Material& m = scene.materials[g.material];
      EXPECT_EQ(glm::vec3(m.baseColor), glm::vec3(albedo));
      EXPECT_EQ(m.metallic, 0.0f);
      EXPECT_EQ(m.roughness, 1.0f);
      EXPECT_EQ(m.emissive, emission);
      EXPECT_EQ(m.alphaMode, AlphaMode::Opaque);
      EXPECT_LT(m.baseColorTexture, 0);
    }
  EXPECT_EQ(scene.sun.irradiance, 0.0f);
  EXPECT_EQ(scene.sky.radiance, glm::vec3(0.0f));
  EXPECT_TRUE(scene.lights.empty());
  // The built-in one is the a = 0.5, Le = 1 case.
  Scene builtin = buildBuiltin("furnace");
  EXPECT_EQ(glm::vec3(builtin.materials.at(0).baseColor), glm::vec3(0.5f));
  EXPECT_EQ(builtin.materials.at(0).emissive, glm::vec3(1.0f));
}

// ---- cornell -----------------------------------------------------------------------------------

// Reads one accessor of the shared cornell_box.gltf straight from its .bin (float VEC3 or
// uint16 SCALAR, tightly packed, which is all that file uses).
class CornellFile {
 public:
  CornellFile() {
    const std::string dir = test::sharedDir() + "/scenes/cornell_box/";
    std::ifstream gltf(dir + "cornell_box.gltf");
    json_ = nlohmann::json::parse(gltf);
    std::ifstream bin(dir + "cornell_box.bin", std::ios::binary);
    bin_.assign(std::istreambuf_iterator<char>(bin), {});
  }
  const nlohmann::json& json() const { return json_; }

  std::vector<glm::vec3> vec3s(int accessor) const {
    auto [offset, count] = locate(accessor, 5126, "VEC3");
    std::vector<glm::vec3> out(count);
    std::memcpy(out.data(), bin_.data() + offset, count * sizeof(glm::vec3));
    return out;
  }
  std::vector<uint32_t> indices(int accessor) const {
    auto [offset, count] = locate(accessor, 5123, "SCALAR");
    std::vector<uint32_t> out(count);
    for (size_t i = 0; i < count; ++i) {
      uint16_t v;
      std::memcpy(&v, bin_.data() + offset + 2 * i, 2);
      out[i] = v;
    }
    return out;
  }

 private:
  std::pair<size_t, size_t> locate(int accessor, int componentType, const char* type) const {
    const auto& a = json_["accessors"][accessor];
    EXPECT_EQ(a["componentType"].get<int>(), componentType);
    EXPECT_EQ(a["type"].get<std::string>(), type);
    const auto& view = json_["bufferViews"][a["bufferView"].get<int>()];
    size_t offset = view.value("byteOffset", 0) + a.value("byteOffset", 0);
    size_t count = a["count"].get<size_t>();
    size_t elementSize = componentType == 5126 ? 12 : 2;
    if (offset + count * elementSize > bin_.size())
      throw std::runtime_error("accessor past the .bin");
    return {offset, count};
  }
  nlohmann::json json_;
  std::vector<char> bin_;
};

const Mesh* findMesh(const Scene& scene, const std::string& name) {
  for (const Mesh& m : scene.meshes)
    if (m.name == name) return &m;
  return nullptr;
}

TEST(CornellScene, HasTheSharedFilesVerticesExactly) {
  CornellFile file;
  Scene scene = buildBuiltin("cornell");
  EXPECT_EQ(scene.triangleCount(), 32u);
  size_t meshesChecked = 0;
  for (const auto& node : file.json()["nodes"]) {
    if (!node.contains("mesh")) continue;
    const auto& fileMesh = file.json()["meshes"][node["mesh"].get<int>()];
    const std::string name = fileMesh["name"];
    const Mesh* mesh = findMesh(scene, name);
    ASSERT_NE(mesh, nullptr) << name;
    ASSERT_EQ(mesh->geometries.size(), 1u) << name;
    const Geometry& g = mesh->geometries[0];
    const auto& primitive = fileMesh["primitives"][0];
    std::vector<glm::vec3> positions = file.vec3s(primitive["attributes"]["POSITION"]);
    std::vector<glm::vec3> normals = file.vec3s(primitive["attributes"]["NORMAL"]);
    ASSERT_EQ(g.positions.size(), positions.size()) << name;
    for (size_t i = 0; i < positions.size(); ++i) {
      EXPECT_EQ(g.positions[i], positions[i]) << name << " vertex " << i;  // bit for bit
      EXPECT_NEAR(glm::dot(g.normals[i], normals[i]), 1.0f, 1e-5f) << name << " normal " << i;
    }
    EXPECT_EQ(g.indices, file.indices(primitive["indices"])) << name;
    const auto& fileMaterial = file.json()["materials"][primitive["material"].get<int>()];
    const Material& material = scene.materials[g.material];
    EXPECT_EQ(material.name, fileMaterial["name"].get<std::string>()) << name;
    EXPECT_EQ(material.doubleSided, fileMaterial.value("doubleSided", false)) << name;
    ++meshesChecked;
  }
  EXPECT_EQ(meshesChecked, 8u);
  EXPECT_EQ(scene.meshes.size(), 8u);
}

TEST(CornellScene, HasTheCornellColoursLightAndCamera) {
  Scene scene = buildBuiltin("cornell");
  std::map<std::string, const Material*> byName;
  for (const Material& m : scene.materials) byName[m.name] = &m;
  ASSERT_EQ(byName.size(), 4u);
  auto expectColor = [&](const char* name, glm::vec3 color) {
    ASSERT_TRUE(byName.count(name)) << name;
    EXPECT_EQ(glm::vec3(byName[name]->baseColor), color) << name;
  };
  expectColor("cb_white", {0.725f, 0.71f, 0.68f});
  expectColor("cb_red", {0.63f, 0.065f, 0.05f});
  expectColor("cb_green", {0.14f, 0.45f, 0.091f});
  ASSERT_TRUE(byName.count("cb_light"));
  EXPECT_EQ(byName["cb_light"]->emissive, glm::vec3(17.0f, 12.0f, 4.0f));
  for (const Material& m : scene.materials) {
    EXPECT_EQ(m.metallic, 0.0f) << m.name;
    EXPECT_EQ(m.roughness, 1.0f) << m.name;
    if (m.name != "cb_light") {
      EXPECT_EQ(m.emissive, glm::vec3(0.0f)) << m.name;
    }
  }
  // The light is one quad facing down.
  const Mesh* light = findMesh(scene, "light");
  ASSERT_NE(light, nullptr);
  EXPECT_EQ(light->geometries.at(0).triangleCount(), 2u);
  for (const glm::vec3& n : light->geometries[0].normals)
    EXPECT_EQ(n, glm::vec3(0.0f, -1.0f, 0.0f));

  ASSERT_TRUE(scene.camera.has_value());
  EXPECT_EQ(scene.camera->position, glm::vec3(0.278f, 0.273f, -0.8f));
  EXPECT_EQ(scene.camera->target, glm::vec3(0.278f, 0.273f, 0.0f));
  EXPECT_NEAR(scene.camera->verticalFovDegrees, 39.3077f, 1e-4f);
  EXPECT_EQ(scene.sun.irradiance, 0.0f);
  EXPECT_EQ(scene.sky.radiance, glm::vec3(0.0f));
}

// ---- sunroom -----------------------------------------------------------------------------------

// Random points in the room's air, not inside any piece of furniture (whose bounds do not
// contain the whole room, unlike the shell's).
std::vector<glm::vec3> pointsInRoomAir(const Scene& scene, int count, Pcg32& rng) {
  const Aabb& room = sunroomLayout().interior;
  std::vector<Aabb> furniture;
  for (const Instance& instance : scene.instances) {
    Aabb b = instanceBounds(scene, instance);
    if (!(contains(b, room.min, 1e-3f) && contains(b, room.max, 1e-3f))) furniture.push_back(b);
  }
  std::vector<glm::vec3> points;
  while (int(points.size()) < count) {
    glm::vec3 p = glm::mix(room.min + 0.05f, room.max - 0.05f,
                           glm::vec3(rng.uniform(), rng.uniform(), rng.uniform()));
    bool free = true;
    for (const Aabb& b : furniture) free = free && !contains(b, p, 0.02f);
    if (free) points.push_back(p);
  }
  return points;
}

TEST(SunroomScene, WindowIsTheOnlyOpening) {
  Scene scene = buildBuiltin("sunroom");
  const SunroomLayout& layout = sunroomLayout();
  const float windowWallZ = layout.interior.min.z;
  const std::vector<WorldTriangle> triangles = worldTriangles(scene);
  Pcg32 rng(2024);
  int escaped = 0, hit = 0, backFacing = 0, escapedElsewhere = 0;
  for (const glm::vec3& origin : pointsInRoomAir(scene, 8, rng)) {
    for (int i = 0; i < 500; ++i) {
      glm::vec3 direction = randomDirection(rng);
      std::optional<RayHit> h = closestHit(scene, triangles, origin, direction, false);
      if (h) {
        ++hit;
        // Everything inside is single-sided and faces the room.
        backFacing += !h->frontFacing;
        continue;
      }
      ++escaped;
      // An escaping ray must cross the window wall's plane inside the window.
      bool throughWindow = false;
      if (direction.z < 0.0f) {
        float t = (windowWallZ - origin.z) / direction.z;
        glm::vec3 p = origin + t * direction;
        throughWindow = p.x >= layout.windowMin.x - 1e-4f && p.x <= layout.windowMax.x + 1e-4f &&
                        p.y >= layout.windowMin.y - 1e-4f && p.y <= layout.windowMax.y + 1e-4f;
      }
      escapedElsewhere += !throughWindow;
    }
  }
  std::printf("sunroom: %d rays hit the room, %d escaped through the window\n", hit, escaped);
  EXPECT_EQ(escapedElsewhere, 0);
  EXPECT_EQ(backFacing, 0);
  EXPECT_GT(escaped, 0) << "the window should be open to the sky";
  EXPECT_GT(hit, escaped);
}

// Sunlit fraction of the room's inner surfaces (floor, ceiling, walls), by area.
TEST(SunroomScene, SunMakesAPatchAndMostOfTheRoomIsLitIndirectly) {
  Scene scene = buildBuiltin("sunroom");
  ASSERT_GT(scene.sun.irradiance, 50.0f);
  ASSERT_GT(scene.sky.radiance.z, 0.0f);
  const std::vector<WorldTriangle> triangles = worldTriangles(scene);
  const Aabb& room = sunroomLayout().interior;
  const glm::vec3 towardsSun = -scene.sun.direction;
  const int n = 24;
  double litArea = 0.0, totalArea = 0.0, litFloor = 0.0;
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side) {
      const int a = (axis + 1) % 3, b = (axis + 2) % 3;
      const double cellArea = double(room.extent()[a] * room.extent()[b]) / (n * n);
      glm::vec3 inward{0.0f};
      inward[axis] = side == 0 ? 1.0f : -1.0f;
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
          glm::vec3 p;
          p[axis] = (side == 0 ? room.min[axis] : room.max[axis]) + 1e-3f * inward[axis];
          p[a] = room.min[a] + room.extent()[a] * (i + 0.5f) / n;
          p[b] = room.min[b] + room.extent()[b] * (j + 0.5f) / n;
          totalArea += cellArea;
          if (glm::dot(inward, towardsSun) <= 0.0f) continue;
          if (closestHit(scene, triangles, p, towardsSun, false, true)) continue;
          litArea += cellArea;
          if (axis == 1 && side == 0) litFloor += cellArea;
        }
    }
  const double floorArea = double(room.extent().x * room.extent().z);
  std::printf("sunroom: sunlit %.1f%% of the floor, %.1f%% of all inner surfaces\n",
              100.0 * litFloor / floorArea, 100.0 * litArea / totalArea);
  EXPECT_GT(litFloor, 0.05 * floorArea) << "the sun should make a patch on the floor";
  EXPECT_LT(litArea, 0.25 * totalArea) << "most of the room should be lit only indirectly";
}

TEST(SunroomScene, HasASeparateMovablePanel) {
  Scene scene = buildBuiltin("sunroom");
  size_t panels = 0;
  for (const Instance& instance : scene.instances)
    if (instance.name == "movable_panel") {
      ++panels;
      EXPECT_EQ(scene.meshes[instance.mesh].name, "movable_panel");
      size_t users = 0;
      for (const Instance& other : scene.instances) users += other.mesh == instance.mesh;
      EXPECT_EQ(users, 1u) << "moving the panel must not move anything else";
      Aabb b = instanceBounds(scene, instance);
      EXPECT_NEAR(b.extent().y, 2.0f, 0.01f) << "door-sized";
    }
  EXPECT_EQ(panels, 1u);
}

// ---- spheres -----------------------------------------------------------------------------------

const Instance* findInstance(const Scene& scene, const std::string& name) {
  for (const Instance& instance : scene.instances)
    if (instance.name == name) return &instance;
  return nullptr;
}

// The grid the specular tests rely on: every sphere its own instance and material, the row's
// material (metals first) and the column's roughness, resting on the floor without touching
// its neighbours.
TEST(SpheresScene, RowsOfMaterialsAndColumnsOfRoughness) {
  Scene scene = buildBuiltin("spheres");
  for (int row = 0; row < procedural::kSpheresRows; ++row)
    for (int column = 0; column < procedural::kSpheresColumns; ++column) {
      SCOPED_TRACE(testing::Message() << "row " << row << " column " << column);
      const Instance* sphere = findInstance(scene, fmt::format("sphere_{}_{}", row, column));
      ASSERT_NE(sphere, nullptr);
      const Mesh& mesh = scene.meshes[sphere->mesh];
      ASSERT_EQ(mesh.geometries.size(), 1u);
      const Material& m = scene.materials[mesh.geometries[0].material];
      EXPECT_EQ(m.roughness, procedural::kSpheresRoughness[size_t(column)]);
      EXPECT_EQ(m.metallic, row < procedural::kSpheresMetalRows ? 1.0f : 0.0f);
      EXPECT_EQ(m.emissive, glm::vec3(0.0f));
      Aabb b = instanceBounds(scene, *sphere);
      EXPECT_NEAR(b.min.y, 0.0f, 1e-5f) << "rests on the floor";
      EXPECT_NEAR(b.extent().x, b.extent().y, 1e-3f);
      EXPECT_NEAR(b.extent().x, b.extent().z, 1e-3f);
      if (column > 0) {
        Aabb left = instanceBounds(
            scene, *findInstance(scene, fmt::format("sphere_{}_{}", row, column - 1)));
        EXPECT_GT(b.min.x, left.max.x) << "apart from its neighbour";
      }
    }
  for (size_t c = 1; c < procedural::kSpheresRoughness.size(); ++c)
    EXPECT_GT(procedural::kSpheresRoughness[c], procedural::kSpheresRoughness[c - 1]);
  EXPECT_LE(procedural::kSpheresRoughness.front(), 0.02f) << "from near-mirror";
  EXPECT_EQ(procedural::kSpheresRoughness.back(), 1.0f) << "to fully rough";
}

// Lit by the sun, the daylight sky and emissive panels; the camera sees every sphere: the ray
// from the camera to each sphere's top half hits that sphere first.
TEST(SpheresScene, SunSkyPanelsAndACameraThatSeesEverySphere) {
  Scene scene = buildBuiltin("spheres");
  EXPECT_GT(scene.sun.irradiance, 0.0f);
  EXPECT_EQ(scene.sky.model, SkyModel::Daylight);
  int emitters = 0;
  for (const Material& m : scene.materials) emitters += glm::length(m.emissive) > 0.0f;
  EXPECT_EQ(emitters, 3);
  const std::vector<WorldTriangle> triangles = worldTriangles(scene);
  const glm::vec3 eye = scene.camera->position;
  for (int row = 0; row < procedural::kSpheresRows; ++row)
    for (int column = 0; column < procedural::kSpheresColumns; ++column) {
      const Instance* sphere = findInstance(scene, fmt::format("sphere_{}_{}", row, column));
      ASSERT_NE(sphere, nullptr);
      Aabb b = instanceBounds(scene, *sphere);
      glm::vec3 target = b.center() + glm::vec3(0.0f, 0.25f * b.extent().y, 0.0f);
      std::optional<RayHit> hit =
          closestHit(scene, triangles, eye, glm::normalize(target - eye), false);
      ASSERT_TRUE(hit.has_value());
      glm::vec3 p = eye + hit->t * glm::normalize(target - eye);
      EXPECT_TRUE(contains(b, p, 1e-3f)) << "sphere " << row << " " << column << " is hidden";
    }
}

// ---- foliage -----------------------------------------------------------------------------------

TEST(FoliageScene, LeavesAreAlphaMaskedCardsWithABinaryMask) {
  Scene scene = buildBuiltin("foliage");
  size_t maskMaterials = 0;
  for (const Material& m : scene.materials) {
    if (m.alphaMode != AlphaMode::Mask) continue;
    ++maskMaterials;
    EXPECT_EQ(m.alphaCutoff, 0.5f);
    EXPECT_TRUE(m.doubleSided);
    ASSERT_GE(m.baseColorTexture, 0);
    const Image& image = scene.images[size_t(m.baseColorTexture)];
    size_t transparent = 0, opaque = 0;
    for (size_t i = 3; i < image.rgba.size(); i += 4) {
      transparent += image.rgba[i] == 0;
      opaque += image.rgba[i] == 255;
    }
    EXPECT_GT(transparent, 0u);
    EXPECT_GT(opaque, 0u);
    EXPECT_EQ(transparent + opaque, size_t(image.width) * size_t(image.height));
  }
  EXPECT_GE(maskMaterials, 1u);
  uint64_t leafTriangles = 0;
  for (const Instance& instance : scene.instances)
    for (const Geometry& g : scene.meshes[instance.mesh].geometries)
      if (scene.materials[g.material].alphaMode == AlphaMode::Mask)
        leafTriangles += g.triangleCount();
  EXPECT_GE(leafTriangles / 2, 2000u) << "a few thousand leaf cards";
}

// Shadow rays from the forest floor (the square spanned by the trunks), with and without the
// alpha test.
TEST(FoliageScene, MostOfTheForestFloorIsInShade) {
  Scene scene = buildBuiltin("foliage");
  ASSERT_GT(scene.sun.irradiance, 0.0f);
  const std::vector<WorldTriangle> triangles = worldTriangles(scene);
  Aabb trunks;
  for (const Instance& instance : scene.instances)
    if (instance.name.rfind("tree_", 0) == 0) trunks.extend(glm::vec3(instance.transform[3]));
  ASSERT_GT(trunks.extent().x, 10.0f) << "a forest, not a tree";
  Pcg32 rng(5);
  const int samples = 300;
  int shadedAlphaTested = 0, shadedByCards = 0;
  for (int i = 0; i < samples; ++i) {
    glm::vec3 p{rng.uniform(trunks.min.x, trunks.max.x), 0.01f,
                rng.uniform(trunks.min.z, trunks.max.z)};
    shadedAlphaTested +=
        closestHit(scene, triangles, p, -scene.sun.direction, true, true).has_value();
    shadedByCards += closestHit(scene, triangles, p, -scene.sun.direction, false, true).has_value();
  }
  std::printf("foliage: %.1f%% of the forest floor in shade (%.1f%% if leaf cards were opaque)\n",
              100.0 * shadedAlphaTested / samples, 100.0 * shadedByCards / samples);
  EXPECT_GT(shadedAlphaTested, samples * 6 / 10);
  EXPECT_LT(shadedAlphaTested, shadedByCards) << "cut-outs must let some sun through";
}

// ---- manylights --------------------------------------------------------------------------------

TEST(ManyLightsScene, Has64PointLightsInsideTheRoom) {
  Scene scene = buildBuiltin("manylights");
  ASSERT_EQ(scene.lights.size(), 64u);
  const Aabb room = scene.bounds();
  std::vector<Aabb> furniture;
  for (const Instance& instance : scene.instances) {
    Aabb b = instanceBounds(scene, instance);
    if (glm::any(glm::notEqual(b.min, room.min)) || glm::any(glm::notEqual(b.max, room.max)))
      furniture.push_back(b);
  }
  EXPECT_FALSE(furniture.empty());
  std::set<std::string> names;
  for (const PunctualLight& light : scene.lights) {
    EXPECT_EQ(light.type, PunctualLight::Type::Point) << light.name;
    EXPECT_GT(light.intensity, 0.0f) << light.name;
    EXPECT_GT(glm::length(light.color), 0.0f) << light.name;
    EXPECT_TRUE(contains(room, light.position, -0.1f)) << light.name;
    for (const Aabb& b : furniture) EXPECT_FALSE(contains(b, light.position)) << light.name;
    names.insert(light.name);
  }
  EXPECT_EQ(names.size(), 64u) << "light names are unique";
  EXPECT_EQ(scene.sun.irradiance, 0.0f);
}

// ---- city --------------------------------------------------------------------------------------

TEST(CityScene, HasOverAMillionTrianglesAndBuildsQuickly) {
  auto start = std::chrono::steady_clock::now();
  Scene scene = buildBuiltin("city");
  double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("city: %llu triangles (%llu unique), %zu meshes, %zu instances, built in %.0f ms\n",
              (unsigned long long)scene.triangleCount(),
              (unsigned long long)scene.uniqueTriangleCount(), scene.meshes.size(),
              scene.instances.size(), seconds * 1000.0);
  EXPECT_GE(scene.triangleCount(), 1000000u);
  EXPECT_GE(scene.uniqueTriangleCount(), 300000u);
  EXPECT_GT(scene.instances.size(), scene.meshes.size()) << "props and blocks are instanced";
  EXPECT_LT(seconds, 2.0) << "a sanity bound, not a benchmark";
}

// The flux of a spot light in the scene's units (klm when intensity is kcd): its luminous
// intensity times the solid angle its glTF falloff covers, integrated here by the midpoint rule
// over the polar angle (not the closed form city.cpp uses).
double spotFlux(const PunctualLight& light) {
  const double cosInner = std::cos(double(light.innerConeAngle));
  const double cosOuter = std::cos(double(light.outerConeAngle));
  const int steps = 100000;
  double solidAngle = 0.0;
  for (int i = 0; i < steps; ++i) {
    const double theta = (double(i) + 0.5) / steps * M_PI, dTheta = M_PI / steps;
    const double a = std::clamp((std::cos(theta) - cosOuter) / (cosInner - cosOuter), 0.0, 1.0);
    solidAngle += a * a * 2.0 * M_PI * std::sin(theta) * dTheta;
  }
  return solidAngle * double(luminance(light.intensity * light.color));
}

// The street lights of a city (or city-10k) as its light table sees them.
struct CityLights {
  Scene scene;
  LightTable table;
  double tableSeconds = 0.0;  // buildLightTable and the large/small split, not the BVH
  uint32_t coverMaterial = 0;
  std::vector<bool> large;
};

CityLights cityLights(const std::string& name) {
  CityLights c{buildBuiltin(name), {}, 0.0, 0, {}};
  rt::SceneBvh bvh = rt::buildSceneBvh(c.scene);
  auto start = std::chrono::steady_clock::now();
  c.table = buildLightTable(c.scene, bvh);
  c.large = largeEmitterMaterials(c.table, c.scene.bounds());
  c.tableSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  for (uint32_t m = 0; m < c.scene.materials.size(); ++m)
    if (c.scene.materials[m].name == "street_light_cover") c.coverMaterial = m;
  return c;
}

// Issue 20: every street light is a light, a lamp of 12,000 lm (city.cpp's photometry): its
// spot light shining down carries 9,600 lm and its cover, two emissive triangles that the
// light table samples (small emitters, not left to rays), 2,400 lm.
TEST(CityScene, EveryStreetLightIsATwelveKilolumenLamp) {
  CityLights c = cityLights("city");
  const size_t lamps = size_t(procedural::kCityBlocksPerSide * procedural::kCityBlocksPerSide *
                              procedural::kCityStreetLightsPerBlock);
  ASSERT_EQ(lamps, 1024u);
  ASSERT_EQ(c.scene.lights.size(), lamps);
  for (const PunctualLight& light : c.scene.lights) {
    ASSERT_EQ(light.type, PunctualLight::Type::Spot) << light.name;
    EXPECT_NEAR(light.direction.y, -1.0f, 1e-6f) << light.name << " shines down";
    EXPECT_NEAR(light.position.y, 0.15f + 6.93f, 1e-4f) << light.name << " under its lamp";
    EXPECT_NEAR(spotFlux(light), 9.6, 0.01 * 9.6) << light.name;
  }
  EXPECT_EQ(c.table.punctualLights.size(), lamps);
  EXPECT_EQ(c.table.emissiveTriangles.size(), 2 * lamps) << "one quad of cover per lamp";
  EXPECT_EQ(c.table.localLightCount(), 3 * lamps);
  const Material& cover = c.scene.materials.at(c.coverMaterial);
  const double coverFlux =
      M_PI * double(luminance(cover.emissive)) * c.table.materialEmissiveArea[c.coverMaterial];
  EXPECT_NEAR(coverFlux / double(lamps), 2.4, 0.01 * 2.4);
  EXPECT_FALSE(c.large.at(c.coverMaterial))
      << "lamp covers must be sampled by DI, not left to rays";
  std::printf("city: %zu lights in the light table, built and split in %.1f ms\n",
              size_t(c.table.localLightCount()), 1e3 * c.tableSeconds);
}

// The scale-test variant: 10,000 street lights (30,000 local lights with the covers), the same
// unique meshes, and a light table built in milliseconds.
TEST(CityScene, TenThousandLightVariantHasTenThousandLamps) {
  CityLights c = cityLights("city-10k");
  EXPECT_EQ(c.scene.lights.size(), 10000u);
  EXPECT_EQ(c.table.punctualLights.size(), 10000u);
  EXPECT_EQ(c.table.emissiveTriangles.size(), 20000u);
  EXPECT_FALSE(c.large.at(c.coverMaterial));
  EXPECT_EQ(c.scene.uniqueTriangleCount(), buildBuiltin("city").uniqueTriangleCount());
  std::printf(
      "city-10k: %llu triangles (%llu unique), %zu instances, %u lights in the light "
      "table, built and split in %.1f ms\n",
      (unsigned long long)c.scene.triangleCount(),
      (unsigned long long)c.scene.uniqueTriangleCount(), c.scene.instances.size(),
      c.table.localLightCount(), 1e3 * c.tableSeconds);
  EXPECT_LT(c.tableSeconds, 1.0) << "a sanity bound, not a benchmark";
}

}  // namespace
}  // namespace bounce
