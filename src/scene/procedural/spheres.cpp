// Spheres: the scene for specular shading (issue 19). Four rows of seven spheres on a
// chequered floor, roughness growing from left to right (kSpheresRoughness), one material per
// row (front to back): white metal, gold, white dielectric, red dielectric. A clear daylight sky
// and a sun from behind the camera light them, and three emissive panels (behind the rows and
// to either side) give the mirrors something sharp to reflect. Every sphere is its own instance,
// named "sphere_<row>_<column>", so tests can find a row's pixels through vbuffer.ids.
#include <array>
#include <string>

#include <fmt/format.h>

#include "scene/procedural/builtin_scenes.h"
#include "scene/procedural/mesh_builder.h"

namespace bounce::procedural {

namespace {

constexpr float kRadius = 0.4f;
constexpr float kColumnSpacing = 1.0f;
constexpr float kRowSpacing = 1.1f;
constexpr int kFloorTiles = 16;      // per side, 1 m each
constexpr int kSphereSegments = 48;  // around; half as many rings pole to pole

struct RowMaterial {
  const char* name;
  glm::vec3 baseColor;
  float metallic;
};

// Front to back. The metals' base colours are their F0: silver and gold as the glTF sample
// models give them (Khronos, KHR_materials guide: "physically based values").
constexpr std::array<RowMaterial, kSpheresRows> kRows = {{
    {"white_metal", {0.97f, 0.96f, 0.91f}, 1.0f},
    {"gold", {1.0f, 0.78f, 0.34f}, 1.0f},
    {"white_dielectric", {0.8f, 0.8f, 0.8f}, 0.0f},
    {"red_dielectric", {0.7f, 0.08f, 0.06f}, 0.0f},
}};

// A chequered floor of 1 m tiles in two greys, so that reflections show structure.
Mesh makeFloor(uint32_t light, uint32_t dark) {
  MeshBuilder builder;
  const float half = 0.5f * float(kFloorTiles);
  for (int i = 0; i < kFloorTiles; ++i)
    for (int j = 0; j < kFloorTiles; ++j) {
      float x0 = float(i) - half, z0 = float(j) - half;
      addQuadFacing(builder.geometry((i + j) % 2 == 0 ? light : dark), {0, 1, 0}, {x0, 0, z0},
                    {x0 + 1, 0, z0}, {x0 + 1, 0, z0 + 1}, {x0, 0, z0 + 1});
    }
  return builder.build("floor");
}

glm::vec3 spherePosition(int row, int column) {
  float x = (float(column) - 0.5f * float(kSpheresColumns - 1)) * kColumnSpacing;
  float z = (0.5f * float(kSpheresRows - 1) - float(row)) * kRowSpacing;
  return {x, kRadius, z};
}

void addSpheres(Scene& scene) {
  for (int row = 0; row < kSpheresRows; ++row)
    for (int column = 0; column < kSpheresColumns; ++column) {
      const RowMaterial& r = kRows[size_t(row)];
      Material m = lambertMaterial(
          fmt::format("{}_roughness_{:.2f}", r.name, kSpheresRoughness[size_t(column)]),
          r.baseColor);
      m.metallic = r.metallic;
      m.roughness = kSpheresRoughness[size_t(column)];
      Geometry g;
      g.material = addMaterial(scene, m);
      addSphere(g, {0, 0, 0}, kRadius, kSphereSegments, kSphereSegments / 2);
      Mesh mesh;
      mesh.name = fmt::format("sphere_{}_{}", row, column);
      mesh.geometries.push_back(std::move(g));
      std::string name = mesh.name;
      addInstance(scene, addMesh(scene, std::move(mesh)), translation(spherePosition(row, column)),
                  name);
    }
}

// An emissive rectangle standing on the floor, facing `front`.
void addPanel(Scene& scene, const std::string& name, const glm::vec3& radiance, const Frame& frame,
              const glm::vec2& min, const glm::vec2& max) {
  Material m = lambertMaterial(name, glm::vec3(0.0f));
  m.emissive = radiance;
  Geometry g;
  g.material = addMaterial(scene, m);
  addRect(g, frame, min, max);
  Mesh mesh;
  mesh.name = name;
  mesh.geometries.push_back(std::move(g));
  addMeshInstance(scene, std::move(mesh));
}

void addPanels(Scene& scene) {
  // Behind the rows, facing the camera (+Z); a warm white strip.
  addPanel(scene, "panel_back", {12.0f, 11.0f, 9.0f}, Frame{{0, 0, -4.5f}, {1, 0, 0}, {0, 1, 0}},
           {-3.0f, 0.55f}, {3.0f, 1.45f});
  // Left (-X), facing +X; a cool blue. Right (+X), facing -X; an orange.
  addPanel(scene, "panel_left", {3.0f, 6.0f, 14.0f}, Frame{{-5.5f, 0, 0}, {0, 0, 1}, {0, 1, 0}},
           {-1.5f, 0.3f}, {1.5f, 2.7f});
  addPanel(scene, "panel_right", {14.0f, 7.0f, 3.0f}, Frame{{5.5f, 0, 0}, {0, 0, -1}, {0, 1, 0}},
           {-1.5f, 0.3f}, {1.5f, 2.7f});
}

}  // namespace

Scene makeSpheresScene() {
  Scene scene;
  scene.name = "spheres";
  uint32_t light = addMaterial(scene, lambertMaterial("floor_light", glm::vec3(0.6f)));
  uint32_t dark = addMaterial(scene, lambertMaterial("floor_dark", glm::vec3(0.25f)));
  addMeshInstance(scene, makeFloor(light, dark));
  addSpheres(scene);
  addPanels(scene);

  // From behind the camera's right shoulder, 40 degrees up; a clear daylight sky.
  scene.sun = sunFromAngles(40.0f, 200.0f, 100.0f, {1.0f, 0.96f, 0.9f});
  scene.sky.model = SkyModel::Daylight;
  scene.sky.turbidity = 3.0f;

  Camera camera;
  camera.position = {0.0f, 3.6f, 6.4f};
  camera.target = {0.0f, 0.2f, -0.3f};
  camera.verticalFovDegrees = 42.0f;
  scene.camera = camera;
  return scene;
}

}  // namespace bounce::procedural
