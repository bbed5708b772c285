// Skinned: the scene for deforming meshes (issue 22). In a corner of two walls stand a skinned
// tube, three joints stacked up its height that bend and twist it back and forth, and a gold
// blob that stretches up and squashes flat through two morph targets. The sun and a daylight
// sky light them; the walls catch their bounce light and the floor their shadows. Its animation
// loops every kLoopSeconds, so `--animate` shows moving geometry, its shadows and GI, and the
// motion vectors of vertices that move while their instances stand still. `skinned-crowd` is the
// cost test: 16 x 16 finer tubes and 8 x 8 blobs on a plain, each its own mesh, out of phase.
#include <cmath>
#include <string>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include "scene/procedural/builtin_scenes.h"
#include "scene/procedural/mesh_builder.h"

namespace bounce::procedural {

namespace {

constexpr float kPi = 3.14159265358979f;
constexpr float kLoopSeconds = 4.0f;
constexpr int kKeys = 17;  // keys per loop, the last equal to the first

// A tube: `rings` rings of `segments` vertices up to kTubeHeight above `base`, one joint at the
// base and one a third and two thirds of the way up, swaying `phase` radians into its loop.
constexpr float kTubeHeight = 2.1f;
constexpr float kTubeRadius = 0.22f;
constexpr int kTubeJoints = 3;
struct TubeShape {
  glm::vec3 base{0.0f};
  int rings = 36;
  int segments = 24;
  float phase = 0.0f;
};

constexpr float kBlobRadius = 0.45f;

float jointHeight(int joint) {
  return kTubeHeight * float(joint) / float(kTubeJoints);
}

// Each vertex follows the two joints nearest below and above its height, blended linearly
// between their heights so that the bends are smooth.
void tubeInfluence(float height, glm::uvec4& joints, glm::vec4& weights) {
  float spacing = kTubeHeight / float(kTubeJoints);
  float s = glm::clamp(height / spacing - 0.5f, 0.0f, float(kTubeJoints - 1));
  int lower = std::min(int(s), kTubeJoints - 2);
  float f = s - float(lower);
  joints = glm::uvec4(uint32_t(lower), uint32_t(lower + 1), 0u, 0u);
  weights = glm::vec4(1.0f - f, f, 0.0f, 0.0f);
}

Geometry makeTube(uint32_t material, const TubeShape& shape) {
  Geometry g;
  g.material = material;
  for (int ring = 0; ring <= shape.rings; ++ring) {
    float y = kTubeHeight * float(ring) / float(shape.rings);
    for (int s = 0; s <= shape.segments; ++s) {
      float phi = 2.0f * kPi * float(s) / float(shape.segments);
      glm::vec3 n{std::cos(phi), 0.0f, -std::sin(phi)};
      g.positions.push_back(shape.base + glm::vec3(0.0f, y, 0.0f) + kTubeRadius * n);
      g.normals.push_back(n);
      g.uvs.emplace_back(float(s) / float(shape.segments), 1.0f - y / kTubeHeight);
      glm::uvec4 joints;
      glm::vec4 weights;
      tubeInfluence(y, joints, weights);
      g.joints.push_back(joints);
      g.weights.push_back(weights);
    }
  }
  auto at = [&](int ring, int s) { return uint32_t(ring * (shape.segments + 1) + s); };
  for (int ring = 0; ring < shape.rings; ++ring)
    for (int s = 0; s < shape.segments; ++s) {
      // phi grows counter-clockwise seen from +Y: (ring, s), (ring, s + 1), (ring + 1, s + 1)
      // turns counter-clockwise seen from outside.
      uint32_t a = at(ring, s), b = at(ring, s + 1), c = at(ring + 1, s + 1), d = at(ring + 1, s);
      g.indices.insert(g.indices.end(), {a, b, c, a, c, d});
    }
  return g;
}

Skin makeTubeSkin(Scene& scene, const std::string& name, const glm::vec3& base) {
  Skin skin;
  skin.name = name + "_skin";
  for (int j = 0; j < kTubeJoints; ++j) {
    SkeletonNode node;
    node.name = name + "_joint_" + std::to_string(j);
    node.parent = j == 0 ? -1 : int(scene.skeleton.size()) - 1;
    glm::vec3 offset = j == 0 ? base : glm::vec3(0.0f, jointHeight(1), 0.0f);
    node.local = glm::translate(glm::mat4(1.0f), offset);
    skin.joints.push_back(uint32_t(scene.skeleton.size()));
    scene.skeleton.push_back(node);
    glm::mat4 bindWorld = glm::translate(glm::mat4(1.0f), base + glm::vec3(0, jointHeight(j), 0));
    skin.inverseBindMatrices.push_back(glm::inverse(bindWorld));
  }
  return skin;
}

// A loop of kKeys rotation keys: the base twists about Y, the upper joints bend about Z and X
// out of phase, so the tube sways in a figure of eight.
void animateTube(const Scene& scene, const Skin& skin, float phaseOffset,
                 SceneAnimation& animation) {
  for (int j = 0; j < kTubeJoints; ++j) {
    JointTrack track;
    track.node = skin.joints[size_t(j)];
    track.trs.restTranslation = glm::vec3(scene.skeleton[track.node].local[3]);
    for (int k = 0; k < kKeys; ++k) {
      float t = kLoopSeconds * float(k) / float(kKeys - 1);
      float phase = 2.0f * kPi * t / kLoopSeconds + phaseOffset;
      glm::quat q(1.0f, 0.0f, 0.0f, 0.0f);
      if (j == 0)
        q = glm::angleAxis(glm::radians(40.0f) * std::sin(phase), glm::vec3(0, 1, 0));
      else
        q = glm::angleAxis(glm::radians(22.0f) * std::sin(phase + float(j)), glm::vec3(0, 0, 1)) *
            glm::angleAxis(glm::radians(12.0f) * std::cos(phase), glm::vec3(1, 0, 0));
      track.trs.rotation.times.push_back(t);
      track.trs.rotation.values.push_back(q);
    }
    animation.joints.push_back(std::move(track));
  }
}

// A morph target scaling the blob by `scale` about `base`: positions move there, normals turn
// to the scaled sphere's (the inverse-scaled normal).
MorphTarget scaledTarget(const Geometry& rest, const glm::vec3& base, const glm::vec3& scale) {
  MorphTarget target;
  for (size_t v = 0; v < rest.positions.size(); ++v) {
    glm::vec3 p = base + scale * (rest.positions[v] - base);
    glm::vec3 n = glm::normalize(rest.normals[v] / scale);
    target.positions.push_back(p - rest.positions[v]);
    target.normals.push_back(n - rest.normals[v]);
  }
  return target;
}

// A blob standing on the floor at `base` (the point it stretches from).
Mesh makeBlob(uint32_t material, const glm::vec3& base, std::string name) {
  Geometry g;
  g.material = material;
  addSphere(g, base + glm::vec3(0.0f, kBlobRadius, 0.0f), kBlobRadius, 40, 20);
  g.morphTargets.push_back(scaledTarget(g, base, {0.75f, 1.6f, 0.75f}));   // stretched up
  g.morphTargets.push_back(scaledTarget(g, base, {1.35f, 0.55f, 1.35f}));  // squashed flat
  Mesh mesh;
  mesh.name = std::move(name);
  mesh.geometries.push_back(std::move(g));
  mesh.morphWeights = {0.0f, 0.0f};
  return mesh;
}

// Stretch for the first half of the loop, squash for the second.
MorphWeightTrack animateBlob(uint32_t mesh, float phaseOffset) {
  MorphWeightTrack track;
  track.mesh = mesh;
  track.targets = 2;
  for (int k = 0; k < kKeys; ++k) {
    float t = kLoopSeconds * float(k) / float(kKeys - 1);
    float s = std::sin(2.0f * kPi * t / kLoopSeconds + phaseOffset);
    track.times.push_back(t);
    track.values.push_back(std::max(s, 0.0f));
    track.values.push_back(std::max(-s, 0.0f));
  }
  return track;
}

void addRoomCorner(Scene& scene) {
  uint32_t floor = addMaterial(scene, lambertMaterial("floor", glm::vec3(0.6f)));
  uint32_t back = addMaterial(scene, lambertMaterial("back_wall", glm::vec3(0.75f)));
  uint32_t side = addMaterial(scene, lambertMaterial("side_wall", {0.15f, 0.3f, 0.7f}));
  MeshBuilder builder;
  // From the back wall to under the camera.
  addRect(builder.geometry(floor), Frame{{0, 0, 0}, {1, 0, 0}, {0, 0, -1}}, {-3.0f, -5.5f},
          {3.0f, 2.0f});
  addRect(builder.geometry(back), Frame{{0, 0, -2.0f}, {1, 0, 0}, {0, 1, 0}}, {-3.0f, 0.0f},
          {3.0f, 3.0f});
  addRect(builder.geometry(side), Frame{{-3.0f, 0, 0}, {0, 0, 1}, {0, 1, 0}}, {-2.0f, 0.0f},
          {3.0f, 3.0f});
  addMeshInstance(scene, builder.build("room_corner"));
}

Material tubeMaterial() {
  Material orange = lambertMaterial("tube", {0.8f, 0.32f, 0.08f});
  orange.roughness = 0.5f;
  orange.doubleSided = true;  // its top is open
  return orange;
}

Material blobMaterial() {
  Material gold = lambertMaterial("blob", {1.0f, 0.78f, 0.34f});
  gold.metallic = 1.0f;
  gold.roughness = 0.3f;
  return gold;
}

// A skinned tube of its own mesh and skin, animated; placed by the identity (its joints place
// it).
void addTube(Scene& scene, uint32_t material, const std::string& name, const TubeShape& shape) {
  Mesh tube;
  tube.name = name;
  tube.geometries.push_back(makeTube(material, shape));
  tube.skin = int(scene.skins.size());
  Skin skin = makeTubeSkin(scene, name, shape.base);
  animateTube(scene, skin, shape.phase, scene.animation);
  scene.skins.push_back(std::move(skin));
  addMeshInstance(scene, std::move(tube));
}

void addBlob(Scene& scene, uint32_t material, const std::string& name, const glm::vec3& base,
             float phase) {
  uint32_t blob = addMeshInstance(scene, makeBlob(material, base, name));
  scene.animation.morphWeights.push_back(animateBlob(blob, phase));
}

void addDaylight(Scene& scene) {
  scene.sun = sunFromAngles(50.0f, 160.0f, 100.0f, {1.0f, 0.96f, 0.9f});
  scene.sky.model = SkyModel::Daylight;
  scene.sky.turbidity = 3.0f;
}

}  // namespace

Scene makeSkinnedScene() {
  Scene scene;
  scene.name = "skinned";
  addRoomCorner(scene);
  addTube(scene, addMaterial(scene, tubeMaterial()), "tube", {.base = {-0.7f, 0.0f, 0.0f}});
  addBlob(scene, addMaterial(scene, blobMaterial()), "blob", {0.9f, 0.0f, 0.2f}, 0.0f);
  addDaylight(scene);
  scene.camera = Camera{.position = {0.6f, 2.2f, 5.2f}, .target = {0.0f, 0.9f, 0.0f}};
  return scene;
}

// 16 x 16 tubes of 72 rings of 32 vertices (4,608 triangles each) and 8 x 8 blobs among them on
// a 40 m plain, every one its own deforming mesh, each a step further into its loop.
Scene makeSkinnedCrowdScene() {
  Scene scene;
  scene.name = "skinned-crowd";
  uint32_t ground = addMaterial(scene, lambertMaterial("ground", glm::vec3(0.5f)));
  MeshBuilder builder;
  addRect(builder.geometry(ground), Frame{{0, 0, 0}, {1, 0, 0}, {0, 0, -1}}, {-20.0f, -20.0f},
          {20.0f, 20.0f});
  addMeshInstance(scene, builder.build("ground"));
  uint32_t tube = addMaterial(scene, tubeMaterial());
  uint32_t blob = addMaterial(scene, blobMaterial());
  constexpr int kTubesPerSide = 16, kBlobsPerSide = 8;
  constexpr float kSpacing = 1.5f;
  for (int i = 0; i < kTubesPerSide * kTubesPerSide; ++i) {
    glm::vec3 base{(float(i % kTubesPerSide) - 7.5f) * kSpacing, 0.0f,
                   (float(i / kTubesPerSide) - 7.5f) * kSpacing};
    addTube(scene, tube, "tube_" + std::to_string(i),
            {.base = base, .rings = 72, .segments = 32, .phase = 0.37f * float(i)});
  }
  for (int i = 0; i < kBlobsPerSide * kBlobsPerSide; ++i) {
    glm::vec3 base{(float(i % kBlobsPerSide) - 3.5f) * 2.0f * kSpacing, 0.0f,
                   (float(i / kBlobsPerSide) - 3.5f) * 2.0f * kSpacing};
    addBlob(scene, blob, "blob_" + std::to_string(i), base, 0.61f * float(i));
  }
  addDaylight(scene);
  scene.camera = Camera{
      .position = {0.0f, 3.0f, 13.0f}, .target = {0.0f, 0.5f, 0.0f}, .verticalFovDegrees = 50.0f};
  return scene;
}

}  // namespace bounce::procedural
