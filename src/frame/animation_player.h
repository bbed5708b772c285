// Plays a SceneAnimation on a HybridFrame: at each frame's time t it evaluates the
// instance transforms, the deforming meshes' pose, the time of day and the camera path, hands them
// to the frame and resets temporal history at camera cuts, so no stale history shows after a jump.
//
//   AnimationPlayer player(scene, scene.animation);
//   for (uint32_t i = 0; i < frames; ++i) frame.render(player.apply(frame, i / fps));
#pragma once
#include <optional>
#include <vector>

#include "frame/hybrid_frame.h"
#include "scene/animation.h"
#include "scene/deformation.h"
#include "scene/scene.h"

namespace bounce {

class AnimationPlayer {
 public:
  // `scene` gives the rest placement, the daylight sun and sky, and the camera used where the
  // animation has no camera path; it must outlive the player.
  AnimationPlayer(const Scene& scene, SceneAnimation animation);

  // Sets the frame's time (HybridFrame::setTime), instances, lights and sun for time t, resets its
  // history at a cut, and returns the camera to render with. Times must not decrease between
  // calls.
  Camera apply(HybridFrame& frame, float t);
  // Whether the last apply() reset history (a cut: a path key marked cut, or a jump of the
  // camera by more than kCutJumpFraction of its distance to its target in one frame).
  bool lastWasCut() const { return lastWasCut_; }

  static constexpr float kCutJumpFraction = 0.5f;

 private:
  const Scene& scene_;
  SceneAnimation animation_;
  std::vector<glm::mat4> transforms_;
  std::vector<PunctualLight> lights_;
  DeformationPose pose_;
  std::optional<float> lastTime_;
  std::optional<Camera> lastCamera_;
  bool lastWasCut_ = false;
};

}  // namespace bounce
