// glTF animations (glTF 2.0 §3.11) as SceneAnimation tracks. Every animation of the file plays
// at once (they share the timeline), as viewers do when asked to "play all". Supported, with
// LINEAR and STEP samplers: translation, rotation and scale channels of nodes that place an
// unskinned mesh (transform tracks) and of skeleton nodes: the joints of skins, the animated
// ancestors of mesh nodes, and their ancestors (joint tracks; a node that is both gets both).
// A mesh node below an animated ancestor gets a transform track, animated or at rest, that
// hangs under its parent's skeleton node, so it follows the ancestors (the sword in the hand
// bone, the wheel of the moving car). Also `weights` channels of nodes with a morphed mesh
// (morph weight tracks). Not supported, with a warning: channels on nodes that affect nothing
// drawn (no mesh in or below them, no joint: an animated camera or light node). TRS channels
// of a skinned mesh's own node are dropped silently: glTF ignores that node's transform.
// CUBICSPLINE samplers are an error naming the sampler, rather than a silent approximation.
#include <cmath>
#include <map>
#include <type_traits>

#include <glm/gtc/matrix_transform.hpp>

#include "core/error.h"
#include "scene/gltf_accessor.h"
#include "scene/gltf_internal.h"

namespace bounce::gltf {

namespace {

glm::vec3 vec3At(const std::vector<double>& v, glm::vec3 fallback) {
  return v.size() == 3 ? glm::vec3(float(v[0]), float(v[1]), float(v[2])) : fallback;
}

// The node's rest TRS; a node given by `matrix` has no TRS to animate.
TransformTrack restTrack(const Source& src, int node, uint32_t instance, const glm::mat4& parent) {
  const tinygltf::Node& n = src.model.nodes[size_t(node)];
  if (!n.matrix.empty())
    fail("{}: {} is animated but has a matrix (glTF allows animating TRS nodes only)", src.path,
         describe("node", node, n.name));
  TransformTrack track;
  track.instance = instance;
  track.parent = parent;
  track.restTranslation = vec3At(n.translation, glm::vec3(0.0f));
  track.restScale = vec3At(n.scale, glm::vec3(1.0f));
  if (n.rotation.size() == 4)
    track.restRotation = glm::quat(float(n.rotation[3]), float(n.rotation[0]), float(n.rotation[1]),
                                   float(n.rotation[2]));  // w, x, y, z
  return track;
}

Interpolation readInterpolation(const Source& src, const tinygltf::AnimationSampler& sampler,
                                const std::string& what) {
  if (sampler.interpolation == "STEP") return Interpolation::Step;
  if (sampler.interpolation == "CUBICSPLINE")
    fail(
        "{}: {} uses CUBICSPLINE interpolation, which Bounce does not support (re-export with "
        "LINEAR or STEP)",
        src.path, what);
  if (!sampler.interpolation.empty() && sampler.interpolation != "LINEAR")
    fail("{}: {} has unknown interpolation '{}'", src.path, what, sampler.interpolation);
  return Interpolation::Linear;
}

std::vector<float> readTimes(const Source& src, const tinygltf::AnimationSampler& sampler,
                             const std::string& what) {
  std::vector<float> times =
      readFloatAccessor(src, sampler.input, TINYGLTF_TYPE_SCALAR, "input of " + what);
  for (size_t i = 0; i < times.size(); ++i)
    if (!std::isfinite(times[i]) || (i > 0 && !(times[i] > times[i - 1])))
      fail("{}: {} key times must be finite and strictly increasing (key {})", src.path, what, i);
  return times;
}

template <typename T>
Channel<T> readChannel(const Source& src, const tinygltf::AnimationSampler& sampler,
                       const std::string& what, int components) {
  Channel<T> channel;
  channel.interpolation = readInterpolation(src, sampler, what);
  channel.times = readTimes(src, sampler, what);
  std::vector<float> values = readFloatAccessor(
      src, sampler.output, components == 4 ? TINYGLTF_TYPE_VEC4 : TINYGLTF_TYPE_VEC3,
      "output of " + what);
  if (values.size() != channel.times.size() * size_t(components))
    fail("{}: {} has {} key times but {} values", src.path, what, channel.times.size(),
         values.size() / size_t(components));
  for (size_t i = 0; i < channel.times.size(); ++i) {
    const float* v = values.data() + i * size_t(components);
    for (int c = 0; c < components; ++c)
      if (!std::isfinite(v[c])) fail("{}: {} has a non-finite value at key {}", src.path, what, i);
    if constexpr (std::is_same_v<T, glm::quat>)
      channel.values.push_back(glm::normalize(glm::quat(v[3], v[0], v[1], v[2])));
    else
      channel.values.push_back(T(v[0], v[1], v[2]));
  }
  return channel;
}

// A `weights` channel: one weight per morph target of the mesh at each key (glTF 2.0 §3.11:
// the output holds keys x targets scalars, key-major).
MorphWeightTrack readWeightChannel(const Source& src, const tinygltf::AnimationSampler& sampler,
                                   const std::string& what, uint32_t mesh, uint32_t targets) {
  MorphWeightTrack track;
  track.mesh = mesh;
  track.targets = targets;
  track.interpolation = readInterpolation(src, sampler, what);
  track.times = readTimes(src, sampler, what);
  track.values = readFloatAccessor(src, sampler.output, TINYGLTF_TYPE_SCALAR, "output of " + what);
  if (track.values.size() != track.times.size() * targets)
    fail(
        "{}: {} has {} weights in its output; {} keys x {} morph targets need {} (output of the "
        "weights channel)",
        src.path, what, track.values.size(), track.times.size(), targets,
        track.times.size() * targets);
  for (size_t i = 0; i < track.values.size(); ++i)
    if (!std::isfinite(track.values[i]))
      fail("{}: {} has a non-finite weight at key {}", src.path, what, i / targets);
  return track;
}

// Sets the channel of `track` that `path` names.
void assignTransformChannel(const Source& src, const tinygltf::AnimationSampler& sampler,
                            const std::string& path, const std::string& what,
                            TransformTrack& track) {
  if (path == "translation")
    track.translation = readChannel<glm::vec3>(src, sampler, what, 3);
  else if (path == "rotation")
    track.rotation = readChannel<glm::quat>(src, sampler, what, 4);
  else if (path == "scale")
    track.scale = readChannel<glm::vec3>(src, sampler, what, 3);
  else
    fail("{}: {} has unknown target path '{}'", src.path, what, path);
}

}  // namespace

void loadAnimations(const Source& src, const AnimationTargets& targets,
                    const std::vector<Mesh>& meshes, SceneAnimation& out) {
  std::map<int, size_t> trackOfNode, jointTrackOfNode;
  // Instances under animated ancestors move even without channels of their own.
  for (const AnimatedInstance& i : targets.instances) {
    if (i.parentNode < 0) continue;
    trackOfNode[i.node] = out.transforms.size();
    TransformTrack track;  // the node's skeleton node places it: identity TRS
    if (!i.placedBySkeleton) track = restTrack(src, i.node, i.instance, i.parent);
    track.instance = i.instance;
    track.parent = i.parent;
    track.parentNode = i.parentNode;
    out.transforms.push_back(std::move(track));
  }
  for (size_t a = 0; a < src.model.animations.size(); ++a) {
    const tinygltf::Animation& animation = src.model.animations[a];
    for (size_t c = 0; c < animation.channels.size(); ++c) {
      const tinygltf::AnimationChannel& channel = animation.channels[c];
      std::string what = fmt::format("animation {} channel {}", a, c);
      if (channel.sampler < 0 || size_t(channel.sampler) >= animation.samplers.size())
        fail("{}: {} refers to sampler {} ({} samplers)", src.path, what, channel.sampler,
             animation.samplers.size());
      const tinygltf::AnimationSampler& sampler = animation.samplers[size_t(channel.sampler)];
      int node = channel.target_node;
      if (channel.target_path == "weights") {
        auto morphed = targets.morphedMeshes.find(node);
        if (morphed == targets.morphedMeshes.end()) {
          warnIgnored(src, "weights animations of nodes without a morphed mesh are ignored",
                      "animation channels", what);
          continue;
        }
        uint32_t mesh = morphed->second;
        out.morphWeights.push_back(readWeightChannel(src, sampler, what, mesh,
                                                     uint32_t(meshes[mesh].morphWeights.size())));
        continue;
      }
      const AnimatedInstance* target = nullptr;
      for (const AnimatedInstance& i : targets.instances)
        if (i.node == node) target = &i;
      auto joint = targets.skeletonNodes.find(node);
      if (target) {
        auto [it, added] = trackOfNode.try_emplace(node, out.transforms.size());
        if (added) out.transforms.push_back(restTrack(src, node, target->instance, target->parent));
        assignTransformChannel(src, sampler, channel.target_path, what, out.transforms[it->second]);
      }
      if (joint != targets.skeletonNodes.end()) {
        auto [it, added] = jointTrackOfNode.try_emplace(node, out.joints.size());
        if (added) out.joints.push_back({joint->second, restTrack(src, node, 0, glm::mat4(1.0f))});
        assignTransformChannel(src, sampler, channel.target_path, what, out.joints[it->second].trs);
      }
      if (!target && joint == targets.skeletonNodes.end() && !targets.skinnedNodes.count(node))
        warnIgnored(src,
                    "animations of nodes that place no mesh, have none below them and are no "
                    "skin joint are ignored",
                    "animation channels", what);
    }
  }
}

}  // namespace bounce::gltf
