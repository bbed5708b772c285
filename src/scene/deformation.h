// Deforming meshes (glTF 2.0 §3.7.2.2 morph targets, §3.7.3 skins): the pose of every deforming
// mesh at a time t, and the CPU arithmetic that applies it. The GPU applies the same pose in
// `scene-deform` (shaders/rt/scene_deform.comp); posedScene() is its mirror on the CPU, for the
// reference renderer and the tests.
//
// A vertex is posed in two steps, as glTF defines them:
//   morph  p = p_rest + sum_k w_k dp_k (normals and tangents alike, then renormalised)
//   skin   p' = (sum_i weight_i J[joint_i]) p, J[j] = skeletonWorld(joints[j]) x inverseBind[j]
// Normals and tangents go through the skin matrix's upper 3x3 and are renormalised (exact for
// the rotations and uniform scales skins are made of).
#pragma once
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace bounce {

// Everything that decides the deforming meshes' shapes at one time.
struct DeformationPose {
  std::vector<glm::mat4> skeletonWorld;  // per Scene::skeleton node: world transform
  // Joint matrices of every skin, concatenated in Scene::skins order; skin s starts at
  // jointBase[s].
  std::vector<glm::mat4> jointMatrices;
  std::vector<uint32_t> jointBase;
  // Per mesh: its current morph weights (the rest weights where no track animates them);
  // empty for a mesh without morph targets.
  std::vector<std::vector<float>> morphWeights;
};

// The rest pose: the skeleton's rest transforms and the meshes' rest weights.
DeformationPose restPose(const Scene& scene);
// The pose at time t (looping as SceneAnimation::loop says, with the transform tracks). `pose`
// may come from an earlier call; its vectors are reused.
void evaluatePose(const Scene& scene, const SceneAnimation& animation, float t,
                  DeformationPose& pose);

// The posed positions, normals and tangents of one geometry of mesh `mesh` (other streams are
// left untouched): `out` must be a copy of the rest geometry.
void poseGeometry(const Scene& scene, const DeformationPose& pose, uint32_t mesh,
                  const Geometry& rest, Geometry& out);
// A copy of `scene` with every deforming mesh posed (its morph weights cleared and its skin
// removed, so the result is a still scene).
Scene posedScene(const Scene& scene, const DeformationPose& pose);

// The scene as it stands at animation time t, as a still scene: instances placed and lights set
// by their tracks, deforming meshes posed (posedScene), and those tracks dropped from its
// animation (the camera path and time of day stay). For a reference or a fresh BVH of one frame
// of an animation (`--pose-time`).
Scene sceneFrozenAt(const Scene& scene, float t);

// Checks what deformation needs beyond validateScene: joint and weight streams sized together,
// joint indices inside the skin, finite weights, morph target counts and stream sizes, skin
// references, skeleton parents before children, joint and morph weight tracks that name a
// skeleton node or mesh that exists with its target count, transform tracks whose parentNode
// exists. Throws bounce::Error naming `source`.
void validateDeformation(const Scene& scene, const std::string& source);

}  // namespace bounce
