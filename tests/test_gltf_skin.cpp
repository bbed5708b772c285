// glTF skins and morph targets (src/scene/gltf_skin.cpp, gltf_loader.cpp, gltf_animation.cpp)
// and their CPU posing (src/scene/deformation.cpp): loaded files are posed at a time t and their
// vertices compared with positions computed by hand from the glTF 2.0 definitions (§3.7.2.2,
// §3.7.3); broken files must give a bounce::Error naming the file and the field.
#include <cmath>
#include <filesystem>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "gltf_writer.h"
#include "harness.h"
#include "scene/deformation.h"
#include "scene/load.h"

namespace bounce {
namespace {

using nlohmann::json;
using test::GltfWriter;
using test::kFloat;
using test::kUnsignedShort;
namespace fs = std::filesystem;

constexpr int kUnsignedByte = 5121;
constexpr float kTolerance = 1e-5f;

class GltfSkinTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir = test::tempDir(std::string("gltf-skin-") +
                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
  }
  void TearDown() override { fs::remove_all(dir); }

  // Loading `path` must throw bounce::Error naming the file and containing every keyword.
  static void expectError(const std::string& path, std::initializer_list<std::string> keywords) {
    try {
      loadGltf(path);
      ADD_FAILURE() << path << " loaded, expected an error";
    } catch (const Error& e) {
      std::string message = e.what();
      EXPECT_NE(message.find(fs::path(path).filename().string()), std::string::npos) << message;
      for (const std::string& keyword : keywords)
        EXPECT_NE(message.find(keyword), std::string::npos)
            << "message lacks '" << keyword << "': " << message;
    }
  }

  std::string dir;
};

template <typename T>
int addData(GltfWriter& w, const std::vector<T>& data, int componentType, const char* type) {
  size_t components = std::string(type) == "SCALAR" ? 1
                      : std::string(type) == "MAT4" ? 16
                                                    : size_t(std::string(type)[3] - '0');
  size_t bytes = data.size() * sizeof(T);
  size_t componentBytes = componentType == kFloat ? 4 : componentType == kUnsignedShort ? 2 : 1;
  return w.addAccessor(w.addView(data.data(), bytes), componentType,
                       bytes / (components * componentBytes), type);
}

glm::vec3 posedPosition(const Scene& scene, float t, uint32_t mesh, size_t vertex,
                        bool loop = true) {
  DeformationPose pose;
  SceneAnimation animation = scene.animation;
  animation.loop = loop;
  evaluatePose(scene, animation, t, pose);
  return posedScene(scene, pose).meshes[mesh].geometries[0].positions[vertex];
}

#define EXPECT_VEC3_NEAR(a, b)                                                                  \
  EXPECT_LT(glm::length(glm::vec3(a) - glm::vec3(b)), kTolerance)                               \
      << "got (" << (a).x << ", " << (a).y << ", " << (a).z << "), expected (" << (b).x << ", " \
      << (b).y << ", " << (b).z << ")"

// ---- skins ----

// A strip along +X from x = 0 to 2 (two rows, y = 0 and 0.2) skinned to two joints: joint 0 at
// the origin, joint 1 at x = 1 (its child). Column x = 0 follows joint 0, x = 2 joint 1, x = 1
// half each. Both joints hang under an armature node translated by (0, 0, -3). The skinned
// node's own transform (a translation by (5, 5, 5)) must be ignored.
struct StripFile {
  int mesh = -1, armature = -1, joint0 = -1, joint1 = -1, skinned = -1;
};

StripFile writeStrip(GltfWriter& w) {
  StripFile f;
  int pos =
      w.addPositions({{0, 0, 0}, {0, 0.2f, 0}, {1, 0, 0}, {1, 0.2f, 0}, {2, 0, 0}, {2, 0.2f, 0}});
  int idx = w.addIndices16({0, 2, 3, 0, 3, 1, 2, 4, 5, 2, 5, 3});
  std::vector<uint16_t> joints = {0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0,
                                  0, 1, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0};
  std::vector<float> weights = {1,    0,    0, 0, 1, 0, 0, 0, 0.5f, 0.5f, 0, 0,
                                0.5f, 0.5f, 0, 0, 1, 0, 0, 0, 1,    0,    0, 0};
  int j = addData(w, joints, kUnsignedShort, "VEC4");
  int wt = addData(w, weights, kFloat, "VEC4");
  f.mesh = w.addMesh(
      {{"attributes", {{"POSITION", pos}, {"JOINTS_0", j}, {"WEIGHTS_0", wt}}}, {"indices", idx}});
  f.joint1 = w.addNode({{"name", "tip"}, {"translation", {1, 0, 0}}}, false);
  f.joint0 = w.addNode({{"name", "base"}, {"children", {f.joint1}}}, false);
  f.skinned = w.addNode(
      {{"name", "strip"}, {"mesh", f.mesh}, {"skin", 0}, {"translation", {5, 5, 5}}}, false);
  f.armature = w.addNode(
      {{"name", "armature"}, {"translation", {0, 0, -3}}, {"children", {f.joint0, f.skinned}}});
  json skin = {{"joints", {f.joint0, f.joint1}}};
  // The inverse bind matrices of joints bound in the armature's space (joint 0 at the origin,
  // joint 1 at (1, 0, 0)), so the armature's translation moves the skinned strip.
  std::vector<glm::mat4> inverse = {glm::mat4(1.0f),
                                    glm::translate(glm::mat4(1.0f), glm::vec3(-1, 0, 0))};
  skin["inverseBindMatrices"] = w.addAccessor(w.addView(inverse.data(), 128), kFloat, 2, "MAT4");
  w.doc["skins"] = json::array({skin});
  return f;
}

// Joint 1 turns about +Z from 0 to 90 degrees over 1 s (LINEAR); at t = 0.5 it stands at 45.
void animateTip(GltfWriter& w, int joint) {
  const float times[] = {0.0f, 1.0f};
  const float s = std::sqrt(0.5f);
  const float rotations[] = {0, 0, 0, 1, 0, 0, s, s};  // x, y, z, w
  int in = w.addAccessor(w.addView(times, sizeof(times)), kFloat, 2, "SCALAR");
  int out = w.addAccessor(w.addView(rotations, sizeof(rotations)), kFloat, 2, "VEC4");
  w.doc["animations"] = json::array(
      {{{"samplers", {{{"input", in}, {"output", out}}}},
        {"channels", {{{"sampler", 0}, {"target", {{"node", joint}, {"path", "rotation"}}}}}}}});
}

TEST_F(GltfSkinTest, TwoJointStripFollowsItsAnimatedJoint) {
  GltfWriter w;
  StripFile f = writeStrip(w);
  animateTip(w, f.joint1);
  LoadWarnings warnings;
  Scene scene = loadGltf(w.writeGltf(dir, "strip"), warnings);
  EXPECT_TRUE(warnings.empty()) << (warnings.empty() ? "" : warnings.summary()[0]);

  // The skeleton: the armature, then base, then tip (parents first), and one skin over them.
  ASSERT_EQ(scene.skeleton.size(), 3u);
  EXPECT_EQ(scene.skeleton[0].name, "armature");
  EXPECT_EQ(scene.skeleton[0].parent, -1);
  EXPECT_EQ(scene.skeleton[1].name, "base");
  EXPECT_EQ(scene.skeleton[1].parent, 0);
  EXPECT_EQ(scene.skeleton[2].name, "tip");
  EXPECT_EQ(scene.skeleton[2].parent, 1);
  ASSERT_EQ(scene.skins.size(), 1u);
  EXPECT_EQ(scene.skins[0].joints, (std::vector<uint32_t>{1, 2}));
  ASSERT_EQ(scene.meshes.size(), 1u);
  EXPECT_EQ(scene.meshes[0].skin, 0);
  ASSERT_EQ(scene.instances.size(), 1u);
  EXPECT_EQ(scene.instances[0].transform, glm::mat4(1.0f)) << "the skinned node's own transform";
  ASSERT_EQ(scene.animation.joints.size(), 1u);
  EXPECT_EQ(scene.animation.joints[0].node, 2u);
  EXPECT_TRUE(scene.animation.transforms.empty());

  // At rest (t = 0) the bind pose under the armature: every vertex moved by (0, 0, -3).
  const glm::vec3 rest[] = {{0, 0, 0},    {0, 0.2f, 0}, {1, 0, 0},
                            {1, 0.2f, 0}, {2, 0, 0},    {2, 0.2f, 0}};
  for (size_t v = 0; v < 6; ++v)
    EXPECT_VEC3_NEAR(posedPosition(scene, 0.0f, 0, v), rest[v] + glm::vec3(0, 0, -3));

  // At t = 0.5 the tip has turned 45 degrees about +Z around (1, 0, -3). A vertex (x, y) bound
  // to it moves to (1 + c (x - 1) - s y, s (x - 1) + c y); a vertex on the joint (x = 1) is
  // half that, half its rest position.
  const float c = std::cos(glm::radians(45.0f)), s = std::sin(glm::radians(45.0f));
  auto turned = [&](glm::vec3 p) {
    return glm::vec3(1 + c * (p.x - 1) - s * p.y, s * (p.x - 1) + c * p.y, p.z);
  };
  const glm::vec3 offset(0, 0, -3);
  EXPECT_VEC3_NEAR(posedPosition(scene, 0.5f, 0, 0), rest[0] + offset);
  EXPECT_VEC3_NEAR(posedPosition(scene, 0.5f, 0, 1), rest[1] + offset);
  for (size_t v : {2, 3})
    EXPECT_VEC3_NEAR(posedPosition(scene, 0.5f, 0, v),
                     0.5f * rest[v] + 0.5f * turned(rest[v]) + offset);
  for (size_t v : {4, 5})
    EXPECT_VEC3_NEAR(posedPosition(scene, 0.5f, 0, v), turned(rest[v]) + offset);
  // The last key holds: the tip points up.
  EXPECT_VEC3_NEAR(posedPosition(scene, 1.0f, 0, 4, false), glm::vec3(1, 1, -3));
  EXPECT_VEC3_NEAR(posedPosition(scene, 1.0f, 0, 5, false), glm::vec3(0.8f, 1, -3));
}

// A node that places a mesh of its own and is a joint gets a transform track for its instance
// and a joint track for the skeleton, from the same channel.
TEST_F(GltfSkinTest, AMeshNodeThatIsAJointGetsBothTracks) {
  GltfWriter w;
  StripFile f = writeStrip(w);
  int pos = w.addPositions({{0, 0, 0}, {0.1f, 0, 0}, {0, 0.1f, 0}});
  w.doc["nodes"][size_t(f.joint1)]["mesh"] = w.addMesh({{"attributes", {{"POSITION", pos}}}});
  animateTip(w, f.joint1);
  Scene scene = loadGltf(w.writeGltf(dir, "both"));
  ASSERT_EQ(scene.instances.size(), 2u);
  ASSERT_EQ(scene.animation.joints.size(), 1u);
  ASSERT_EQ(scene.animation.transforms.size(), 1u);
  EXPECT_EQ(scene.instances[scene.animation.transforms[0].instance].name, "tip");
  std::vector<glm::mat4> transforms(scene.instances.size());
  SceneAnimation held = scene.animation;
  held.loop = false;
  evaluateTransforms(held, 1.0f, {}, transforms);
  const glm::mat4& tip = transforms[scene.animation.transforms[0].instance];
  EXPECT_VEC3_NEAR(glm::vec3(tip * glm::vec4(1, 0, 0, 1)), glm::vec3(1, 1, -3));
}

// ---- meshes under animated parents ----

// The instance transforms at t as AnimationPlayer::apply makes them: the pose first, then the
// transform tracks under its skeleton.
std::vector<glm::mat4> playedTransforms(const Scene& scene, float t, bool loop = true) {
  SceneAnimation animation = scene.animation;
  animation.loop = loop;
  DeformationPose pose;
  evaluatePose(scene, animation, t, pose);
  std::vector<glm::mat4> transforms;
  for (const Instance& instance : scene.instances) transforms.push_back(instance.transform);
  evaluateTransforms(animation, t, pose.skeletonWorld, transforms);
  return transforms;
}

glm::vec3 place(const glm::mat4& m, glm::vec3 p) {
  return glm::vec3(m * glm::vec4(p, 1.0f));
}

// (x, y, z) turned by `degrees` about +Y: (x c + z s, y, -x s + z c).
glm::vec3 turnedAboutY(glm::vec3 p, float degrees) {
  float c = std::cos(glm::radians(degrees)), s = std::sin(glm::radians(degrees));
  return {p.x * c + p.z * s, p.y, -p.x * s + p.z * c};
}

// Channels over 1 s (LINEAR) on `node`: `path` from key value `from` to `to` (3 or 4 floats).
void addChannel(GltfWriter& w, int node, const char* path, std::vector<float> from,
                std::vector<float> to) {
  const float times[] = {0.0f, 1.0f};
  std::vector<float> values = from;
  values.insert(values.end(), to.begin(), to.end());
  const char* type = from.size() == 4 ? "VEC4" : "VEC3";
  int in = w.addAccessor(w.addView(times, sizeof(times)), kFloat, 2, "SCALAR");
  int out = w.addAccessor(w.addView(values.data(), values.size() * 4), kFloat, 2, type);
  if (!w.doc.contains("animations"))
    w.doc["animations"] = json::array({{{"samplers", json::array()}, {"channels", json::array()}}});
  json& animation = w.doc["animations"][0];
  animation["channels"].push_back(
      {{"sampler", animation["samplers"].size()}, {"target", {{"node", node}, {"path", path}}}});
  animation["samplers"].push_back({{"input", in}, {"output", out}});
}

// A static root "stage" at (0, 1, 0), under it an empty "turntable", under that a mesh node
// "box" at (2, 0, 0) (given by TRS or by a matrix). The mesh is a triangle at the node's origin.
struct TurntableFile {
  int stage = -1, turntable = -1, box = -1;
};

TurntableFile writeTurntable(GltfWriter& w, bool matrix = false) {
  TurntableFile f;
  int pos = w.addPositions({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
  json box = {{"name", "box"}, {"mesh", w.addMesh({{"attributes", {{"POSITION", pos}}}})}};
  if (matrix)
    box["matrix"] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 2, 0, 0, 1};  // column-major
  else
    box["translation"] = {2, 0, 0};
  f.box = w.addNode(box, false);
  f.turntable = w.addNode({{"name", "turntable"}, {"children", {f.box}}}, false);
  f.stage = w.addNode({{"name", "stage"}, {"translation", {0, 1, 0}}, {"children", {f.turntable}}});
  return f;
}

// The turntable turns 0 to 90 degrees about +Y over 1 s; the box, not animated itself, rides on
// it: its origin is (0, 1, 0) + R_y(theta) (2, 0, 0), its vertex (1, 0, 0) at R_y (3, 0, 0), as
// the player and sceneFrozenAt evaluate it; with the box given by a matrix as well.
TEST_F(GltfSkinTest, MeshUnderAnAnimatedEmptyRidesOnIt) {
  for (bool matrix : {false, true}) {
    SCOPED_TRACE(matrix ? "box given by a matrix" : "box given by TRS");
    GltfWriter w;
    TurntableFile f = writeTurntable(w, matrix);
    const float s = std::sqrt(0.5f);
    addChannel(w, f.turntable, "rotation", {0, 0, 0, 1}, {0, s, 0, s});
    LoadWarnings warnings;
    Scene scene = loadGltf(w.writeGltf(dir, "turntable"), warnings);
    EXPECT_TRUE(warnings.empty()) << (warnings.empty() ? "" : warnings.summary()[0]);
    ASSERT_EQ(scene.instances.size(), 1u);
    // The rest placement is unchanged; the turntable and its ancestor join the skeleton.
    EXPECT_VEC3_NEAR(place(scene.instances[0].transform, glm::vec3(0)), glm::vec3(2, 1, 0));
    ASSERT_GE(scene.skeleton.size(), 2u);
    EXPECT_EQ(scene.skeleton[0].name, "stage");
    EXPECT_EQ(scene.skeleton[1].name, "turntable");
    EXPECT_EQ(scene.skeleton[1].parent, 0);
    ASSERT_EQ(scene.animation.joints.size(), 1u);
    EXPECT_EQ(scene.animation.joints[0].node, 1u);
    ASSERT_EQ(scene.animation.transforms.size(), 1u);
    EXPECT_EQ(scene.animation.transforms[0].instance, 0u);
    EXPECT_GE(scene.animation.transforms[0].parentNode, 1);
    for (float t : {0.0f, 0.5f, 1.0f}) {
      SCOPED_TRACE("t = " + std::to_string(t));
      const float degrees = 90.0f * t;
      const glm::mat4 box = playedTransforms(scene, t, false)[0];
      EXPECT_VEC3_NEAR(place(box, glm::vec3(0)),
                       glm::vec3(0, 1, 0) + turnedAboutY(glm::vec3(2, 0, 0), degrees));
      EXPECT_VEC3_NEAR(place(box, glm::vec3(1, 0, 0)),
                       glm::vec3(0, 1, 0) + turnedAboutY(glm::vec3(3, 0, 0), degrees));
      if (t < 1.0f) {  // sceneFrozenAt loops: t = 1 is t = 0 there
        const Scene frozen = sceneFrozenAt(scene, t);
        EXPECT_EQ(frozen.instances[0].transform, playedTransforms(scene, t)[0]);
        EXPECT_TRUE(frozen.animation.transforms.empty());
      }
    }
  }
}

// A mesh whose own node is animated and whose parent is animated composes both: the box slides
// from x = 2 to x = 4 while the turntable turns, so at t the origin is R_y(90 t) (2 + 2t, 0, 0).
TEST_F(GltfSkinTest, AnimatedMeshUnderAnAnimatedParentComposesBoth) {
  GltfWriter w;
  TurntableFile f = writeTurntable(w);
  const float s = std::sqrt(0.5f);
  addChannel(w, f.turntable, "rotation", {0, 0, 0, 1}, {0, s, 0, s});
  addChannel(w, f.box, "translation", {2, 0, 0}, {4, 0, 0});
  Scene scene = loadGltf(w.writeGltf(dir, "sliding"));
  ASSERT_EQ(scene.animation.transforms.size(), 1u);
  for (float t : {0.0f, 0.25f, 0.5f, 1.0f}) {
    SCOPED_TRACE("t = " + std::to_string(t));
    const glm::mat4 box = playedTransforms(scene, t, false)[0];
    EXPECT_VEC3_NEAR(place(box, glm::vec3(0)),
                     glm::vec3(0, 1, 0) + turnedAboutY(glm::vec3(2 + 2 * t, 0, 0), 90.0f * t));
  }
  EXPECT_EQ(sceneFrozenAt(scene, 0.5f).instances[0].transform, playedTransforms(scene, 0.5f)[0]);
}

// A prop in a hand: a mesh node "sword" under the strip's animated tip joint, 1 along the
// tip's +X, follows the tip as the strip's vertex (2, 0, 0), bound to the tip alone, does:
// origin (1 + cos theta, sin theta, -3) with theta = 90 t about +Z. The skin's nodes are shared
// (no new skeleton node) and the skinned mesh's instance stays the identity.
TEST_F(GltfSkinTest, MeshUnderASkinJointFollowsIt) {
  GltfWriter w;
  StripFile f = writeStrip(w);
  int pos = w.addPositions({{0, 0, 0}, {0.1f, 0, 0}, {0, 0.1f, 0}});
  int sword = w.addNode({{"name", "sword"},
                         {"mesh", w.addMesh({{"attributes", {{"POSITION", pos}}}})},
                         {"translation", {1, 0, 0}}},
                        false);
  w.doc["nodes"][size_t(f.joint1)]["children"] = {sword};
  animateTip(w, f.joint1);
  LoadWarnings warnings;
  Scene scene = loadGltf(w.writeGltf(dir, "sword"), warnings);
  EXPECT_TRUE(warnings.empty()) << (warnings.empty() ? "" : warnings.summary()[0]);
  EXPECT_EQ(scene.skeleton.size(), 3u);
  ASSERT_EQ(scene.instances.size(), 2u);
  ASSERT_EQ(scene.animation.transforms.size(), 1u);
  const TransformTrack& track = scene.animation.transforms[0];
  EXPECT_EQ(scene.instances[track.instance].name, "sword");
  EXPECT_EQ(track.parentNode, 2);  // the tip
  const uint32_t strip = 1 - track.instance;
  for (float t : {0.0f, 0.5f, 1.0f}) {
    SCOPED_TRACE("t = " + std::to_string(t));
    const float theta = glm::radians(90.0f * t);
    const std::vector<glm::mat4> transforms = playedTransforms(scene, t, false);
    const glm::vec3 hilt = place(transforms[track.instance], glm::vec3(0));
    EXPECT_VEC3_NEAR(hilt, glm::vec3(1 + std::cos(theta), std::sin(theta), -3));
    EXPECT_VEC3_NEAR(hilt, posedPosition(scene, t, scene.instances[strip].mesh, 4, false));
    EXPECT_EQ(transforms[strip], glm::mat4(1.0f));
  }
}

// glTF animations hide objects with scale 0, a parent's included: a box under a turntable that
// starts at scale 0 and grows to 1 is kept (singular, so hidden, at rest) and appears at
// (2, 1, 0) when its parent scales up, instead of being skipped as a still scale-0 node is.
TEST_F(GltfSkinTest, MeshUnderAParentAnimatedFromScaleZeroIsKept) {
  GltfWriter w;
  TurntableFile f = writeTurntable(w);
  w.doc["nodes"][size_t(f.turntable)]["scale"] = {0, 0, 0};
  addChannel(w, f.turntable, "scale", {0, 0, 0}, {1, 1, 1});
  LoadWarnings warnings;
  Scene scene = loadGltf(w.writeGltf(dir, "growing"), warnings);
  ASSERT_EQ(scene.instances.size(), 1u);
  EXPECT_EQ(warnings.count("starts with a singular transform (scale 0): hidden until its "
                           "animation scales it up"),
            1u);
  EXPECT_EQ(glm::determinant(glm::mat3(playedTransforms(scene, 0.0f, false)[0])), 0.0f);
  EXPECT_VEC3_NEAR(place(playedTransforms(scene, 1.0f, false)[0], glm::vec3(0)),
                   glm::vec3(2, 1, 0));
}

// Without animations the hierarchy is baked as before: no tracks, no skeleton. A channel on a
// node with no mesh in or below it (an animated empty beside the box, not above it) still moves
// nothing, with the warning, and the box gets no track.
TEST_F(GltfSkinTest, StaticHierarchiesAndChannelsWithoutMeshesAreAsBefore) {
  {
    GltfWriter w;
    writeTurntable(w);
    LoadWarnings warnings;
    Scene scene = loadGltf(w.writeGltf(dir, "still"), warnings);
    EXPECT_TRUE(warnings.empty());
    EXPECT_TRUE(scene.animation.empty());
    EXPECT_TRUE(scene.skeleton.empty());
    ASSERT_EQ(scene.instances.size(), 1u);
    EXPECT_VEC3_NEAR(place(scene.instances[0].transform, glm::vec3(0)), glm::vec3(2, 1, 0));
  }
  GltfWriter w;
  writeTurntable(w);
  int empty = w.addNode({{"name", "spinner"}});
  const float s = std::sqrt(0.5f);
  addChannel(w, empty, "rotation", {0, 0, 0, 1}, {0, s, 0, s});
  LoadWarnings warnings;
  Scene scene = loadGltf(w.writeGltf(dir, "beside"), warnings);
  EXPECT_TRUE(scene.animation.transforms.empty());
  EXPECT_TRUE(scene.animation.joints.empty());
  EXPECT_TRUE(scene.skeleton.empty());
  ASSERT_EQ(warnings.summary().size(), 1u);
  EXPECT_NE(warnings.summary()[0].find("animations of nodes that place no mesh, have none below "
                                       "them and are no skin joint are ignored"),
            std::string::npos)
      << warnings.summary()[0];
}

// One joint, no inverseBindMatrices (identities): every vertex moves rigidly with the joint's
// transform. The joint is translated by (1, 2, 3) and turned 90 degrees about +Y, which takes
// (x, y, z) to (z, y, -x); weights (0.5, 0, 0, 0) are renormalised to 1.
TEST_F(GltfSkinTest, SingleJointSkinIsARigidTransformOfTheBindPose) {
  GltfWriter w;
  const std::vector<glm::vec3> rest = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0.5f}, {0, 1, -0.5f}};
  int pos = w.addPositions(rest);
  int idx = w.addIndices16({0, 1, 2, 0, 2, 3});
  std::vector<uint8_t> joints(16, 0);
  std::vector<float> weights = {0.5f, 0, 0, 0, 0.5f, 0, 0, 0, 0.5f, 0, 0, 0, 0.5f, 0, 0, 0};
  int j = addData(w, joints, kUnsignedByte, "VEC4");
  int wt = addData(w, weights, kFloat, "VEC4");
  int mesh = w.addMesh(
      {{"attributes", {{"POSITION", pos}, {"JOINTS_0", j}, {"WEIGHTS_0", wt}}}, {"indices", idx}});
  const float s = std::sqrt(0.5f);
  int joint = w.addNode({{"translation", {1, 2, 3}}, {"rotation", {0, s, 0, s}}});
  w.addNode({{"mesh", mesh}, {"skin", 0}});
  w.doc["skins"] = json::array({{{"joints", {joint}}}});
  Scene scene = loadGltf(w.writeGltf(dir, "rigid"));
  ASSERT_EQ(scene.meshes.size(), 1u);
  for (const glm::vec4& weight : scene.meshes[0].geometries[0].weights)
    EXPECT_EQ(weight, glm::vec4(1, 0, 0, 0));
  DeformationPose pose = restPose(scene);
  Scene posed = posedScene(scene, pose);
  EXPECT_FALSE(posed.deforms());
  for (size_t v = 0; v < rest.size(); ++v) {
    glm::vec3 p = rest[v];
    EXPECT_VEC3_NEAR(posed.meshes[0].geometries[0].positions[v],
                     glm::vec3(p.z + 1, p.y + 2, -p.x + 3));
  }
  // Normals turn with it.
  for (size_t v = 0; v < rest.size(); ++v) {
    glm::vec3 n = scene.meshes[0].geometries[0].normals[v];
    EXPECT_VEC3_NEAR(posed.meshes[0].geometries[0].normals[v], glm::vec3(n.z, n.y, -n.x));
  }
}

// WEIGHTS_0 as normalized unsigned bytes and shorts: c / 255 (c / 65535), then renormalised.
TEST_F(GltfSkinTest, NormalizedUnsignedWeights) {
  for (int type : {kUnsignedByte, kUnsignedShort}) {
    SCOPED_TRACE(type);
    GltfWriter w;
    int pos = w.addPositions({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
    std::vector<uint8_t> joints = {0, 1, 0, 0, 0, 1, 0, 0, 1, 0, 0, 0};
    const float max = type == kUnsignedByte ? 255.0f : 65535.0f;
    // (0.2, 0.8) exact; (100, 100) of 255 renormalised to halves; (max, 0): 1.
    std::vector<float> wanted = {0.2f * max, 0.8f * max, 0, 0, 100, 100, 0, 0, max, 0, 0, 0};
    int wt;
    if (type == kUnsignedByte) {
      std::vector<uint8_t> raw(wanted.begin(), wanted.end());
      wt = addData(w, raw, type, "VEC4");
    } else {
      std::vector<uint16_t> raw(wanted.begin(), wanted.end());
      wt = addData(w, raw, type, "VEC4");
    }
    w.doc["accessors"][size_t(wt)]["normalized"] = true;
    int j = addData(w, joints, kUnsignedByte, "VEC4");
    int mesh = w.addMesh({{"attributes", {{"POSITION", pos}, {"JOINTS_0", j}, {"WEIGHTS_0", wt}}}});
    int a = w.addNode({{"name", "a"}});
    int b = w.addNode({{"name", "b"}});
    w.addNode({{"mesh", mesh}, {"skin", 0}});
    w.doc["skins"] = json::array({{{"joints", {a, b}}}});
    Scene scene = loadGltf(w.writeGltf(dir, "u" + std::to_string(type)));
    const Geometry& g = scene.meshes[0].geometries[0];
    ASSERT_EQ(g.weights.size(), 3u);
    EXPECT_NEAR(g.weights[0].x, 0.2f, 1e-3f);
    EXPECT_NEAR(g.weights[0].y, 0.8f, 1e-3f);
    EXPECT_NEAR(g.weights[1].x, 0.5f, 1e-6f);
    EXPECT_NEAR(g.weights[1].y, 0.5f, 1e-6f);
    EXPECT_EQ(g.weights[2], glm::vec4(1, 0, 0, 0));
    EXPECT_EQ(g.joints[0], glm::uvec4(0, 1, 0, 0));
    EXPECT_EQ(g.joints[2], glm::uvec4(1, 0, 0, 0));
    for (const glm::vec4& weight : g.weights)
      EXPECT_NEAR(weight.x + weight.y + weight.z + weight.w, 1.0f, 1e-6f);
  }
}

// More than four influences: the second set is ignored with one warning line, and the first
// four renormalised.
TEST_F(GltfSkinTest, SecondInfluenceSetIsIgnoredWithAWarning) {
  GltfWriter w;
  int pos = w.addPositions({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
  std::vector<uint8_t> joints(12, 0);
  std::vector<float> weights = {0.3f, 0, 0, 0, 0.3f, 0, 0, 0, 0.3f, 0, 0, 0};
  std::vector<float> more = {0.7f, 0, 0, 0, 0.7f, 0, 0, 0, 0.7f, 0, 0, 0};
  int j = addData(w, joints, kUnsignedByte, "VEC4");
  int mesh = w.addMesh({{"attributes",
                         {{"POSITION", pos},
                          {"JOINTS_0", j},
                          {"WEIGHTS_0", addData(w, weights, kFloat, "VEC4")},
                          {"JOINTS_1", j},
                          {"WEIGHTS_1", addData(w, more, kFloat, "VEC4")}}}});
  int joint = w.addNode({{"name", "j"}});
  w.addNode({{"mesh", mesh}, {"skin", 0}});
  w.doc["skins"] = json::array({{{"joints", {joint}}}});
  LoadWarnings warnings;
  Scene scene = loadGltf(w.writeGltf(dir, "eight"), warnings);
  ASSERT_EQ(warnings.summary().size(), 1u);
  EXPECT_NE(warnings.summary()[0].find("JOINTS_1 and WEIGHTS_1 are ignored"), std::string::npos);
  EXPECT_EQ(scene.meshes[0].geometries[0].weights[0], glm::vec4(1, 0, 0, 0));
}

// A primitive of a skinned mesh without JOINTS_0/WEIGHTS_0 stays where an unskinned node would
// draw it (its node's rest world transform, baked in), with a warning; its skinned sibling
// primitive follows the joints.
TEST_F(GltfSkinTest, SkinnedMeshPrimitiveWithoutJointsStaysRigid) {
  GltfWriter w;
  int pos = w.addPositions({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
  std::vector<uint8_t> joints(12, 0);
  std::vector<float> weights = {1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0};
  json skinnedPrimitive = {{"attributes",
                            {{"POSITION", pos},
                             {"JOINTS_0", addData(w, joints, kUnsignedByte, "VEC4")},
                             {"WEIGHTS_0", addData(w, weights, kFloat, "VEC4")}}}};
  json rigidPrimitive = {{"attributes", {{"POSITION", pos}}}};
  w.doc["meshes"].push_back({{"primitives", {skinnedPrimitive, rigidPrimitive}}});
  int joint = w.addNode({{"translation", {0, 4, 0}}});
  w.addNode({{"mesh", 0}, {"skin", 0}, {"translation", {0, 0, 7}}});
  w.doc["skins"] = json::array({{{"joints", {joint}}}});
  LoadWarnings warnings;
  Scene scene = loadGltf(w.writeGltf(dir, "partly"), warnings);
  ASSERT_EQ(warnings.summary().size(), 1u);
  EXPECT_NE(warnings.summary()[0].find("without JOINTS_0 and WEIGHTS_0 stay rigid"),
            std::string::npos);
  Scene posed = posedScene(scene, restPose(scene));
  EXPECT_VEC3_NEAR(posed.meshes[0].geometries[0].positions[1], glm::vec3(1, 4, 0));
  EXPECT_VEC3_NEAR(posed.meshes[0].geometries[1].positions[1], glm::vec3(1, 0, 7));
}

// ---- morph targets ----

// A quad with two targets: target 0 lifts vertex 2 by +Z and tilts its normal, target 1 moves
// vertex 3 by +X. The weights channel goes from (0, 0) at t = 0 to (1, 0.5) at t = 2 (key-major
// output), so t = 1 is halfway.
TEST_F(GltfSkinTest, AnimatedMorphWeightsGiveRestHalfwayAndFullDisplacement) {
  GltfWriter w;
  const std::vector<glm::vec3> rest = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  int pos = w.addPositions(rest);
  int idx = w.addIndices16({0, 1, 2, 0, 2, 3});
  int lift = w.addPositions({{0, 0, 0}, {0, 0, 0}, {0, 0, 1}, {0, 0, 0}});
  int tilt = w.addPositions({{0, 0, 0}, {0, 0, 0}, {1, 0, -1}, {0, 0, 0}});
  int slide = w.addPositions({{0, 0, 0}, {0, 0, 0}, {0, 0, 0}, {1, 0, 0}});
  int mesh =
      w.addMesh({{"attributes", {{"POSITION", pos}}},
                 {"indices", idx},
                 {"targets", json::array({json::object({{"POSITION", lift}, {"NORMAL", tilt}}),
                                          json::object({{"POSITION", slide}})})}});
  w.doc["meshes"][size_t(mesh)]["weights"] = {0.25, 0.0};
  int node = w.addNode({{"mesh", mesh}, {"translation", {0, 0, -2}}});
  const float times[] = {0.0f, 2.0f};
  const float values[] = {0.0f, 0.0f, 1.0f, 0.5f};
  int in = w.addAccessor(w.addView(times, sizeof(times)), kFloat, 2, "SCALAR");
  int out = w.addAccessor(w.addView(values, sizeof(values)), kFloat, 4, "SCALAR");
  w.doc["animations"] = json::array(
      {{{"samplers", {{{"input", in}, {"output", out}}}},
        {"channels", {{{"sampler", 0}, {"target", {{"node", node}, {"path", "weights"}}}}}}}});
  Scene scene = loadGltf(w.writeGltf(dir, "morph"));
  ASSERT_EQ(scene.meshes.size(), 1u);
  EXPECT_EQ(scene.meshes[0].morphWeights, (std::vector<float>{0.25f, 0.0f}));
  EXPECT_EQ(scene.meshes[0].skin, -1);
  ASSERT_EQ(scene.instances.size(), 1u);
  EXPECT_VEC3_NEAR(glm::vec3(scene.instances[0].transform[3]), glm::vec3(0, 0, -2))
      << "a morphed, unskinned node keeps its transform";
  ASSERT_EQ(scene.animation.morphWeights.size(), 1u);
  EXPECT_EQ(scene.animation.morphWeights[0].targets, 2u);

  // The rest pose uses the mesh's weights (0.25, 0).
  Scene posedRest = posedScene(scene, restPose(scene));
  EXPECT_VEC3_NEAR(posedRest.meshes[0].geometries[0].positions[2], glm::vec3(1, 1, 0.25f));
  for (float t : {0.0f, 1.0f, 2.0f}) {
    SCOPED_TRACE(t);
    float w0 = t / 2.0f, w1 = 0.25f * t;
    EXPECT_VEC3_NEAR(posedPosition(scene, t, 0, 0, false), rest[0]);
    EXPECT_VEC3_NEAR(posedPosition(scene, t, 0, 2, false), rest[2] + glm::vec3(0, 0, w0));
    EXPECT_VEC3_NEAR(posedPosition(scene, t, 0, 3, false), rest[3] + glm::vec3(w1, 0, 0));
  }
  // The normal of vertex 2 at full weight: (0, 0, 1) + (1, 0, -1), renormalised.
  DeformationPose pose;
  SceneAnimation held = scene.animation;
  held.loop = false;
  evaluatePose(scene, held, 2.0f, pose);
  EXPECT_VEC3_NEAR(posedScene(scene, pose).meshes[0].geometries[0].normals[2], glm::vec3(1, 0, 0));
}

// Every node placing a morphed mesh gets its own copy; rest weights come from node.weights,
// else mesh.weights.
TEST_F(GltfSkinTest, EachMorphedNodeGetsItsOwnMeshAndRestWeights) {
  GltfWriter w;
  int pos = w.addPositions({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
  int delta = w.addPositions({{0, 0, 1}, {0, 0, 1}, {0, 0, 1}});
  int mesh = w.addMesh({{"attributes", {{"POSITION", pos}}}, {"targets", {{{"POSITION", delta}}}}});
  w.doc["meshes"][size_t(mesh)]["weights"] = {0.1};
  w.addNode({{"mesh", mesh}, {"weights", {0.7}}});
  w.addNode({{"mesh", mesh}});
  int plain = w.addPositions({{0, 0, 0}, {2, 0, 0}, {0, 2, 0}});
  int still = w.addMesh({{"attributes", {{"POSITION", plain}}}});
  w.addNode({{"mesh", still}});
  w.addNode({{"mesh", still}});
  Scene scene = loadGltf(w.writeGltf(dir, "copies"));
  ASSERT_EQ(scene.meshes.size(), 3u) << "two morphed copies and one shared still mesh";
  ASSERT_EQ(scene.instances.size(), 4u);
  EXPECT_EQ(scene.meshes[scene.instances[0].mesh].morphWeights, std::vector<float>{0.7f});
  EXPECT_EQ(scene.meshes[scene.instances[1].mesh].morphWeights, std::vector<float>{0.1f});
  EXPECT_NE(scene.instances[0].mesh, scene.instances[1].mesh);
  EXPECT_EQ(scene.instances[2].mesh, scene.instances[3].mesh);
}

// Which channels are dropped, and how: a skinned node's own TRS silently (glTF ignores that
// node's transform), a `weights` channel of a node without morph targets with a warning; a
// CUBICSPLINE `weights` sampler is an error like any other.
TEST_F(GltfSkinTest, ChannelsWithoutEffect) {
  GltfWriter w;
  StripFile f = writeStrip(w);
  int pos = w.addPositions({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
  int plain = w.addNode({{"mesh", w.addMesh({{"attributes", {{"POSITION", pos}}}})}});
  const float times[] = {0.0f, 1.0f};
  const float moves[] = {0, 0, 0, 1, 0, 0};
  int in = w.addAccessor(w.addView(times, sizeof(times)), kFloat, 2, "SCALAR");
  int out = w.addAccessor(w.addView(moves, sizeof(moves)), kFloat, 2, "VEC3");
  int weights = w.addAccessor(w.addView(times, sizeof(times)), kFloat, 2, "SCALAR");
  w.doc["animations"] = json::array(
      {{{"samplers", {{{"input", in}, {"output", out}}, {{"input", in}, {"output", weights}}}},
        {"channels",
         {{{"sampler", 0}, {"target", {{"node", f.skinned}, {"path", "translation"}}}},
          {{"sampler", 1}, {"target", {{"node", plain}, {"path", "weights"}}}}}}}});
  LoadWarnings warnings;
  Scene scene = loadGltf(w.writeGltf(dir, "dropped"), warnings);
  EXPECT_TRUE(scene.animation.transforms.empty());
  EXPECT_TRUE(scene.animation.joints.empty());
  EXPECT_TRUE(scene.animation.morphWeights.empty());
  ASSERT_EQ(warnings.summary().size(), 1u);
  EXPECT_NE(warnings.summary()[0].find("weights animations of nodes without a morphed mesh are "
                                       "ignored"),
            std::string::npos)
      << warnings.summary()[0];

  GltfWriter cubic;
  int p = cubic.addPositions({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
  int mesh = cubic.addMesh({{"attributes", {{"POSITION", p}}}, {"targets", {{{"POSITION", p}}}}});
  int node = cubic.addNode({{"mesh", mesh}});
  const float values[6] = {};
  int cin = cubic.addAccessor(cubic.addView(times, sizeof(times)), kFloat, 2, "SCALAR");
  int cout = cubic.addAccessor(cubic.addView(values, sizeof(values)), kFloat, 6, "SCALAR");
  cubic.doc["animations"] = json::array(
      {{{"samplers", {{{"input", cin}, {"output", cout}, {"interpolation", "CUBICSPLINE"}}}},
        {"channels", {{{"sampler", 0}, {"target", {{"node", node}, {"path", "weights"}}}}}}}});
  expectError(cubic.writeGltf(dir, "cubic"), {"animation 0 channel 0", "CUBICSPLINE"});
}

// A mesh both morphed and skinned morphs first, then skins (glTF 2.0 §3.7.2.2): a delta of
// (1, 0, 0) at weight 1 on a joint turned 90 degrees about +Z lands at R (p + d), not R p + d.
// Two skinned nodes sharing the skin share the Scene::skins entry and get a mesh each.
TEST_F(GltfSkinTest, MorphBeforeSkinAndASharedSkin) {
  GltfWriter w;
  int pos = w.addPositions({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
  int delta = w.addPositions({{1, 0, 0}, {1, 0, 0}, {1, 0, 0}});
  std::vector<uint8_t> joints(12, 0);
  std::vector<float> weights = {1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0};
  int j = addData(w, joints, kUnsignedByte, "VEC4");
  int wt = addData(w, weights, kFloat, "VEC4");
  int morphed = w.addMesh({{"attributes", {{"POSITION", pos}, {"JOINTS_0", j}, {"WEIGHTS_0", wt}}},
                           {"targets", {{{"POSITION", delta}}}}});
  w.doc["meshes"][size_t(morphed)]["weights"] = {1.0};
  int plain = w.addMesh({{"attributes", {{"POSITION", pos}, {"JOINTS_0", j}, {"WEIGHTS_0", wt}}}});
  const float s = std::sqrt(0.5f);
  int joint = w.addNode({{"rotation", {0, 0, s, s}}});
  w.addNode({{"mesh", morphed}, {"skin", 0}});
  w.addNode({{"mesh", plain}, {"skin", 0}});
  w.doc["skins"] = json::array({{{"joints", {joint}}}});
  Scene scene = loadGltf(w.writeGltf(dir, "both"));
  ASSERT_EQ(scene.meshes.size(), 2u);
  ASSERT_EQ(scene.skins.size(), 1u);
  EXPECT_EQ(scene.meshes[0].skin, 0);
  EXPECT_EQ(scene.meshes[1].skin, 0);
  Scene posed = posedScene(scene, restPose(scene));
  // (x, y) turned 90 degrees about +Z is (-y, x).
  EXPECT_VEC3_NEAR(posed.meshes[0].geometries[0].positions[1], glm::vec3(0, 2, 0));
  EXPECT_VEC3_NEAR(posed.meshes[0].geometries[0].positions[2], glm::vec3(-1, 1, 0));
  EXPECT_VEC3_NEAR(posed.meshes[1].geometries[0].positions[1], glm::vec3(0, 1, 0));
}

// ---- errors ----

// A one-triangle skinned mesh with two joints whose parts the tests break.
struct SkinParts {
  std::vector<uint8_t> joints = {0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0};
  std::vector<float> weights = {1, 0, 0, 0, 1, 0, 0, 0, 0.5f, 0.5f, 0, 0};
  size_t inverseBindMatrices = 2;
};

std::string writeSkin(GltfWriter& w, const std::string& dir, const SkinParts& parts) {
  int pos = w.addPositions({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
  int j = addData(w, parts.joints, kUnsignedByte, "VEC4");
  int wt = addData(w, parts.weights, kFloat, "VEC4");
  int mesh = w.addMesh({{"attributes", {{"POSITION", pos}, {"JOINTS_0", j}, {"WEIGHTS_0", wt}}}});
  int a = w.addNode({{"name", "a"}});
  int b = w.addNode({{"name", "b"}});
  w.addNode({{"mesh", mesh}, {"skin", 0}});
  std::vector<glm::mat4> inverse(parts.inverseBindMatrices, glm::mat4(1.0f));
  int ibm =
      w.addAccessor(w.addView(inverse.data(), inverse.size() * 64), kFloat, inverse.size(), "MAT4");
  w.doc["skins"] =
      json::array({{{"name", "rig"}, {"joints", {a, b}}, {"inverseBindMatrices", ibm}}});
  return w.writeGltf(dir, "broken");
}

TEST_F(GltfSkinTest, JointIndexOutsideTheSkin) {
  GltfWriter w;
  SkinParts parts;
  parts.joints[8] = 5;  // vertex 2's first joint, weighted 0.5
  expectError(writeSkin(w, dir, parts),
              {"mesh 0 primitive 0", "JOINTS_0 of vertex 2 names joint 5", "2 joints"});
}

TEST_F(GltfSkinTest, WeightsAndJointsOfDifferentCounts) {
  GltfWriter w;
  SkinParts parts;
  parts.weights.resize(8);
  expectError(writeSkin(w, dir, parts), {"mesh 0 primitive 0", "WEIGHTS_0 has 2 elements"});
}

TEST_F(GltfSkinTest, WeightsSummingToZero) {
  GltfWriter w;
  SkinParts parts;
  parts.weights[4] = 0.0f;
  expectError(writeSkin(w, dir, parts), {"mesh 0 primitive 0", "WEIGHTS_0 of vertex 1 sums to 0"});
}

TEST_F(GltfSkinTest, InverseBindMatrixCountMismatch) {
  GltfWriter w;
  SkinParts parts;
  parts.inverseBindMatrices = 3;
  expectError(writeSkin(w, dir, parts), {"skin 0 ('rig')", "3 inverseBindMatrices for 2 joints"});
}

TEST_F(GltfSkinTest, MorphWeightOutputOfTheWrongCount) {
  GltfWriter w;
  int pos = w.addPositions({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
  int mesh = w.addMesh({{"attributes", {{"POSITION", pos}}},
                        {"targets", {{{"POSITION", pos}}, {{"POSITION", pos}}}}});
  int node = w.addNode({{"mesh", mesh}});
  const float times[] = {0.0f, 1.0f};
  const float values[] = {0.0f, 1.0f, 0.5f};  // 3, where 2 keys x 2 targets need 4
  int in = w.addAccessor(w.addView(times, sizeof(times)), kFloat, 2, "SCALAR");
  int out = w.addAccessor(w.addView(values, sizeof(values)), kFloat, 3, "SCALAR");
  w.doc["animations"] = json::array(
      {{{"samplers", {{{"input", in}, {"output", out}}}},
        {"channels", {{{"sampler", 0}, {"target", {{"node", node}, {"path", "weights"}}}}}}}});
  expectError(w.writeGltf(dir, "weights"),
              {"animation 0 channel 0", "3 weights", "2 keys x 2 morph targets need 4"});
}

TEST_F(GltfSkinTest, PrimitivesWithDifferentTargetCounts) {
  GltfWriter w;
  int pos = w.addPositions({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
  json one = {{"attributes", {{"POSITION", pos}}}, {"targets", {{{"POSITION", pos}}}}};
  json two = {{"attributes", {{"POSITION", pos}}},
              {"targets", {{{"POSITION", pos}}, {{"POSITION", pos}}}}};
  w.doc["meshes"].push_back({{"primitives", {one, two}}});
  w.addNode({{"mesh", 0}});
  expectError(w.writeGltf(dir, "targets"),
              {"mesh 0 primitive 0 has 1 morph targets but mesh 0 primitive 1 has 2"});
}

TEST_F(GltfSkinTest, NodeWeightsOfTheWrongCount) {
  GltfWriter w;
  int pos = w.addPositions({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
  int mesh = w.addMesh({{"attributes", {{"POSITION", pos}}}, {"targets", {{{"POSITION", pos}}}}});
  w.addNode({{"name", "n"}, {"mesh", mesh}, {"weights", {0.5, 0.5}}});
  expectError(w.writeGltf(dir, "nodeweights"), {"node 0 ('n') has 2 weights for 1 morph targets"});
}

// ---- deformation.cpp on hand-built scenes ----

// One triangle skinned to two joints (a root and its child at x = 1), with a tangent stream.
Scene handBuiltSkin() {
  Scene scene;
  scene.materials.push_back(Material{});
  Geometry g;
  g.positions = {{0, 0, 0}, {2, 0, 0}, {2, 1, 0}};
  g.normals = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
  g.uvs.assign(3, glm::vec2(0.0f));
  g.tangents = {{1, 0, 0, -1}, {1, 0, 0, -1}, {1, 0, 0, -1}};
  g.indices = {0, 1, 2};
  g.joints = {{0, 0, 0, 0}, {1, 0, 0, 0}, {1, 0, 0, 0}};
  g.weights = {{1, 0, 0, 0}, {1, 0, 0, 0}, {1, 0, 0, 0}};
  Mesh mesh;
  mesh.name = "arm";
  mesh.geometries.push_back(g);
  mesh.skin = 0;
  scene.meshes.push_back(mesh);
  scene.instances.push_back(Instance{0, glm::mat4(1.0f), "arm"});
  scene.skeleton.push_back(SkeletonNode{"root", -1, glm::mat4(1.0f)});
  scene.skeleton.push_back(
      SkeletonNode{"child", 0, glm::translate(glm::mat4(1.0f), glm::vec3(1, 0, 0))});
  Skin skin;
  skin.joints = {0, 1};
  skin.inverseBindMatrices = {glm::mat4(1.0f),
                              glm::translate(glm::mat4(1.0f), glm::vec3(-1, 0, 0))};
  scene.skins.push_back(skin);
  return scene;
}

// Normals and tangents turn with the joint; the tangent's handedness (w) is kept.
TEST(Deformation, NormalsAndTangentsFollowTheSkin) {
  Scene scene = handBuiltSkin();
  validateDeformation(scene, "hand");
  SceneAnimation animation;
  JointTrack track;
  track.node = 1;
  track.trs.restTranslation = glm::vec3(1, 0, 0);
  track.trs.rotation.times = {0.0f};
  track.trs.rotation.values = {glm::angleAxis(glm::radians(90.0f), glm::vec3(0, 1, 0))};
  animation.joints.push_back(track);
  DeformationPose pose;
  evaluatePose(scene, animation, 0.0f, pose);
  Scene posed = posedScene(scene, pose);
  const Geometry& g = posed.meshes[0].geometries[0];
  // 90 degrees about +Y around (1, 0, 0): (2, 0, 0) -> (1, 0, -1); +Z -> +X; +X -> -Z.
  EXPECT_VEC3_NEAR(g.positions[0], glm::vec3(0, 0, 0));
  EXPECT_VEC3_NEAR(g.positions[1], glm::vec3(1, 0, -1));
  EXPECT_VEC3_NEAR(g.positions[2], glm::vec3(1, 1, -1));
  EXPECT_VEC3_NEAR(g.normals[1], glm::vec3(1, 0, 0));
  EXPECT_VEC3_NEAR(glm::vec3(g.tangents[1]), glm::vec3(0, 0, -1));
  EXPECT_EQ(g.tangents[1].w, -1.0f);
  EXPECT_VEC3_NEAR(g.normals[0], glm::vec3(0, 0, 1)) << "vertex 0 stays on the root";
  EXPECT_TRUE(g.joints.empty());
  EXPECT_EQ(posed.meshes[0].skin, -1);
}

// A morph weight track whose target count differs from its mesh's is skipped (the rest weights
// stay), not read out of bounds.
TEST(Deformation, MorphTrackOfAnotherTargetCountIsSkipped) {
  Scene scene = handBuiltSkin();
  Geometry& g = scene.meshes[0].geometries[0];
  g.morphTargets.push_back(MorphTarget{{{0, 0, 1}, {0, 0, 1}, {0, 0, 1}}, {}, {}});
  scene.meshes[0].morphWeights = {0.5f};
  validateDeformation(scene, "hand");
  SceneAnimation animation;
  animation.morphWeights.push_back(MorphWeightTrack{0, 2, {0.0f}, {1.0f, 1.0f}});
  DeformationPose pose;
  evaluatePose(scene, animation, 0.0f, pose);
  EXPECT_EQ(pose.morphWeights[0], std::vector<float>{0.5f});
  EXPECT_VEC3_NEAR(posedScene(scene, pose).meshes[0].geometries[0].positions[0],
                   glm::vec3(0, 0, 0.5f));
}

void expectInvalid(const Scene& scene, const std::string& keyword) {
  try {
    validateDeformation(scene, "hand");
    ADD_FAILURE() << "valid, expected an error containing '" << keyword << "'";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(keyword), std::string::npos) << e.what();
  }
}

TEST(Deformation, ValidationNamesTheProblem) {
  {
    Scene scene = handBuiltSkin();
    scene.instances.push_back(scene.instances[0]);
    expectInvalid(scene, "placed by 2 instances");
  }
  {
    Scene scene = handBuiltSkin();
    scene.skeleton[0].parent = 1;
    expectInvalid(scene, "does not come before it");
  }
  {
    Scene scene = handBuiltSkin();
    scene.skins[0].inverseBindMatrices.pop_back();
    expectInvalid(scene, "2 joints but 1 inverse bind matrices");
  }
  {
    Scene scene = handBuiltSkin();
    scene.meshes[0].geometries[0].weights[2] = {0.5f, 0.2f, 0, 0};
    expectInvalid(scene, "vertex 2 has joint weights summing to");
  }
  {
    Scene scene = handBuiltSkin();
    scene.meshes[0].geometries[0].joints[1].x = 2;
    expectInvalid(scene, "vertex 1 uses joint 2 of a skin with 2 joints");
  }
  {
    Scene scene = handBuiltSkin();
    scene.meshes[0].morphWeights = {1.0f};
    expectInvalid(scene, "0 morph targets, but the mesh has 1 morph weights");
  }
  {
    Scene scene = handBuiltSkin();
    JointTrack track;
    track.node = 5;
    scene.animation.joints.push_back(track);
    expectInvalid(scene, "joint track 0 animates skeleton node 5 (2 nodes)");
  }
  {
    Scene scene = handBuiltSkin();
    scene.animation.morphWeights.push_back(MorphWeightTrack{0, 2, {0.0f}, {1.0f, 1.0f}});
    expectInvalid(scene, "morph weight track 0 has 2 targets but mesh 0 has 0 morph weights");
  }
  {
    Scene scene = handBuiltSkin();
    TransformTrack track;
    track.parentNode = 2;
    scene.animation.transforms.push_back(track);
    expectInvalid(scene, "transform track 0 hangs under skeleton node 2 (2 nodes)");
  }
}

}  // namespace
}  // namespace bounce
