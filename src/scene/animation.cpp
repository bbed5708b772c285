#include "scene/animation.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "scene/scene.h"

namespace bounce {

namespace {

// Index i of the key interval [times[i], times[i + 1]) holding t and the fraction in it;
// clamped to the ends (glTF: values hold outside the key range).
struct KeySpan {
  size_t i = 0;
  float u = 0.0f;
};

KeySpan locate(const std::vector<float>& times, float t) {
  if (times.size() < 2 || t <= times.front()) return {0, 0.0f};
  if (t >= times.back()) return {times.size() - 2, 1.0f};
  size_t i = size_t(std::upper_bound(times.begin(), times.end(), t) - times.begin()) - 1;
  return {i, (t - times[i]) / (times[i + 1] - times[i])};
}

// t wrapped into [0, duration); t itself for duration 0.
float wrap(float t, float duration) {
  if (!(duration > 0.0f)) return t;
  float w = std::fmod(t, duration);
  return w < 0.0f ? w + duration : w;
}

template <typename T, typename Mix>
T sample(const Channel<T>& c, float t, const T& rest, Mix mix) {
  if (c.empty()) return rest;
  if (c.times.size() == 1) return c.values[0];
  KeySpan k = locate(c.times, t);
  if (c.interpolation == Interpolation::Step) return c.values[k.u >= 1.0f ? k.i + 1 : k.i];
  return mix(c.values[k.i], c.values[k.i + 1], k.u);
}

glm::vec3 catmullRom(const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2,
                     const glm::vec3& p3, float u) {
  float u2 = u * u, u3 = u2 * u;
  return 0.5f * (2.0f * p1 + (p2 - p0) * u + (2.0f * p0 - 5.0f * p1 + 4.0f * p2 - p3) * u2 +
                 (3.0f * p1 - p0 - 3.0f * p2 + p3) * u3);
}

bool finite(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

}  // namespace

float TimeOfDayTrack::hoursAt(float t) const {
  float h = dayCycleSeconds > 0.0f ? hours + 24.0f * t / dayCycleSeconds : hours;
  return wrap(h, 24.0f);
}

static float trsDuration(const TransformTrack& track) {
  float d = 0.0f;
  for (const std::vector<float>* times :
       {&track.translation.times, &track.rotation.times, &track.scale.times})
    if (!times->empty()) d = std::max(d, times->back());
  return d;
}

float SceneAnimation::transformDuration() const {
  float d = 0.0f;
  for (const TransformTrack& track : transforms) d = std::max(d, trsDuration(track));
  for (const JointTrack& track : joints) d = std::max(d, trsDuration(track.trs));
  for (const MorphWeightTrack& track : morphWeights)
    if (!track.times.empty()) d = std::max(d, track.times.back());
  return d;
}

float SceneAnimation::lightDuration() const {
  float d = 0.0f;
  for (const LightTrack& track : lights)
    for (const std::vector<float>* times : {&track.position.times, &track.intensityScale.times})
      if (!times->empty()) d = std::max(d, times->back());
  return d;
}

float sampleChannel(const Channel<float>& channel, float t, float rest) {
  return sample(channel, t, rest, [](float a, float b, float u) { return a + (b - a) * u; });
}

glm::vec3 sampleChannel(const Channel<glm::vec3>& channel, float t, const glm::vec3& rest) {
  return sample(channel, t, rest,
                [](const glm::vec3& a, const glm::vec3& b, float u) { return glm::mix(a, b, u); });
}

glm::quat sampleChannel(const Channel<glm::quat>& channel, float t, const glm::quat& rest) {
  // glm::slerp takes the shorter arc (flips b when dot(a, b) < 0), as glTF asks.
  return sample(channel, t, rest, [](const glm::quat& a, const glm::quat& b, float u) {
    return glm::normalize(glm::slerp(a, b, u));
  });
}

// T x R x S at t, without the parent.
static glm::mat4 evaluateTrs(const TransformTrack& track, float t) {
  glm::mat4 m =
      glm::translate(glm::mat4(1.0f), sampleChannel(track.translation, t, track.restTranslation));
  m *= glm::mat4_cast(sampleChannel(track.rotation, t, track.restRotation));
  return glm::scale(m, sampleChannel(track.scale, t, track.restScale));
}

glm::mat4 evaluateTrack(const TransformTrack& track, float t) {
  return track.parent * evaluateTrs(track, t);
}

void evaluateTransforms(const SceneAnimation& animation, float t,
                        std::span<const glm::mat4> skeletonWorld,
                        std::vector<glm::mat4>& transforms) {
  float local = animation.loop ? wrap(t, animation.transformDuration()) : t;
  for (const TransformTrack& track : animation.transforms) {
    if (track.instance >= transforms.size()) continue;
    bool underSkeleton = track.parentNode >= 0 && size_t(track.parentNode) < skeletonWorld.size();
    const glm::mat4& parent =
        underSkeleton ? skeletonWorld[size_t(track.parentNode)] : track.parent;
    transforms[track.instance] = parent * evaluateTrs(track, local);
  }
}

bool transformsNeedSkeleton(const SceneAnimation& animation) {
  for (const TransformTrack& track : animation.transforms)
    if (track.parentNode >= 0) return true;
  return false;
}

void evaluateJoints(const SceneAnimation& animation, float t, std::vector<glm::mat4>& locals) {
  float local = animation.loop ? wrap(t, animation.transformDuration()) : t;
  for (const JointTrack& track : animation.joints)
    if (track.node < locals.size()) locals[track.node] = evaluateTrack(track.trs, local);
}

void evaluateMorphWeights(const SceneAnimation& animation, float t,
                          std::vector<std::vector<float>>& weights) {
  float local = animation.loop ? wrap(t, animation.transformDuration()) : t;
  for (const MorphWeightTrack& track : animation.morphWeights) {
    if (track.mesh >= weights.size() || track.times.empty()) continue;
    std::vector<float>& out = weights[track.mesh];
    size_t n = track.targets;
    if (out.size() != n || track.values.size() != track.times.size() * n) continue;
    KeySpan k = locate(track.times, local);
    if (track.times.size() == 1 || track.interpolation == Interpolation::Step) {
      size_t key = track.times.size() == 1 ? 0 : (k.u >= 1.0f ? k.i + 1 : k.i);
      for (size_t i = 0; i < n; ++i) out[i] = track.values[key * n + i];
      continue;
    }
    for (size_t i = 0; i < n; ++i) {
      float a = track.values[k.i * n + i], b = track.values[(k.i + 1) * n + i];
      out[i] = a + (b - a) * k.u;
    }
  }
}

void evaluateLights(const SceneAnimation& animation, float t,
                    const std::vector<PunctualLight>& rest, std::vector<PunctualLight>& lights) {
  float local = animation.loop ? wrap(t, animation.lightDuration()) : t;
  for (const LightTrack& track : animation.lights) {
    if (track.light >= lights.size() || track.light >= rest.size()) continue;
    const PunctualLight& r = rest[track.light];
    PunctualLight& l = lights[track.light];
    l.position = sampleChannel(track.position, local, r.position);
    l.intensity = r.intensity * std::max(0.0f, sampleChannel(track.intensityScale, local, 1.0f));
  }
}

Camera evaluateCameraPath(const CameraPath& path, float t) {
  const std::vector<CameraKeyframe>& keys = path.keys;
  Camera camera;
  if (keys.empty()) return camera;
  float local = path.loop ? wrap(t, path.duration()) : t;
  size_t i = 0;
  float u = 0.0f;
  if (keys.size() > 1 && local > keys.front().time) {
    if (local >= keys.back().time) {
      i = keys.size() - 2;
      u = 1.0f;
    } else {
      while (keys[i + 1].time <= local) ++i;
      u = (local - keys[i].time) / (keys[i + 1].time - keys[i].time);
    }
  }
  const CameraKeyframe& a = keys[i];
  if (keys.size() == 1) {
    camera.position = a.position;
    camera.target = a.target;
    camera.verticalFovDegrees = a.verticalFovDegrees;
    return camera;
  }
  const CameraKeyframe& b = keys[i + 1];
  // A cut key is reached by a jump: hold the previous key's view until its time.
  if (b.cut && u < 1.0f) u = 0.0f;
  // Neighbours for the spline; a cut on either side ends the segment's smoothness there.
  const CameraKeyframe& before = (i > 0 && !a.cut) ? keys[i - 1] : a;
  const CameraKeyframe& after = (i + 2 < keys.size() && !keys[i + 2].cut) ? keys[i + 2] : b;
  if (path.catmullRom) {
    camera.position = catmullRom(before.position, a.position, b.position, after.position, u);
    camera.target = catmullRom(before.target, a.target, b.target, after.target, u);
  } else {
    camera.position = glm::mix(a.position, b.position, u);
    camera.target = glm::mix(a.target, b.target, u);
  }
  camera.verticalFovDegrees = glm::mix(a.verticalFovDegrees, b.verticalFovDegrees, u);
  return camera;
}

bool cameraCutBetween(const CameraPath& path, float t0, float t1) {
  if (path.keys.empty() || !(t1 > t0)) return false;
  float d = path.duration();
  bool wrapped = false;
  if (path.loop && d > 0.0f) {
    wrapped = std::floor(t0 / d) != std::floor(t1 / d);
    const CameraKeyframe &first = path.keys.front(), &last = path.keys.back();
    // Crossing the loop point jumps from the last key's view to the first key's.
    if (wrapped && (first.cut || first.position != last.position || first.target != last.target))
      return true;
    t0 = wrap(t0, d);
    t1 = wrap(t1, d);
  }
  for (const CameraKeyframe& k : path.keys) {
    bool crossed = wrapped ? (k.time > t0 || k.time <= t1) : (k.time > t0 && k.time <= t1);
    if (k.cut && crossed) return true;
  }
  return false;
}

void validateCameraPath(const CameraPath& path, const std::string& source) {
  if (path.keys.empty())
    fail("{}: \"keyframes\" is empty; a camera path needs at least one", source);
  for (size_t i = 0; i < path.keys.size(); ++i) {
    const CameraKeyframe& k = path.keys[i];
    if (!std::isfinite(k.time)) fail("{}: keyframes[{}].time is not finite", source, i);
    if (i > 0 && !(k.time > path.keys[i - 1].time))
      fail("{}: keyframes[{}].time {} does not increase (keyframes[{}].time is {})", source, i,
           k.time, i - 1, path.keys[i - 1].time);
    if (!(k.verticalFovDegrees > 0.0f && k.verticalFovDegrees < 180.0f))
      fail("{}: keyframes[{}].vfov {} is outside (0, 180) degrees", source, i,
           k.verticalFovDegrees);
    if (!finite(k.position) || !finite(k.target))
      fail("{}: keyframes[{}] has a non-finite position or target", source, i);
    if (k.position == k.target)
      fail("{}: keyframes[{}].position equals its target (no view direction)", source, i);
  }
}

CameraPath parseCameraPathJson(const std::string& text, const std::string& source) {
  using nlohmann::json;
  json doc;
  try {
    doc = json::parse(text);
  } catch (const json::parse_error& e) {
    fail("{}: not valid JSON: {}", source, e.what());
  }
  if (!doc.is_object()) fail("{}: expected a JSON object with \"keyframes\"", source);
  if (!doc.contains("keyframes")) fail("{}: missing field \"keyframes\"", source);
  const json& keys = doc["keyframes"];
  if (!keys.is_array()) fail("{}: \"keyframes\" must be an array", source);
  auto number = [&](const json& k, size_t i, const char* field) -> float {
    if (!k.contains(field)) fail("{}: keyframes[{}]: missing field \"{}\"", source, i, field);
    if (!k[field].is_number()) fail("{}: keyframes[{}].{} must be a number", source, i, field);
    return k[field].get<float>();
  };
  auto vec3 = [&](const json& k, size_t i, const char* field) -> glm::vec3 {
    if (!k.contains(field)) fail("{}: keyframes[{}]: missing field \"{}\"", source, i, field);
    const json& v = k[field];
    if (!v.is_array() || v.size() != 3 || !v[0].is_number() || !v[1].is_number() ||
        !v[2].is_number())
      fail("{}: keyframes[{}].{} must be an array of 3 numbers [x, y, z]", source, i, field);
    return {v[0].get<float>(), v[1].get<float>(), v[2].get<float>()};
  };
  CameraPath path;
  for (size_t i = 0; i < keys.size(); ++i) {
    const json& k = keys[i];
    if (!k.is_object()) fail("{}: keyframes[{}] must be an object", source, i);
    CameraKeyframe key;
    key.time = number(k, i, "time");
    key.position = vec3(k, i, "position");
    key.target = vec3(k, i, "target");
    key.verticalFovDegrees = k.contains("vfov") ? number(k, i, "vfov") : 45.0f;
    if (k.contains("cut")) {
      if (!k["cut"].is_boolean()) fail("{}: keyframes[{}].cut must be true or false", source, i);
      key.cut = k["cut"].get<bool>();
    }
    path.keys.push_back(key);
  }
  if (doc.contains("loop")) {
    if (!doc["loop"].is_boolean()) fail("{}: \"loop\" must be true or false", source);
    path.loop = doc["loop"].get<bool>();
  }
  if (doc.contains("interpolation")) {
    const json& v = doc["interpolation"];
    if (v == "catmull-rom")
      path.catmullRom = true;
    else if (v == "linear")
      path.catmullRom = false;
    else
      fail("{}: \"interpolation\" must be \"catmull-rom\" or \"linear\"", source);
  }
  validateCameraPath(path, source);
  return path;
}

CameraPath loadCameraPath(const std::string& path) {
  std::ifstream f(path);
  if (!f) fail("{}: cannot read the camera path file", path);
  std::stringstream text;
  text << f.rdbuf();
  return parseCameraPathJson(text.str(), path);
}

CameraPath swayCameraPath(const Camera& camera, float degrees, float dolly, float seconds) {
  CameraPath path;
  path.loop = true;
  glm::vec3 offset = camera.position - camera.target;
  // Keys back at the start at the end: a closed loop, so wrapping is smooth and no cut.
  const float yaws[] = {0.0f, degrees, 0.0f, -degrees, 0.0f};
  const float distances[] = {1.0f, 1.0f - 0.5f * dolly, 1.0f - dolly, 1.0f - 0.5f * dolly, 1.0f};
  for (int i = 0; i < 5; ++i) {
    glm::mat4 r = glm::rotate(glm::mat4(1.0f), glm::radians(yaws[i]), glm::vec3(0, 1, 0));
    CameraKeyframe k;
    k.time = seconds * float(i) / 4.0f;
    k.position = camera.target + distances[i] * glm::vec3(r * glm::vec4(offset, 0.0f));
    k.target = camera.target;
    k.verticalFovDegrees = camera.verticalFovDegrees;
    path.keys.push_back(k);
  }
  return path;
}

}  // namespace bounce
