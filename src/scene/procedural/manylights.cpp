// Many lights: a closed room lit only by 64 coloured point lights (seed 002's ReSTIR DI test:
// sampling one light uniformly is noisy here, resampling by contribution is not). Sixteen hang
// in a grid under the ceiling, 48 line the walls at two heights; the furniture stands clear of
// all of them and casts overlapping coloured shadows.
#include <cmath>
#include <string>

#include <fmt/format.h>

#include "scene/procedural/builtin_scenes.h"
#include "scene/procedural/mesh_builder.h"
#include "scene/procedural/random.h"

namespace bounce::procedural {

namespace {

const Aabb kRoom{{-5.0f, 0.0f, -6.0f}, {5.0f, 3.2f, 6.0f}};
constexpr float kWallLightOffset = 0.5f;  // metres in front of the wall
constexpr int kWallLightsPerRow = 6;
constexpr float kWallLightHeights[2] = {0.9f, 2.1f};

struct RoomMaterials {
  uint32_t floor, ceiling, wall, accentWall, wood, fabric, gold;
};

RoomMaterials addRoomMaterials(Scene& scene) {
  RoomMaterials m;
  m.floor = addMaterial(scene, lambertMaterial("floor_stone", {0.55f, 0.50f, 0.45f}));
  m.ceiling = addMaterial(scene, lambertMaterial("ceiling_white", {0.80f, 0.80f, 0.78f}));
  m.wall = addMaterial(scene, lambertMaterial("wall_plaster", {0.70f, 0.68f, 0.64f}));
  m.accentWall = addMaterial(scene, lambertMaterial("wall_sage", {0.32f, 0.50f, 0.36f}));
  m.wood = addMaterial(scene, lambertMaterial("furniture_wood", {0.45f, 0.30f, 0.18f}));
  m.fabric = addMaterial(scene, lambertMaterial("sofa_fabric", {0.25f, 0.30f, 0.52f}));
  Material gold = lambertMaterial("crate_gold", {1.0f, 0.78f, 0.34f});
  gold.metallic = 1.0f;
  gold.roughness = 0.3f;
  m.gold = addMaterial(scene, gold);
  return m;
}

Mesh makeRoom(const RoomMaterials& m) {
  MeshBuilder builder;
  addBox(builder.geometry(m.floor), kRoom, Facing::Inward, kFaceNegY);
  addBox(builder.geometry(m.ceiling), kRoom, Facing::Inward, kFacePosY);
  addBox(builder.geometry(m.wall), kRoom, Facing::Inward, kFaceNegX | kFacePosX | kFacePosZ);
  addBox(builder.geometry(m.accentWall), kRoom, Facing::Inward, kFaceNegZ);
  return builder.build("room");
}

// ---- furniture, each built standing on y = 0 around the origin ---------------------------------

Aabb boxAt(const glm::vec3& center, const glm::vec3& size, float bottom) {
  return Aabb{{center.x - 0.5f * size.x, bottom, center.z - 0.5f * size.z},
              {center.x + 0.5f * size.x, bottom + size.y, center.z + 0.5f * size.z}};
}

// Four legs under a top of `size` (x, z) at `height`, `inset` in from its edges.
void addLegs(Geometry& g, const glm::vec2& size, float height, float leg, float inset) {
  for (float sx : {-1.0f, 1.0f})
    for (float sz : {-1.0f, 1.0f}) {
      glm::vec3 c{sx * (0.5f * size.x - inset - 0.5f * leg), 0,
                  sz * (0.5f * size.y - inset - 0.5f * leg)};
      addBox(g, boxAt(c, {leg, height, leg}, 0.0f), Facing::Outward, kNoBottom & ~kFacePosY);
    }
}

Mesh makeTable(uint32_t wood) {
  MeshBuilder builder;
  Geometry& g = builder.geometry(wood);
  addBox(g, boxAt({0, 0, 0}, {1.8f, 0.05f, 0.9f}, 0.72f));
  addLegs(g, {1.8f, 0.9f}, 0.72f, 0.07f, 0.05f);
  return builder.build("table");
}

Mesh makeChair(uint32_t wood) {
  MeshBuilder builder;
  Geometry& g = builder.geometry(wood);
  addBox(g, boxAt({0, 0, 0}, {0.45f, 0.04f, 0.45f}, 0.43f));
  addBox(g, boxAt({0, 0, -0.205f}, {0.45f, 0.45f, 0.04f}, 0.47f));  // back rest
  addLegs(g, {0.45f, 0.45f}, 0.43f, 0.04f, 0.01f);
  return builder.build("chair");
}

Mesh makeShelf(uint32_t wood) {
  const glm::vec3 size{1.2f, 1.8f, 0.4f};
  const float board = 0.03f;
  MeshBuilder builder;
  Geometry& g = builder.geometry(wood);
  for (float side : {-1.0f, 1.0f})
    addBox(g, boxAt({side * 0.5f * (size.x - board), 0, 0}, {board, size.y, size.z}, 0.0f),
           Facing::Outward, kNoBottom);
  addBox(g, boxAt({0, 0, -0.5f * (size.z - board)}, {size.x - 2 * board, size.y, board}, 0.0f),
         Facing::Outward, kNoBottom);
  for (int level = 0; level < 5; ++level) {
    float y = float(level) * (size.y - board) / 4.0f;
    addBox(g, boxAt({0, 0, 0.5f * board}, {size.x - 2 * board, board, size.z - board}, y));
  }
  return builder.build("shelf");
}

Mesh makeSofa(uint32_t fabric) {
  MeshBuilder builder;
  Geometry& g = builder.geometry(fabric);
  addBox(g, boxAt({0, 0, 0.05f}, {1.8f, 0.42f, 0.8f}, 0.0f), Facing::Outward, kNoBottom);
  addBox(g, boxAt({0, 0, -0.4f}, {2.2f, 0.85f, 0.2f}, 0.0f), Facing::Outward, kNoBottom);
  for (float side : {-1.0f, 1.0f})
    addBox(g, boxAt({side * 1.0f, 0, 0.05f}, {0.2f, 0.62f, 0.8f}, 0.0f), Facing::Outward,
           kNoBottom);
  return builder.build("sofa");
}

Mesh makeCrate(uint32_t gold) {
  MeshBuilder builder;
  addBox(builder.geometry(gold), boxAt({0, 0, 0}, glm::vec3(0.6f), 0.0f), Facing::Outward,
         kNoBottom);
  return builder.build("crate_gold");
}

void placeFurniture(Scene& scene, uint32_t mesh, const glm::vec2& xz, float yawDegrees,
                    const std::string& name) {
  addInstance(scene, mesh, translation({xz.x, 0.0f, xz.y}) * rotationY(glm::radians(yawDegrees)),
              name);
}

void furnish(Scene& scene, const RoomMaterials& m) {
  uint32_t table = addMesh(scene, makeTable(m.wood));
  uint32_t chair = addMesh(scene, makeChair(m.wood));
  uint32_t shelf = addMesh(scene, makeShelf(m.wood));
  uint32_t sofa = addMesh(scene, makeSofa(m.fabric));
  uint32_t crate = addMesh(scene, makeCrate(m.gold));
  placeFurniture(scene, table, {-1.5f, -2.0f}, 0.0f, "table_0");
  placeFurniture(scene, table, {2.0f, 2.5f}, 90.0f, "table_1");
  const glm::vec2 chairs[4] = {{-2.0f, -2.7f}, {-1.0f, -2.7f}, {-2.0f, -1.3f}, {-1.0f, -1.3f}};
  for (int i = 0; i < 4; ++i)
    placeFurniture(scene, chair, chairs[i], i < 2 ? 0.0f : 180.0f, fmt::format("chair_{}", i));
  placeFurniture(scene, shelf, {3.3f, -3.5f}, -90.0f, "shelf_0");
  placeFurniture(scene, shelf, {-3.3f, 3.0f}, 90.0f, "shelf_1");
  placeFurniture(scene, sofa, {-1.0f, 3.8f}, 180.0f, "sofa");
  placeFurniture(scene, crate, {1.2f, -0.6f}, 25.0f, "crate_gold");
}

// ---- the 64 lights -----------------------------------------------------------------------------

glm::vec3 hueToRgb(float hue, float saturation) {
  glm::vec3 rgb = glm::clamp(
      glm::abs(glm::mod(hue * 6.0f + glm::vec3(0, 4, 2), 6.0f) - 3.0f) - 1.0f, 0.0f, 1.0f);
  return glm::mix(glm::vec3(1.0f), rgb, saturation);
}

void addPointLight(Scene& scene, Pcg32& rng, const glm::vec3& position, std::string name) {
  PunctualLight light;
  light.type = PunctualLight::Type::Point;
  light.name = std::move(name);
  // Golden-ratio hue steps spread the colours evenly, whatever the count.
  light.color = hueToRgb(std::fmod(0.618034f * float(scene.lights.size()), 1.0f), 0.6f);
  // A few candela each: 64 of them put roughly 10-30 W/m^2 on the room's surfaces, the same
  // order as the sunlit scenes, so one exposure suits every built-in scene.
  light.intensity = rng.uniform(4.0f, 10.0f);
  light.position = position;
  scene.lights.push_back(std::move(light));
}

void addCeilingLights(Scene& scene, Pcg32& rng) {
  const float y = kRoom.max.y - 0.3f;
  for (int row = 0; row < 4; ++row)
    for (int col = 0; col < 4; ++col) {
      float x = glm::mix(kRoom.min.x, kRoom.max.x, (float(col) + 0.5f) / 4.0f);
      float z = glm::mix(kRoom.min.z, kRoom.max.z, (float(row) + 0.5f) / 4.0f);
      addPointLight(scene, rng, {x, y, z}, fmt::format("ceiling_light_r{}_c{}", row, col));
    }
}

// Twelve lights in front of one wall (where coordinate `axis` is at its min or max): six along
// the wall at each of two heights.
void addWallLights(Scene& scene, Pcg32& rng, int axis, bool maxSide, const char* wallName) {
  const int along = axis == 0 ? 2 : 0;
  const float inwards = maxSide ? -kWallLightOffset : kWallLightOffset;
  for (int level = 0; level < 2; ++level)
    for (int i = 0; i < kWallLightsPerRow; ++i) {
      glm::vec3 p;
      p[axis] = (maxSide ? kRoom.max[axis] : kRoom.min[axis]) + inwards;
      p[along] = glm::mix(kRoom.min[along], kRoom.max[along],
                          (float(i) + 0.5f) / float(kWallLightsPerRow));
      p.y = kWallLightHeights[level];
      addPointLight(scene, rng, p,
                    fmt::format("wall_light_{}_{}_{}", wallName, level == 0 ? "low" : "high", i));
    }
}

// The lights' animation (--animate; the light-animation tests): over a 4 s loop, every third wall
// light blinks (off for a second, each at its own phase), the next of each three bobs up and
// down by 0.4 m, and the four middle ceiling lights pulse between 0.2 and 2 times their
// intensity. The other 28 stay as they are.
void animateLights(Scene& scene) {
  constexpr float kLoopSeconds = 4.0f;
  constexpr uint32_t kCeilingLights = 16;
  for (uint32_t i = 0; i < scene.lights.size(); ++i) {
    LightTrack track;
    track.light = i;
    const float phase = 0.25f + 2.5f * float(i % 7) / 7.0f;  // in [0.25, 2.4] s
    if (i < kCeilingLights) {
      const uint32_t row = i / 4, col = i % 4;
      if (row < 1 || row > 2 || col < 1 || col > 2) continue;
      track.intensityScale.times = {0.0f, 1.0f, 2.0f, 3.0f, kLoopSeconds};
      track.intensityScale.values = {1.0f, 2.0f, 1.0f, 0.2f, 1.0f};
    } else if ((i - kCeilingLights) % 3 == 0) {
      // Off from `phase` for a second.
      track.intensityScale.interpolation = Interpolation::Step;
      track.intensityScale.times = {0.0f, phase, phase + 1.0f, kLoopSeconds};
      track.intensityScale.values = {1.0f, 0.0f, 1.0f, 1.0f};
    } else if ((i - kCeilingLights) % 3 == 1) {
      const glm::vec3 p = scene.lights[i].position;
      const glm::vec3 up{0.0f, 0.4f, 0.0f};
      track.position.times = {0.0f, 1.0f, 2.0f, 3.0f, kLoopSeconds};
      track.position.values = {p, p + up, p, p - up, p};
    } else {
      continue;
    }
    scene.animation.lights.push_back(std::move(track));
  }
}

}  // namespace

Scene makeManyLightsScene() {
  Scene scene;
  scene.name = "manylights";
  const RoomMaterials m = addRoomMaterials(scene);
  addMeshInstance(scene, makeRoom(m));
  furnish(scene, m);

  Pcg32 rng(64);
  addCeilingLights(scene, rng);
  addWallLights(scene, rng, 2, false, "north");  // z = min
  addWallLights(scene, rng, 2, true, "south");
  addWallLights(scene, rng, 0, false, "west");  // x = min
  addWallLights(scene, rng, 0, true, "east");
  animateLights(scene);

  // Night: no sun, no sky; the closed room would hide them anyway.
  scene.sun.irradiance = 0.0f;
  scene.sky.radiance = glm::vec3(0.0f);

  Camera camera;
  camera.position = {4.3f, 1.7f, 5.4f};
  camera.target = {-1.5f, 0.8f, -2.5f};
  camera.verticalFovDegrees = 65.0f;
  scene.camera = camera;
  return scene;
}

}  // namespace bounce::procedural
