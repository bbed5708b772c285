// Skinned: the scene for deforming meshes (issue 22). In a corner of two walls stand a skinned
// tube, three joints stacked up its height that bend and twist it back and forth, and a gold
// blob that stretches up and squashes flat through two morph targets. The sun and a daylight
// sky light them; the walls catch their bounce light and the floor their shadows. Its animation
// loops every kLoopSeconds, so `--animate` shows moving geometry, its shadows and GI, and the
// motion vectors of vertices that move while their instances stand still.
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include "scene/procedural/builtin_scenes.h"
#include "scene/procedural/mesh_builder.h"

namespace bounce::procedural {

namespace {

constexpr float kPi = 3.14159265358979f;
constexpr float kLoopSeconds = 4.0f;
constexpr int kKeys = 17;  // keys per loop, the last equal to the first

// The tube: kTubeRings rings of kTubeSegments vertices up to kTubeHeight, one joint at the base
// and one a third and two thirds of the way up.
constexpr glm::vec3 kTubeBase{-0.7f, 0.0f, 0.0f};
constexpr float kTubeHeight = 2.1f;
constexpr float kTubeRadius = 0.22f;
constexpr int kTubeRings = 36;
constexpr int kTubeSegments = 24;
constexpr int kTubeJoints = 3;

constexpr glm::vec3 kBlobBase{0.9f, 0.0f, 0.2f};  // the point on the floor it stretches from
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

Geometry makeTube(uint32_t material) {
  Geometry g;
  g.material = material;
  for (int ring = 0; ring <= kTubeRings; ++ring) {
    float y = kTubeHeight * float(ring) / float(kTubeRings);
    for (int s = 0; s <= kTubeSegments; ++s) {
      float phi = 2.0f * kPi * float(s) / float(kTubeSegments);
      glm::vec3 n{std::cos(phi), 0.0f, -std::sin(phi)};
      g.positions.push_back(kTubeBase + glm::vec3(0.0f, y, 0.0f) + kTubeRadius * n);
      g.normals.push_back(n);
      g.uvs.emplace_back(float(s) / float(kTubeSegments), 1.0f - y / kTubeHeight);
      glm::uvec4 joints;
      glm::vec4 weights;
      tubeInfluence(y, joints, weights);
      g.joints.push_back(joints);
      g.weights.push_back(weights);
    }
  }
  auto at = [](int ring, int s) { return uint32_t(ring * (kTubeSegments + 1) + s); };
  for (int ring = 0; ring < kTubeRings; ++ring)
    for (int s = 0; s < kTubeSegments; ++s) {
      // phi grows counter-clockwise seen from +Y: (ring, s), (ring, s + 1), (ring + 1, s + 1)
      // turns counter-clockwise seen from outside.
      uint32_t a = at(ring, s), b = at(ring, s + 1), c = at(ring + 1, s + 1), d = at(ring + 1, s);
      g.indices.insert(g.indices.end(), {a, b, c, a, c, d});
    }
  return g;
}

Skin makeTubeSkin(Scene& scene) {
  Skin skin;
  skin.name = "tube_skin";
  for (int j = 0; j < kTubeJoints; ++j) {
    SkeletonNode node;
    node.name = "tube_joint_" + std::to_string(j);
    node.parent = j == 0 ? -1 : int(scene.skeleton.size()) - 1;
    glm::vec3 offset = j == 0 ? kTubeBase : glm::vec3(0.0f, jointHeight(1), 0.0f);
    node.local = glm::translate(glm::mat4(1.0f), offset);
    skin.joints.push_back(uint32_t(scene.skeleton.size()));
    scene.skeleton.push_back(node);
    glm::mat4 bindWorld =
        glm::translate(glm::mat4(1.0f), kTubeBase + glm::vec3(0, jointHeight(j), 0));
    skin.inverseBindMatrices.push_back(glm::inverse(bindWorld));
  }
  return skin;
}

// A loop of kKeys rotation keys: the base twists about Y, the upper joints bend about Z and X
// out of phase, so the tube sways in a figure of eight.
void animateTube(const Scene& scene, const Skin& skin, SceneAnimation& animation) {
  for (int j = 0; j < kTubeJoints; ++j) {
    JointTrack track;
    track.node = skin.joints[size_t(j)];
    track.trs.restTranslation = glm::vec3(scene.skeleton[track.node].local[3]);
    for (int k = 0; k < kKeys; ++k) {
      float t = kLoopSeconds * float(k) / float(kKeys - 1);
      float phase = 2.0f * kPi * t / kLoopSeconds;
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

// A morph target scaling the blob by `scale` about kBlobBase: positions move there, normals turn
// to the scaled sphere's (the inverse-scaled normal).
MorphTarget scaledTarget(const Geometry& rest, const glm::vec3& scale) {
  MorphTarget target;
  for (size_t v = 0; v < rest.positions.size(); ++v) {
    glm::vec3 p = kBlobBase + scale * (rest.positions[v] - kBlobBase);
    glm::vec3 n = glm::normalize(rest.normals[v] / scale);
    target.positions.push_back(p - rest.positions[v]);
    target.normals.push_back(n - rest.normals[v]);
  }
  return target;
}

Mesh makeBlob(uint32_t material) {
  Geometry g;
  g.material = material;
  addSphere(g, kBlobBase + glm::vec3(0.0f, kBlobRadius, 0.0f), kBlobRadius, 40, 20);
  g.morphTargets.push_back(scaledTarget(g, {0.75f, 1.6f, 0.75f}));   // stretched up
  g.morphTargets.push_back(scaledTarget(g, {1.35f, 0.55f, 1.35f}));  // squashed flat
  Mesh mesh;
  mesh.name = "blob";
  mesh.geometries.push_back(std::move(g));
  mesh.morphWeights = {0.0f, 0.0f};
  return mesh;
}

// Stretch for the first half of the loop, squash for the second.
MorphWeightTrack animateBlob(uint32_t mesh) {
  MorphWeightTrack track;
  track.mesh = mesh;
  track.targets = 2;
  for (int k = 0; k < kKeys; ++k) {
    float t = kLoopSeconds * float(k) / float(kKeys - 1);
    float s = std::sin(2.0f * kPi * t / kLoopSeconds);
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

}  // namespace

Scene makeSkinnedScene() {
  Scene scene;
  scene.name = "skinned";
  addRoomCorner(scene);

  Material orange = lambertMaterial("tube", {0.8f, 0.32f, 0.08f});
  orange.roughness = 0.5f;
  orange.doubleSided = true;  // its top is open
  Mesh tube;
  tube.name = "tube";
  tube.geometries.push_back(makeTube(addMaterial(scene, orange)));
  tube.skin = int(scene.skins.size());
  Skin skin = makeTubeSkin(scene);
  animateTube(scene, skin, scene.animation);
  scene.skins.push_back(std::move(skin));
  addMeshInstance(scene, std::move(tube));  // skinned: the joints place it, identity instance

  Material gold = lambertMaterial("blob", {1.0f, 0.78f, 0.34f});
  gold.metallic = 1.0f;
  gold.roughness = 0.3f;
  uint32_t blob = addMeshInstance(scene, makeBlob(addMaterial(scene, gold)));
  scene.animation.morphWeights.push_back(animateBlob(blob));

  scene.sun = sunFromAngles(50.0f, 160.0f, 100.0f, {1.0f, 0.96f, 0.9f});
  scene.sky.model = SkyModel::Daylight;
  scene.sky.turbidity = 3.0f;
  Camera camera;
  camera.position = {0.6f, 2.2f, 5.2f};
  camera.target = {0.0f, 0.9f, 0.0f};
  camera.verticalFovDegrees = 45.0f;
  scene.camera = camera;
  return scene;
}

}  // namespace bounce::procedural
