// The Cornell box, vertex for vertex the same as ../shared/scenes/cornell_box/cornell_box.gltf
// (Cornell University's published "Cornell Box Data" in metres, as exported by Blender), so the
// built-in scene and the file render identically and either can serve as the other's reference.
#include <vector>

#include "scene/procedural/builtin_scenes.h"
#include "scene/procedural/mesh_builder.h"

namespace bounce::procedural {

namespace {

struct Quad {
  glm::vec3 p0, p1, p2, p3;
};

enum CornellMaterial : uint32_t { kWhite, kGreen, kRed, kLight };

// One glTF mesh of the file: its quads in the file's vertex order (each quad is two triangles
// 0 1 2 and 0 2 3, as in the file's index buffers).
struct CornellPart {
  const char* name;
  CornellMaterial material;
  std::vector<Quad> quads;
};

// The coordinates are the file's float32 values printed with 9 significant digits, which
// round-trip exactly. The light sits 0.1 mm below the ceiling and faces down.
const std::vector<CornellPart>& cornellParts() {
  static const std::vector<CornellPart> parts = {
      {"floor",
       kWhite,
       {
           {{0.5528f, 0.0f, 0.0f},
            {0.0f, 0.0f, 0.0f},
            {0.0f, 0.0f, 0.559200048f},
            {0.549600005f, 0.0f, 0.559200048f}},
       }},
      {"ceiling",
       kWhite,
       {
           {{0.556000054f, 0.548799992f, 0.0f},
            {0.556000054f, 0.548799992f, 0.559200048f},
            {0.0f, 0.548799992f, 0.559200048f},
            {0.0f, 0.548799992f, 0.0f}},
       }},
      {"back_wall",
       kWhite,
       {
           {{0.549600005f, 0.0f, 0.559200048f},
            {0.0f, 0.0f, 0.559200048f},
            {0.0f, 0.548799992f, 0.559200048f},
            {0.556000054f, 0.548799992f, 0.559200048f}},
       }},
      {"right_wall_green",
       kGreen,
       {
           {{0.0f, 0.0f, 0.559200048f},
            {0.0f, 0.0f, 0.0f},
            {0.0f, 0.548799992f, 0.0f},
            {0.0f, 0.548799992f, 0.559200048f}},
       }},
      {"left_wall_red",
       kRed,
       {
           {{0.5528f, 0.0f, 0.0f},
            {0.549600005f, 0.0f, 0.559200048f},
            {0.556000054f, 0.548799992f, 0.559200048f},
            {0.556000054f, 0.548799992f, 0.0f}},
       }},
      {"short_block",
       kWhite,
       {
           {{0.13000001f, 0.165000007f, 0.0650000051f},
            {0.0820000023f, 0.165000007f, 0.225000009f},
            {0.24000001f, 0.165000007f, 0.272000015f},
            {0.290000021f, 0.165000007f, 0.114000008f}},
           {{0.290000021f, 0.0f, 0.114000008f},
            {0.290000021f, 0.165000007f, 0.114000008f},
            {0.24000001f, 0.165000007f, 0.272000015f},
            {0.24000001f, 0.0f, 0.272000015f}},
           {{0.13000001f, 0.0f, 0.0650000051f},
            {0.13000001f, 0.165000007f, 0.0650000051f},
            {0.290000021f, 0.165000007f, 0.114000008f},
            {0.290000021f, 0.0f, 0.114000008f}},
           {{0.0820000023f, 0.0f, 0.225000009f},
            {0.0820000023f, 0.165000007f, 0.225000009f},
            {0.13000001f, 0.165000007f, 0.0650000051f},
            {0.13000001f, 0.0f, 0.0650000051f}},
           {{0.24000001f, 0.0f, 0.272000015f},
            {0.24000001f, 0.165000007f, 0.272000015f},
            {0.0820000023f, 0.165000007f, 0.225000009f},
            {0.0820000023f, 0.0f, 0.225000009f}},
       }},
      {"tall_block",
       kWhite,
       {
           {{0.423000008f, 0.330000013f, 0.247000009f},
            {0.265000015f, 0.330000013f, 0.296000004f},
            {0.31400001f, 0.330000013f, 0.45600003f},
            {0.472000033f, 0.330000013f, 0.406000018f}},
           {{0.423000008f, 0.0f, 0.247000009f},
            {0.423000008f, 0.330000013f, 0.247000009f},
            {0.472000033f, 0.330000013f, 0.406000018f},
            {0.472000033f, 0.0f, 0.406000018f}},
           {{0.472000033f, 0.0f, 0.406000018f},
            {0.472000033f, 0.330000013f, 0.406000018f},
            {0.31400001f, 0.330000013f, 0.45600003f},
            {0.31400001f, 0.0f, 0.45600003f}},
           {{0.31400001f, 0.0f, 0.45600003f},
            {0.31400001f, 0.330000013f, 0.45600003f},
            {0.265000015f, 0.330000013f, 0.296000004f},
            {0.265000015f, 0.0f, 0.296000004f}},
           {{0.265000015f, 0.0f, 0.296000004f},
            {0.265000015f, 0.330000013f, 0.296000004f},
            {0.423000008f, 0.330000013f, 0.247000009f},
            {0.423000008f, 0.0f, 0.247000009f}},
       }},
      {"light",
       kLight,
       {
           {{0.343000025f, 0.548700035f, 0.227000013f},
            {0.343000025f, 0.548700035f, 0.332000017f},
            {0.213000014f, 0.548700035f, 0.332000017f},
            {0.213000014f, 0.548700035f, 0.227000013f}},
       }},
  };
  return parts;
}

// The file's materials: all doubleSided, metallic 0, roughness 1 (its specular is 0, i.e. pure
// Lambert). The light's emission (17, 12, 4) is the file's emissiveFactor x emissive strength.
void addCornellMaterials(Scene& scene) {
  auto cornellMaterial = [](const char* name, glm::vec3 color) {
    Material m = lambertMaterial(name, color);
    m.doubleSided = true;
    return m;
  };
  addMaterial(scene, cornellMaterial("cb_white", {0.725f, 0.71f, 0.68f}));
  addMaterial(scene, cornellMaterial("cb_green", {0.14f, 0.45f, 0.091f}));
  addMaterial(scene, cornellMaterial("cb_red", {0.63f, 0.065f, 0.05f}));
  Material light = cornellMaterial("cb_light", {0.78f, 0.78f, 0.78f});
  light.emissive = {17.0f, 12.0f, 4.0f};
  addMaterial(scene, light);
}

}  // namespace

Scene makeCornellScene() {
  Scene scene;
  scene.name = "cornell";
  addCornellMaterials(scene);
  for (const CornellPart& part : cornellParts()) {
    Geometry g;
    g.material = part.material;
    for (const Quad& q : part.quads) addQuad(g, q.p0, q.p1, q.p2, q.p3, glm::vec2(1.0f));
    Mesh mesh;
    mesh.name = part.name;
    mesh.geometries.push_back(std::move(g));
    addMeshInstance(scene, std::move(mesh));
  }
  // The file's camera node 'ref_cam': yfov 0.6860488 rad.
  Camera camera;
  camera.position = {0.278f, 0.273f, -0.8f};
  camera.target = {0.278f, 0.273f, 0.0f};
  camera.verticalFovDegrees = 39.3077f;
  scene.camera = camera;
  scene.sun.irradiance = 0.0f;
  scene.sky.radiance = glm::vec3(0.0f);
  return scene;
}

}  // namespace bounce::procedural
