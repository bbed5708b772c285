// The sunroom: a closed room with thick walls and one window. A low sun shines through the
// window onto a patch of the floor; everything else inside (most of the walls, the ceiling, the
// shaded sides of the furniture) is lit only by light bounced off that patch and by skylight
// coming through the window, which is the case seed 000's GI is built for.
// `sunroom-glossy` is the same room with a lacquered floor and a polished steel ball rolling
// through the sun patch: the scene for glossy reflections of the sun patch, walls and furniture
// (issue 19), and for reflections of a moving object.
#include "scene/procedural/sunroom.h"

#include <string>

#include "core/error.h"
#include "scene/procedural/builtin_scenes.h"
#include "scene/procedural/mesh_builder.h"

namespace bounce {

const SunroomLayout& sunroomLayout() {
  // Dimensions in quarter metres, so that every wall, window and reveal corner is exactly
  // representable and the faces meet without cracks.
  static const SunroomLayout layout{
      Aabb{{0.0f, 0.0f, 0.0f}, {8.0f, 3.0f, 6.0f}},
      0.25f,
      {2.5f, 0.75f},
      {5.5f, 2.5f},
  };
  return layout;
}

namespace procedural {

namespace {

struct SunroomMaterials {
  uint32_t floor, ceiling, warmWall, coolWall, whiteWall, exterior, ground;
  uint32_t red, teal, yellow, blue, wood;
};

SunroomMaterials addSunroomMaterials(Scene& scene) {
  SunroomMaterials m;
  m.floor = addMaterial(scene, lambertMaterial("floor_oak", {0.50f, 0.34f, 0.20f}));
  m.ceiling = addMaterial(scene, lambertMaterial("ceiling_white", {0.86f, 0.85f, 0.82f}));
  m.warmWall = addMaterial(scene, lambertMaterial("wall_warm_terracotta", {0.78f, 0.46f, 0.30f}));
  m.coolWall = addMaterial(scene, lambertMaterial("wall_cool_blue", {0.36f, 0.52f, 0.72f}));
  m.whiteWall = addMaterial(scene, lambertMaterial("wall_white", {0.76f, 0.75f, 0.71f}));
  m.exterior = addMaterial(scene, lambertMaterial("exterior_plaster", {0.62f, 0.60f, 0.56f}));
  m.ground = addMaterial(scene, lambertMaterial("ground_grass", {0.22f, 0.32f, 0.12f}));
  m.red = addMaterial(scene, lambertMaterial("box_red", {0.70f, 0.12f, 0.08f}));
  m.teal = addMaterial(scene, lambertMaterial("box_teal", {0.10f, 0.50f, 0.45f}));
  m.yellow = addMaterial(scene, lambertMaterial("box_yellow", {0.80f, 0.65f, 0.15f}));
  m.blue = addMaterial(scene, lambertMaterial("panel_blue", {0.20f, 0.26f, 0.62f}));
  Material varnished = lambertMaterial("table_varnished_wood", {0.40f, 0.24f, 0.12f});
  varnished.roughness = 0.35f;
  m.wood = addMaterial(scene, varnished);
  return m;
}

// The shell is two boxes, the room's inner surface facing in and the building's outer surface
// facing out, joined by the window reveal. Inner, outer and reveal faces share their edges
// exactly, so the only way out is through the window.
Mesh makeShell(const SunroomMaterials& m) {
  const SunroomLayout& layout = sunroomLayout();
  const Aabb& in = layout.interior;
  const float t = layout.wallThickness;
  const Aabb out{in.min - glm::vec3(t), in.max + glm::vec3(t)};
  MeshBuilder builder;

  addBox(builder.geometry(m.floor), in, Facing::Inward, kFaceNegY);
  addBox(builder.geometry(m.ceiling), in, Facing::Inward, kFacePosY);
  addBox(builder.geometry(m.warmWall), in, Facing::Inward, kFaceNegX);
  addBox(builder.geometry(m.coolWall), in, Facing::Inward, kFacePosX);
  addBox(builder.geometry(m.whiteWall), in, Facing::Inward, kFacePosZ);

  // The window wall seen from inside: front +Z, s along +X, t along +Y.
  const Frame inside{in.min, {1, 0, 0}, {0, 1, 0}};
  const glm::vec2 holeMin = layout.windowMin - glm::vec2(in.min.x, in.min.y);
  const glm::vec2 holeMax = layout.windowMax - glm::vec2(in.min.x, in.min.y);
  const glm::vec2 innerSize{in.extent().x, in.extent().y};
  addRectWithHole(builder.geometry(m.whiteWall), inside, {0, 0}, innerSize, holeMin, holeMax);
  addOpeningSides(builder.geometry(m.whiteWall), inside, holeMin, holeMax, t);

  // The same wall seen from outside: front -Z, s along -X from the outer corner at max x.
  Geometry& exterior = builder.geometry(m.exterior);
  addBox(exterior, out, Facing::Outward, kAllFaces & ~kFaceNegZ);
  const Frame outside{{out.max.x, out.min.y, out.min.z}, {-1, 0, 0}, {0, 1, 0}};
  auto toOutside = [&](const glm::vec2& xy) {
    return glm::vec2(out.max.x - xy.x, xy.y - out.min.y);
  };
  const glm::vec2 outerSize{out.extent().x, out.extent().y};
  addRectWithHole(exterior, outside, {0, 0}, outerSize,
                  {toOutside(layout.windowMax).x, toOutside(layout.windowMin).y},
                  {toOutside(layout.windowMin).x, toOutside(layout.windowMax).y});
  return builder.build("room_shell");
}

// Outside ground, a little below the room's floor (it runs through the buried part of the
// walls), large enough to fill the view through the window and bounce sunlight back up.
Mesh makeGround(uint32_t material) {
  const float halfSize = 60.0f;
  const glm::vec3 center = sunroomLayout().interior.center();
  Frame ground{{center.x - halfSize, -0.1f, center.z + halfSize}, {1, 0, 0}, {0, 0, -1}};
  MeshBuilder builder;
  addRect(builder.geometry(material), ground, {0, 0}, {2 * halfSize, 2 * halfSize});
  return builder.build("ground");
}

// A box standing on the floor, centred on the origin in x and z, so instances place it.
Mesh makeStandingBox(const std::string& name, uint32_t material, const glm::vec3& size) {
  MeshBuilder builder;
  addBox(builder.geometry(material),
         Aabb{{-0.5f * size.x, 0, -0.5f * size.z}, {0.5f * size.x, size.y, 0.5f * size.z}},
         Facing::Outward, kNoBottom);
  return builder.build(name);
}

Mesh makeTable(uint32_t material) {
  const glm::vec3 size{1.4f, 0.75f, 0.8f};
  const float top = 0.05f, leg = 0.07f, inset = 0.06f;
  MeshBuilder builder;
  Geometry& g = builder.geometry(material);
  addBox(g, Aabb{{-0.5f * size.x, size.y - top, -0.5f * size.z},
                 {0.5f * size.x, size.y, 0.5f * size.z}});
  for (float sx : {-1.0f, 1.0f}) {
    for (float sz : {-1.0f, 1.0f}) {
      glm::vec2 c{sx * (0.5f * size.x - inset - 0.5f * leg),
                  sz * (0.5f * size.z - inset - 0.5f * leg)};
      addBox(g,
             Aabb{{c.x - 0.5f * leg, 0, c.y - 0.5f * leg},
                  {c.x + 0.5f * leg, size.y - top, c.y + 0.5f * leg}},
             Facing::Outward, kNoBottom & ~kFacePosY);
    }
  }
  return builder.build("table");
}

void placeOnFloor(Scene& scene, Mesh mesh, const glm::vec2& xz, float yawDegrees) {
  std::string name = mesh.name;
  uint32_t index = addMesh(scene, std::move(mesh));
  addInstance(scene, index,
              translation({xz.x, sunroomLayout().interior.min.y, xz.y}) *
                  rotationY(glm::radians(yawDegrees)),
              std::move(name));
}

// The default motion: the blue panel swings 80 degrees about its vertical axis and
// back over 4 s, and the yellow cube in the sun patch slides 0.6 m towards the window and back,
// so both moving shadows and object motion vectors show; the camera sways and dollies in.
void addSunroomAnimation(Scene& scene) {
  auto restTrack = [&](const std::string& name) {
    for (uint32_t i = 0; i < scene.instances.size(); ++i)
      if (scene.instances[i].name == name) {
        const glm::mat4& m = scene.instances[i].transform;
        TransformTrack track;
        track.instance = i;
        track.restTranslation = glm::vec3(m[3]);
        track.restRotation = glm::quat_cast(glm::mat3(m));  // placeOnFloor: rotation only
        return track;
      }
    fail("sunroom: no instance named '{}' to animate", name);
  };
  TransformTrack panel = restTrack("movable_panel");
  glm::quat open = glm::angleAxis(glm::radians(80.0f), glm::vec3(0, 1, 0)) * panel.restRotation;
  panel.rotation.times = {0.0f, 2.0f, 4.0f};
  panel.rotation.values = {panel.restRotation, open, panel.restRotation};
  scene.animation.transforms.push_back(panel);

  TransformTrack cube = restTrack("cube_yellow");
  glm::vec3 moved = cube.restTranslation + glm::vec3(0.0f, 0.0f, -0.6f);
  cube.translation.times = {0.0f, 2.0f, 4.0f};
  cube.translation.values = {cube.restTranslation, moved, cube.restTranslation};
  scene.animation.transforms.push_back(cube);

  scene.animation.camera = swayCameraPath(*scene.camera, 4.0f, 0.3f, 8.0f);
}

}  // namespace

Scene makeSunroomScene() {
  Scene scene;
  scene.name = "sunroom";
  const SunroomMaterials m = addSunroomMaterials(scene);
  addMeshInstance(scene, makeShell(m));
  addMeshInstance(scene, makeGround(m.ground));

  // Furniture, one mesh and instance each so any of it can be moved. The yellow cube and the
  // table stand in the sun patch; the rest is lit indirectly.
  placeOnFloor(scene, makeStandingBox("crate_red", m.red, {0.8f, 0.8f, 0.8f}), {1.3f, 4.6f}, 15.0f);
  placeOnFloor(scene, makeStandingBox("cabinet_teal", m.teal, {1.6f, 1.9f, 0.5f}), {3.2f, 5.7f},
               0.0f);
  placeOnFloor(scene, makeStandingBox("cube_yellow", m.yellow, {0.6f, 0.6f, 0.6f}), {2.9f, 3.1f},
               30.0f);
  placeOnFloor(scene, makeTable(m.wood), {4.6f, 2.3f}, -10.0f);
  // A door-sized panel on its own, for animation tests (swinging it changes the bounce light).
  placeOnFloor(scene, makeStandingBox("movable_panel", m.blue, {0.9f, 2.0f, 0.05f}), {6.6f, 1.3f},
               60.0f);

  // Low afternoon sun through the window (from -Z, slightly from +X); a blue sky that also
  // lights the room through the window.
  scene.sun = sunFromAngles(25.0f, -20.0f, 100.0f, {1.0f, 0.86f, 0.68f});
  scene.sky.radiance = {1.5f, 2.1f, 3.2f};

  Camera camera;
  camera.position = {7.7f, 1.7f, 5.7f};
  camera.target = {2.5f, 0.6f, 2.4f};
  camera.verticalFovDegrees = 65.0f;
  scene.camera = camera;
  addSunroomAnimation(scene);
  return scene;
}

namespace {

// The lacquered floor: the oak's colour under a clear coat, as one glTF metallic-roughness
// layer (a dielectric of F0 0.04) with roughness 0.15: sharp enough that the window, furniture
// and sun patch show as blurred images in it.
constexpr float kGlossyFloorRoughness = 0.15f;
constexpr float kBallRadius = 0.3f;
// The ball rolls 1.2 m along x through the sun patch and back over 4 s, as the cube slides.
constexpr glm::vec3 kBallRest{3.7f, kBallRadius, 3.5f};
constexpr glm::vec3 kBallTravel{1.2f, 0.0f, 0.0f};

void addRollingBall(Scene& scene) {
  Material steel = lambertMaterial("ball_polished_steel", {0.78f, 0.78f, 0.76f});
  steel.metallic = 1.0f;
  steel.roughness = 0.1f;
  Geometry g;
  g.material = addMaterial(scene, steel);
  addSphere(g, {0, 0, 0}, kBallRadius, 48, 24);
  Mesh mesh;
  mesh.name = "ball_steel";
  mesh.geometries.push_back(std::move(g));
  const uint32_t instance = uint32_t(scene.instances.size());
  addInstance(scene, addMesh(scene, std::move(mesh)),
              translation({kBallRest.x, sunroomLayout().interior.min.y + kBallRest.y, kBallRest.z}),
              "ball_steel");
  TransformTrack track;
  track.instance = instance;
  track.restTranslation = glm::vec3(scene.instances[instance].transform[3]);
  track.translation.times = {0.0f, 2.0f, 4.0f};
  track.translation.values = {track.restTranslation, track.restTranslation + kBallTravel,
                              track.restTranslation};
  scene.animation.transforms.push_back(track);
}

}  // namespace

Scene makeGlossySunroomScene() {
  Scene scene = makeSunroomScene();
  scene.name = "sunroom-glossy";
  bool floorFound = false;
  for (Material& m : scene.materials)
    if (m.name == "floor_oak") {
      m.name = "floor_oak_lacquered";
      m.roughness = kGlossyFloorRoughness;
      floorFound = true;
    }
  if (!floorFound) fail("sunroom-glossy: the sunroom has no material 'floor_oak'");
  addRollingBall(scene);
  return scene;
}

}  // namespace procedural

}  // namespace bounce
