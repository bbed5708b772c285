// Time-varying scene state: per-instance transform tracks, a
// camera path and a time-of-day track, evaluated at a time t in seconds. Evaluation allocates
// nothing on the GPU side: the renderer uploads the evaluated transforms into buffers it made
// at init (rt/gpu_scene.h, GpuScene::setInstanceTransforms).
//
// Transform tracks follow glTF animation semantics (glTF 2.0 §3.11): each of translation,
// rotation (unit quaternion, slerp) and scale is a separate channel of keyframes; a missing
// channel keeps the instance's rest value; LINEAR or STEP interpolation; outside the key range
// the end values hold. Looping wraps t into the animation's [0, duration) instead.
#pragma once
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

namespace bounce {

struct Camera;
struct PunctualLight;
struct Sun;

enum class Interpolation { Linear, Step };

template <typename T>
struct Channel {
  std::vector<float> times;  // seconds, strictly increasing
  std::vector<T> values;     // one per time
  Interpolation interpolation = Interpolation::Linear;
  bool empty() const { return times.empty(); }
};

struct TransformTrack {
  uint32_t instance = 0;
  // Rest pose: the value of a channel that has no keys (from the node or the instance).
  glm::vec3 restTranslation{0.0f};
  glm::quat restRotation{1.0f, 0.0f, 0.0f, 0.0f};
  glm::vec3 restScale{1.0f};
  // Where the instance hangs: with `parentNode` >= 0 under a node of Scene::skeleton, world =
  // skeletonWorld[parentNode](t) x TRS(t), so the instance follows its animated ancestors (a
  // glTF mesh node under an animated empty or a skin joint: the sword in the hand bone). With
  // -1, world = parent x TRS(t), `parent` a static transform. `parent` also holds the rest
  // parent-to-world of a tracked node, which stands in when the caller evaluates without the
  // skeleton's world matrices (evaluateTransforms with an empty span).
  int parentNode = -1;
  glm::mat4 parent{1.0f};
  Channel<glm::vec3> translation;
  Channel<glm::quat> rotation;
  Channel<glm::vec3> scale;
};

// An animated node of the skeleton (Scene::skeleton[node]): its local TRS at t replaces the
// node's rest `local`. `trs.instance` is unused and `trs.parent` stays the identity (the parent
// is the skeleton's).
struct JointTrack {
  uint32_t node = 0;
  TransformTrack trs;
};

// glTF `weights` channel of a morphed mesh (Scene::meshes[mesh]): one weight per morph target at
// each key, key-major (values[key * targets + target]). LINEAR or STEP as transform channels.
struct MorphWeightTrack {
  uint32_t mesh = 0;
  uint32_t targets = 0;
  std::vector<float> times;  // seconds, strictly increasing
  std::vector<float> values;
  Interpolation interpolation = Interpolation::Linear;
};

// A KHR punctual light's animation (Scene::lights[light]): its position in world space and a
// factor on its rest intensity (STEP keys of 0 and 1 switch it off and on). A missing channel
// keeps the rest value. Light tracks loop with the transform tracks (SceneAnimation::loop), at
// the end of their own last key.
struct LightTrack {
  uint32_t light = 0;
  Channel<glm::vec3> position;
  Channel<float> intensityScale;
};

struct CameraKeyframe {
  float time = 0.0f;
  glm::vec3 position{0.0f};
  glm::vec3 target{0.0f, 0.0f, -1.0f};
  float verticalFovDegrees = 45.0f;
  // The view jumps here: no interpolation from the previous key, and temporal history is reset
  // when playback crosses this key.
  bool cut = false;
};

// A camera path through keyframes: Catmull-Rom (uniform in key index: the slow, evenly keyed
// paths this serves need no centripetal parametrisation) so the motion has no kinks, or linear.
struct CameraPath {
  std::vector<CameraKeyframe> keys;  // times strictly increasing
  bool loop = false;
  bool catmullRom = true;  // smooth through the keys; else piecewise linear
  float duration() const { return keys.empty() ? 0.0f : keys.back().time; }
};

// The sun follows the time of day (scene/time_of_day.h): `hours` at t = 0, advancing by 24 h
// every `dayCycleSeconds` (0 = a fixed time).
struct TimeOfDayTrack {
  float hours = 12.0f;
  float dayCycleSeconds = 0.0f;
  float hoursAt(float t) const;
};

struct SceneAnimation {
  std::vector<TransformTrack> transforms;
  // Deformation (scene/deformation.h): they play and loop with the transform tracks.
  std::vector<JointTrack> joints;
  std::vector<MorphWeightTrack> morphWeights;
  std::vector<LightTrack> lights;
  std::optional<CameraPath> camera;
  std::optional<TimeOfDayTrack> timeOfDay;
  bool loop = true;  // transform tracks wrap at duration()

  bool empty() const {
    return transforms.empty() && joints.empty() && morphWeights.empty() && lights.empty() &&
           !camera && !timeOfDay;
  }
  // The end of the last transform, joint or morph-weight key (0 without such tracks).
  float transformDuration() const;
  // The end of the last light key (0 without light tracks).
  float lightDuration() const;
};

// Evaluates one channel at t (glTF rules above; rotations slerp along the shorter arc).
glm::vec3 sampleChannel(const Channel<glm::vec3>& channel, float t, const glm::vec3& rest);
glm::quat sampleChannel(const Channel<glm::quat>& channel, float t, const glm::quat& rest);
float sampleChannel(const Channel<float>& channel, float t, float rest);
// parent x T x R x S at t (`parentNode` is not looked at: the static `parent`).
glm::mat4 evaluateTrack(const TransformTrack& track, float t);
// Writes the object-to-world transform of every instance at time t into `transforms` (sized to
// the scene's instance count by the caller; untracked instances keep their value).
// `skeletonWorld` is DeformationPose::skeletonWorld at the same t (evaluatePose), for the tracks
// with a `parentNode`; it may be empty when no track has one (a track whose parentNode is
// outside it hangs under its static `parent`, the rest pose of its ancestors).
void evaluateTransforms(const SceneAnimation& animation, float t,
                        std::span<const glm::mat4> skeletonWorld,
                        std::vector<glm::mat4>& transforms);
// Whether some transform track hangs under a skeleton node (parentNode >= 0): evaluateTransforms
// then needs the pose's skeletonWorld.
bool transformsNeedSkeleton(const SceneAnimation& animation);

// Writes the local transform of every animated skeleton node at time t into `locals` (one per
// Scene::skeleton node, the rest `local`s, made by the caller; unanimated nodes keep theirs).
void evaluateJoints(const SceneAnimation& animation, float t, std::vector<glm::mat4>& locals);
// Writes every animated mesh's morph weights at time t into `weights` (one vector per mesh, the
// rest weights, made by the caller; a track whose target count differs from its mesh's vector
// is skipped; validateDeformation reports it).
void evaluateMorphWeights(const SceneAnimation& animation, float t,
                          std::vector<std::vector<float>>& weights);

// Writes the state of every animated light at time t into `lights` (a copy of Scene::lights,
// the rest state, made by the caller; untracked lights keep their value). `rest` is
// Scene::lights, whose intensities the tracks scale.
void evaluateLights(const SceneAnimation& animation, float t,
                    const std::vector<PunctualLight>& rest, std::vector<PunctualLight>& lights);

// The camera on the path at t (looping paths wrap at duration()). `up` is +Y.
Camera evaluateCameraPath(const CameraPath& path, float t);
// True when playback from t0 to t1 (t0 < t1) crosses a key marked `cut`, or wraps a looping
// path whose end and start differ by a jump (a cut by construction).
bool cameraCutBetween(const CameraPath& path, float t0, float t1);

// Checks keys (at least one, times finite and strictly increasing, fov in (0, 180), position
// != target). Throws bounce::Error naming `source` and the offending key and field.
void validateCameraPath(const CameraPath& path, const std::string& source);
// Reads {"keyframes":[{"time":0,"position":[x,y,z],"target":[x,y,z],"vfov":45,"cut":false},
// ...], "loop": true, "interpolation": "catmull-rom"|"linear"}. Throws bounce::Error naming the
// file and the field for unreadable files, bad JSON, missing or mistyped fields.
CameraPath loadCameraPath(const std::string& path);
CameraPath parseCameraPathJson(const std::string& text, const std::string& source);

// A slow sway of the camera around the point it looks at: +-`degrees` of yaw while dollying in
// by up to `dolly` (a fraction of the distance to the target) and back, over `seconds`,
// looping. Moving towards the target keeps an interior camera inside its room, where a pure
// orbit would pass through walls. The default camera motion of built-in scenes (--animate).
CameraPath swayCameraPath(const Camera& camera, float degrees, float dolly, float seconds);

}  // namespace bounce
