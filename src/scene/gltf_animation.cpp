// glTF animations (glTF 2.0 §3.11) as SceneAnimation transform tracks. Every animation of the
// file plays at once (they share the timeline), as viewers do when asked to "play all".
// Supported: translation, rotation and scale channels of nodes that place a mesh, LINEAR and
// STEP samplers. Not supported, with a warning: morph-target weights, channels on nodes without
// a mesh (an animated parent would have to be evaluated down the hierarchy every frame, which
// the flat per-instance tracks do not model). CUBICSPLINE samplers are an error naming the
// sampler, rather than a silent approximation.
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

template <typename T>
Channel<T> readChannel(const Source& src, const tinygltf::AnimationSampler& sampler,
                       const std::string& what, int components) {
  Channel<T> channel;
  if (sampler.interpolation == "STEP")
    channel.interpolation = Interpolation::Step;
  else if (sampler.interpolation == "CUBICSPLINE")
    fail(
        "{}: {} uses CUBICSPLINE interpolation, which Bounce does not support (re-export with "
        "LINEAR or STEP)",
        src.path, what);
  else if (!sampler.interpolation.empty() && sampler.interpolation != "LINEAR")
    fail("{}: {} has unknown interpolation '{}'", src.path, what, sampler.interpolation);
  channel.times = readFloatAccessor(src, sampler.input, TINYGLTF_TYPE_SCALAR, "input of " + what);
  std::vector<float> values = readFloatAccessor(
      src, sampler.output, components == 4 ? TINYGLTF_TYPE_VEC4 : TINYGLTF_TYPE_VEC3,
      "output of " + what);
  if (values.size() != channel.times.size() * size_t(components))
    fail("{}: {} has {} key times but {} values", src.path, what, channel.times.size(),
         values.size() / size_t(components));
  for (size_t i = 0; i < channel.times.size(); ++i) {
    if (!std::isfinite(channel.times[i]) || (i > 0 && !(channel.times[i] > channel.times[i - 1])))
      fail("{}: {} key times must be finite and strictly increasing (key {})", src.path, what, i);
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

}  // namespace

void loadAnimations(const Source& src, const std::vector<AnimatedInstance>& instances,
                    SceneAnimation& out) {
  std::map<int, size_t> trackOfNode;
  for (size_t a = 0; a < src.model.animations.size(); ++a) {
    const tinygltf::Animation& animation = src.model.animations[a];
    for (size_t c = 0; c < animation.channels.size(); ++c) {
      const tinygltf::AnimationChannel& channel = animation.channels[c];
      std::string what = fmt::format("animation {} channel {}", a, c);
      if (channel.target_path == "weights") {
        warnIgnored(src, "morph target weight animations are ignored", "animation channels", what);
        continue;
      }
      if (channel.sampler < 0 || size_t(channel.sampler) >= animation.samplers.size())
        fail("{}: {} refers to sampler {} ({} samplers)", src.path, what, channel.sampler,
             animation.samplers.size());
      const AnimatedInstance* target = nullptr;
      for (const AnimatedInstance& i : instances)
        if (i.node == channel.target_node) target = &i;
      if (!target) {
        warnIgnored(src,
                    "animations of nodes that place no mesh (skin joints, parents) are ignored",
                    "animation channels", what);
        continue;
      }
      auto [it, added] = trackOfNode.try_emplace(target->node, out.transforms.size());
      if (added)
        out.transforms.push_back(restTrack(src, target->node, target->instance, target->parent));
      TransformTrack& track = out.transforms[it->second];
      const tinygltf::AnimationSampler& sampler = animation.samplers[size_t(channel.sampler)];
      if (channel.target_path == "translation")
        track.translation = readChannel<glm::vec3>(src, sampler, what, 3);
      else if (channel.target_path == "rotation")
        track.rotation = readChannel<glm::quat>(src, sampler, what, 4);
      else if (channel.target_path == "scale")
        track.scale = readChannel<glm::vec3>(src, sampler, what, 3);
      else
        fail("{}: {} has unknown target path '{}'", src.path, what, channel.target_path);
    }
  }
}

}  // namespace bounce::gltf
