#include "frame/animation_player.h"

#include "scene/scene_options.h"
#include "scene/time_of_day.h"

namespace bounce {

AnimationPlayer::AnimationPlayer(const Scene& scene, SceneAnimation animation)
    : scene_(scene), animation_(std::move(animation)) {
  transforms_.reserve(scene.instances.size());
  for (const Instance& instance : scene.instances) transforms_.push_back(instance.transform);
  lights_ = scene.lights;
}

Camera AnimationPlayer::apply(HybridFrame& frame, float t) {
  frame.setTime(t);
  bool deformationTracks = !animation_.joints.empty() || !animation_.morphWeights.empty();
  // Instances under animated skeleton nodes need the pose as much as the deforming meshes.
  bool needsPose = deformationTracks || transformsNeedSkeleton(animation_);
  if (needsPose) evaluatePose(scene_, animation_, t, pose_);
  if (!animation_.transforms.empty()) {
    // pose_ stays empty (never evaluated) when no track needs it.
    evaluateTransforms(animation_, t, pose_.skeletonWorld, transforms_);
    frame.setInstanceTransforms(transforms_);
  }
  // Joint tracks of a scene where nothing deforms only move the skeleton that instances hang
  // under; the GPU has no deformer to hand the pose to then.
  if (deformationTracks && scene_.deforms()) frame.setDeformation(pose_);
  if (!animation_.lights.empty()) {
    evaluateLights(animation_, t, scene_.lights, lights_);
    frame.setLights(lights_);
  }
  if (animation_.timeOfDay) {
    Sun sun;
    Sky sky;
    applyTimeOfDay(animation_.timeOfDay->hoursAt(t), scene_.sun, scene_.sky, sun, sky);
    frame.setSunAndSky(sun, sky);
  }
  Camera camera =
      animation_.camera ? evaluateCameraPath(*animation_.camera, t) : effectiveCamera(scene_);
  lastWasCut_ = false;
  if (lastTime_ && lastCamera_) {
    bool pathCut = animation_.camera && cameraCutBetween(*animation_.camera, *lastTime_, t);
    float reach = glm::length(lastCamera_->position - lastCamera_->target);
    bool jump = glm::length(camera.position - lastCamera_->position) > kCutJumpFraction * reach;
    if (pathCut || jump) {
      frame.resetHistory();
      lastWasCut_ = true;
    }
  }
  lastTime_ = t;
  lastCamera_ = camera;
  return camera;
}

}  // namespace bounce
