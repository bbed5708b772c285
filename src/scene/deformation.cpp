#include "scene/deformation.h"

#include <cmath>

#include "core/error.h"

namespace bounce {

namespace {

void composeSkeleton(const Scene& scene, std::span<const glm::mat4> locals,
                     std::vector<glm::mat4>& world) {
  world.resize(scene.skeleton.size());
  for (size_t n = 0; n < scene.skeleton.size(); ++n) {
    int parent = scene.skeleton[n].parent;
    world[n] = parent < 0 ? locals[n] : world[size_t(parent)] * locals[n];
  }
}

void composeJoints(const Scene& scene, DeformationPose& pose) {
  pose.jointMatrices.clear();
  pose.jointBase.clear();
  for (const Skin& skin : scene.skins) {
    pose.jointBase.push_back(uint32_t(pose.jointMatrices.size()));
    for (size_t j = 0; j < skin.joints.size(); ++j)
      pose.jointMatrices.push_back(pose.skeletonWorld[skin.joints[j]] *
                                   skin.inverseBindMatrices[j]);
  }
}

std::vector<glm::mat4> restLocals(const Scene& scene) {
  std::vector<glm::mat4> locals;
  locals.reserve(scene.skeleton.size());
  for (const SkeletonNode& node : scene.skeleton) locals.push_back(node.local);
  return locals;
}

void restWeights(const Scene& scene, std::vector<std::vector<float>>& weights) {
  weights.resize(scene.meshes.size());
  for (size_t m = 0; m < scene.meshes.size(); ++m) weights[m] = scene.meshes[m].morphWeights;
}

glm::vec3 normalizedOr(const glm::vec3& v, const glm::vec3& fallback) {
  float length = glm::length(v);
  return length > 0.0f && std::isfinite(length) ? v / length : fallback;
}

// The morph step of one vertex: rest + sum of weighted deltas.
void morphVertex(const Geometry& rest, std::span<const float> weights, size_t v, glm::vec3& p,
                 glm::vec3& n, glm::vec3& t) {
  for (size_t k = 0; k < rest.morphTargets.size() && k < weights.size(); ++k) {
    const MorphTarget& target = rest.morphTargets[k];
    float w = weights[k];
    if (w == 0.0f) continue;
    if (!target.positions.empty()) p += w * target.positions[v];
    if (!target.normals.empty()) n += w * target.normals[v];
    if (!target.tangents.empty()) t += w * target.tangents[v];
  }
}

glm::mat4 skinMatrix(const Geometry& rest, std::span<const glm::mat4> joints, size_t v) {
  glm::mat4 m(0.0f);
  for (int i = 0; i < 4; ++i) m += rest.weights[v][i] * joints[rest.joints[v][i]];
  return m;
}

}  // namespace

DeformationPose restPose(const Scene& scene) {
  DeformationPose pose;
  composeSkeleton(scene, restLocals(scene), pose.skeletonWorld);
  composeJoints(scene, pose);
  restWeights(scene, pose.morphWeights);
  return pose;
}

void evaluatePose(const Scene& scene, const SceneAnimation& animation, float t,
                  DeformationPose& pose) {
  std::vector<glm::mat4> locals = restLocals(scene);
  evaluateJoints(animation, t, locals);
  composeSkeleton(scene, locals, pose.skeletonWorld);
  composeJoints(scene, pose);
  restWeights(scene, pose.morphWeights);
  evaluateMorphWeights(animation, t, pose.morphWeights);
}

void poseGeometry(const Scene& scene, const DeformationPose& pose, uint32_t mesh,
                  const Geometry& rest, Geometry& out) {
  const Mesh& m = scene.meshes.at(mesh);
  std::span<const float> weights = pose.morphWeights.at(mesh);
  std::span<const glm::mat4> joints;
  if (m.skin >= 0)
    joints =
        std::span<const glm::mat4>(pose.jointMatrices)
            .subspan(pose.jointBase[size_t(m.skin)], scene.skins[size_t(m.skin)].joints.size());
  bool skinned = !joints.empty() && !rest.joints.empty();
  for (size_t v = 0; v < rest.positions.size(); ++v) {
    glm::vec3 p = rest.positions[v], n = rest.normals[v];
    glm::vec3 t = rest.tangents.empty() ? glm::vec3(0.0f) : glm::vec3(rest.tangents[v]);
    morphVertex(rest, weights, v, p, n, t);
    if (skinned) {
      glm::mat4 s = skinMatrix(rest, joints, v);
      p = glm::vec3(s * glm::vec4(p, 1.0f));
      n = glm::mat3(s) * n;
      t = glm::mat3(s) * t;
    }
    out.positions[v] = p;
    out.normals[v] = normalizedOr(n, rest.normals[v]);
    if (!rest.tangents.empty())
      out.tangents[v] = glm::vec4(normalizedOr(t, glm::vec3(rest.tangents[v])), rest.tangents[v].w);
  }
}

Scene posedScene(const Scene& scene, const DeformationPose& pose) {
  Scene posed = scene;
  for (uint32_t m = 0; m < posed.meshes.size(); ++m) {
    Mesh& mesh = posed.meshes[m];
    if (!mesh.deforms()) continue;
    for (size_t g = 0; g < mesh.geometries.size(); ++g) {
      poseGeometry(scene, pose, m, scene.meshes[m].geometries[g], mesh.geometries[g]);
      mesh.geometries[g].joints.clear();
      mesh.geometries[g].weights.clear();
      mesh.geometries[g].morphTargets.clear();
    }
    mesh.skin = -1;
    mesh.morphWeights.clear();
  }
  return posed;
}

Scene sceneFrozenAt(const Scene& scene, float t) {
  DeformationPose pose;
  evaluatePose(scene, scene.animation, t, pose);
  std::vector<glm::mat4> transforms;
  for (const Instance& instance : scene.instances) transforms.push_back(instance.transform);
  evaluateTransforms(scene.animation, t, pose.skeletonWorld, transforms);
  std::vector<PunctualLight> lights = scene.lights;
  evaluateLights(scene.animation, t, scene.lights, lights);
  Scene frozen = posedScene(scene, pose);
  for (size_t i = 0; i < frozen.instances.size(); ++i)
    frozen.instances[i].transform = transforms[i];
  frozen.lights = std::move(lights);
  frozen.animation.transforms.clear();
  frozen.animation.joints.clear();
  frozen.animation.morphWeights.clear();
  frozen.animation.lights.clear();
  return frozen;
}

namespace {

void validateMorphTargets(const Mesh& mesh, const Geometry& g, const std::string& where) {
  if (g.morphTargets.size() != mesh.morphWeights.size())
    fail("{}: {} morph targets, but the mesh has {} morph weights", where, g.morphTargets.size(),
         mesh.morphWeights.size());
  size_t n = g.positions.size();
  for (size_t k = 0; k < g.morphTargets.size(); ++k) {
    const MorphTarget& target = g.morphTargets[k];
    for (const std::vector<glm::vec3>* stream :
         {&target.positions, &target.normals, &target.tangents})
      if (!stream->empty() && stream->size() != n)
        fail("{}: morph target {} has a stream of {} entries for {} positions", where, k,
             stream->size(), n);
  }
  for (float w : mesh.morphWeights)
    if (!std::isfinite(w)) fail("{}: a morph weight is not finite", where);
}

void validateSkinStreams(const Scene& scene, const Mesh& mesh, const Geometry& g,
                         const std::string& where) {
  if (g.joints.size() != g.weights.size())
    fail("{}: {} joint entries but {} weight entries", where, g.joints.size(), g.weights.size());
  if (g.joints.empty()) return;
  if (g.joints.size() != g.positions.size())
    fail("{}: {} joint entries for {} positions", where, g.joints.size(), g.positions.size());
  if (mesh.skin < 0) fail("{}: has joints and weights but its mesh has no skin", where);
  size_t jointCount = scene.skins[size_t(mesh.skin)].joints.size();
  for (size_t v = 0; v < g.joints.size(); ++v) {
    for (int i = 0; i < 4; ++i)
      if (g.weights[v][i] != 0.0f && g.joints[v][i] >= jointCount)
        fail("{}: vertex {} uses joint {} of a skin with {} joints", where, v, g.joints[v][i],
             jointCount);
    float sum = g.weights[v].x + g.weights[v].y + g.weights[v].z + g.weights[v].w;
    if (!std::isfinite(sum) || std::abs(sum - 1.0f) > 1e-3f)
      fail("{}: vertex {} has joint weights summing to {}, expected 1", where, v, sum);
  }
}

// Tracks that evaluateTransforms, evaluateJoints and evaluateMorphWeights would skip or leave at
// rest (a skeleton node or mesh that does not exist, a target count unlike the mesh's) are
// errors here rather than silently still meshes.
void validateDeformationTracks(const Scene& scene, const std::string& source) {
  const SceneAnimation& animation = scene.animation;
  for (size_t i = 0; i < animation.transforms.size(); ++i)
    if (animation.transforms[i].parentNode < -1 ||
        animation.transforms[i].parentNode >= int(scene.skeleton.size()))
      fail("{}: transform track {} hangs under skeleton node {} ({} nodes)", source, i,
           animation.transforms[i].parentNode, scene.skeleton.size());
  for (size_t i = 0; i < animation.joints.size(); ++i)
    if (animation.joints[i].node >= scene.skeleton.size())
      fail("{}: joint track {} animates skeleton node {} ({} nodes)", source, i,
           animation.joints[i].node, scene.skeleton.size());
  for (size_t i = 0; i < animation.morphWeights.size(); ++i) {
    const MorphWeightTrack& track = animation.morphWeights[i];
    if (track.mesh >= scene.meshes.size())
      fail("{}: morph weight track {} animates mesh {} ({} meshes)", source, i, track.mesh,
           scene.meshes.size());
    size_t targets = scene.meshes[track.mesh].morphWeights.size();
    if (track.targets != targets)
      fail("{}: morph weight track {} has {} targets but mesh {} has {} morph weights", source, i,
           track.targets, track.mesh, targets);
    if (track.values.size() != track.times.size() * targets)
      fail("{}: morph weight track {} has {} values for {} keys x {} targets", source, i,
           track.values.size(), track.times.size(), targets);
  }
}

}  // namespace

void validateDeformation(const Scene& scene, const std::string& source) {
  validateDeformationTracks(scene, source);
  for (size_t n = 0; n < scene.skeleton.size(); ++n)
    if (scene.skeleton[n].parent >= int(n))
      fail("{}: skeleton node {} ('{}') has parent {}, which does not come before it", source, n,
           scene.skeleton[n].name, scene.skeleton[n].parent);
  for (size_t s = 0; s < scene.skins.size(); ++s) {
    const Skin& skin = scene.skins[s];
    if (skin.inverseBindMatrices.size() != skin.joints.size())
      fail("{}: skin {} ('{}') has {} joints but {} inverse bind matrices", source, s, skin.name,
           skin.joints.size(), skin.inverseBindMatrices.size());
    for (uint32_t joint : skin.joints)
      if (joint >= scene.skeleton.size())
        fail("{}: skin {} ('{}') refers to skeleton node {} ({} nodes)", source, s, skin.name,
             joint, scene.skeleton.size());
  }
  std::vector<int> placements(scene.meshes.size(), 0);
  for (const Instance& instance : scene.instances) ++placements[instance.mesh];
  for (size_t m = 0; m < scene.meshes.size(); ++m) {
    const Mesh& mesh = scene.meshes[m];
    std::string where = fmt::format("{}: mesh {} ('{}')", source, m, mesh.name);
    if (mesh.skin >= int(scene.skins.size()))
      fail("{} refers to skin {} ({} skins)", where, mesh.skin, scene.skins.size());
    if (mesh.deforms() && placements[m] > 1)
      fail("{} deforms but is placed by {} instances (a deforming mesh has one)", where,
           placements[m]);
    for (size_t g = 0; g < mesh.geometries.size(); ++g) {
      std::string geometry = fmt::format("{} primitive {}", where, g);
      validateMorphTargets(mesh, mesh.geometries[g], geometry);
      validateSkinStreams(scene, mesh, mesh.geometries[g], geometry);
    }
  }
}

}  // namespace bounce
