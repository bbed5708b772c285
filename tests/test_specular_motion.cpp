// Specular shading in motion (issue 19, docs/reflections.md): the whole frame (composite) over
// `sunroom-glossy`'s lacquered floor, desktop preset, ReSTIR GI and traced reflections.
//   - no ghost trail: after a glossy steel ball rolls over the floor and stops, or after the
//     camera dollies over the floor and stops, each frame's error against the static converged
//     image of the final view must be back within 1.5x of the static error within 8 frames.
//     The converged image and the static error come from a run that starts at the final state.
//     Every temporal history of the frame (shadows, GI, the reflection denoiser when it lands)
//     is in the chain, so stale history anywhere shows. Each run also checks that its metric
//     sees a ghost: the same frames with 15 % of a frame from the middle of the motion blended
//     in must fail the bound;
//   - 1,000 animated frames (the ball, the cube, the swinging panel, a moving camera and sun)
//     stay finite with the validation layers silent.
#include <cmath>
#include <cstdio>
#include <functional>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "frame/hybrid_frame.h"
#include "frame/presets.h"
#include "rt/gpu_scene.h"
#include "scene/animation.h"
#include "scene/load.h"
#include "scene/scene_options.h"
#include "tools/image_io.h"
#include "tools/metrics.h"
#include "vk/context.h"

namespace bounce {
namespace {

constexpr uint32_t kWidth = 64, kHeight = 36;
// The static run: frames 1-32 build every history, frames 17-32 average into the converged
// image.
constexpr int kWarmFrames = 16, kConvergedFrames = 16;
// The moving run: at rest at the start state, then the motion, then 8 frames at the final state
// (frames 33-40, as the static run's error frames).
constexpr int kRestFrames = 16, kMotionFrames = 16, kSettleFrames = 8;
// Issue 19: within 1.5x of the static error within 8 frames after the motion stops.
constexpr double kGhostBound = 1.5;
// The self-check's ghost: this fraction of a frame from the middle of the motion, blended into
// the frames after it (what a history that keeps 15 % of stale light looks like).
constexpr float kProbeGhostWeight = 0.15f;

HybridSettings motionSettings() {
  HybridSettings settings = presetSettings(Preset::Desktop);
  settings.width = kWidth;
  settings.height = kHeight;
  settings.gi = GiMode::Evolve;
  EXPECT_EQ(settings.reflections.divisor, 2u);
  return settings;
}

uint32_t instanceNamed(const Scene& scene, const std::string& name) {
  for (uint32_t i = 0; i < scene.instances.size(); ++i)
    if (scene.instances[i].name == name) return i;
  ADD_FAILURE() << "no instance " << name;
  return 0;
}

// What changes over a run: the state at s in [0, 1] (0 start, 1 final) is applied to the frame
// and gives the camera.
using StateAt = std::function<Camera(HybridFrame& frame, float s)>;

// A ghost trail is light in the wrong place over many pixels; a frame's noise (one reflection
// and GI sample per pixel) is pixel to pixel. The error is relMSE after a 4 x 4 box filter, so
// that it measures the first and not the second.
constexpr int kErrorBlock = 4;

ImageRGBA32F boxFiltered(const ImageRGBA32F& image) {
  ImageRGBA32F out(image.width / kErrorBlock, image.height / kErrorBlock, glm::vec4(0.0f));
  for (int y = 0; y < out.height * kErrorBlock; ++y)
    for (int x = 0; x < out.width * kErrorBlock; ++x) {
      glm::vec4 sum = out.at(x / kErrorBlock, y / kErrorBlock) +
                      image.at(x, y) / float(kErrorBlock * kErrorBlock);
      out.set(x / kErrorBlock, y / kErrorBlock, sum);
    }
  return out;
}

double ghostError(const ImageRGBA32F& frame, const ImageRGBA32F& converged) {
  return relativeMeanSquaredError(boxFiltered(frame), boxFiltered(converged));
}

ImageRGBA32F blend(const ImageRGBA32F& a, const ImageRGBA32F& b, float weightOfB) {
  ImageRGBA32F out = a;
  for (size_t k = 0; k < out.pixels.size(); ++k)
    out.pixels[k] = (1.0f - weightOfB) * a.pixels[k] + weightOfB * b.pixels[k];
  return out;
}

struct GhostRun {
  double staticError = 0.0;  // mean relMSE of static frames 33-40 against the converged image
  std::vector<double> settleErrors;  // relMSE of each frame after the motion stops
  std::vector<double> probeErrors;   // the same with the probe ghost blended in
};

GhostRun runGhostTest(const Scene& scene, const StateAt& stateAt) {
  vk::Context context(vk::contextOptionsFromEnvironment());
  GpuScene gpuScene(context, scene);
  GhostRun run;

  // The static run at the final state: frames 17-32 average into the converged image, frames
  // 33-40 (the history age of the moving run's frames after the stop) give the static error.
  // Their history carries samples of the converged frames, which makes the static error, and
  // so the bound, smaller than an independent run's would be: the test errs on the strict side.
  ImageRGBA32F converged(kWidth, kHeight, glm::vec4(0.0f));
  {
    HybridFrame frame(context, gpuScene, scene, motionSettings());
    frame.requestDebugView("composite");
    for (int i = 0; i < kWarmFrames + kConvergedFrames + kSettleFrames; ++i) {
      frame.render(stateAt(frame, 1.0f));
      if (i < kWarmFrames) continue;
      ImageRGBA32F composite = frame.debugViewImage("composite");
      EXPECT_EQ(countNonFinitePixels(composite), 0u);
      if (i < kWarmFrames + kConvergedFrames) {
        for (size_t k = 0; k < converged.pixels.size(); ++k)
          converged.pixels[k] += composite.pixels[k] / float(kConvergedFrames);
      } else {
        run.staticError += ghostError(composite, converged) / double(kSettleFrames);
      }
    }
  }

  // The moving run: rest at the start, move, stop at the final state.
  {
    HybridFrame frame(context, gpuScene, scene, motionSettings());
    frame.requestDebugView("composite");
    ImageRGBA32F midMotion;
    for (int i = 0; i < kRestFrames + kMotionFrames + kSettleFrames; ++i) {
      const int moving = i - kRestFrames;
      const float s = std::clamp(float(moving + 1) / float(kMotionFrames), 0.0f, 1.0f);
      frame.render(stateAt(frame, s));
      ImageRGBA32F composite = frame.debugViewImage("composite");
      EXPECT_EQ(countNonFinitePixels(composite), 0u);
      if (moving == kMotionFrames / 2) midMotion = composite;
      if (moving < kMotionFrames) continue;
      run.settleErrors.push_back(ghostError(composite, converged));
      run.probeErrors.push_back(
          ghostError(blend(composite, midMotion, kProbeGhostWeight), converged));
      if (const char* dir = std::getenv("BOUNCE_TEST_IMAGES"))
        writeImage(
            fmt::format("{}/ghost-{}-settle-{}.exr", dir, scene.name, moving - kMotionFrames),
            composite);
    }
    if (const char* dir = std::getenv("BOUNCE_TEST_IMAGES"))
      writeImage(fmt::format("{}/ghost-{}-converged.exr", dir, scene.name), converged);
  }
  EXPECT_EQ(context.validationErrorCount(), 0u);
  std::printf("static error %.4f; after the motion stops:", run.staticError);
  for (size_t k = 0; k < run.settleErrors.size(); ++k)
    std::printf(" %.4f (%.2fx; probe %.2fx)", run.settleErrors[k],
                run.settleErrors[k] / run.staticError, run.probeErrors[k] / run.staticError);
  std::printf("\n");
  return run;
}

// The bound: the last frame of the 8 after the stop within 1.5x the static error; and the
// metric must see the probe ghost in that frame.
void expectNoGhost(const GhostRun& run) {
  ASSERT_EQ(run.settleErrors.size(), size_t(kSettleFrames));
  ASSERT_GT(run.staticError, 0.0);
  EXPECT_LE(run.settleErrors.back(), kGhostBound * run.staticError);
  EXPECT_GT(run.probeErrors.back(), kGhostBound * run.staticError)
      << "the metric does not see a " << kProbeGhostWeight << " ghost";
}

// The steel ball rolls 1.2 m across the lacquered floor (through the sun patch) in 16 frames
// and stops: its reflection in the floor, its shadow and its own reflections move with it.
// Disabled until reflections-denoise lands and the numbers are understood: today the frames after
// the stop stay at 1.9-2.5x the static error for all 8 frames (docs/reflections.md, "Motion").
TEST(SpecularMotion, DISABLED_MovingGlossyBallLeavesNoGhostTrail) {
  Scene scene = *makeBuiltinScene("sunroom-glossy");
  const uint32_t ball = instanceNamed(scene, "ball_steel");
  std::vector<glm::mat4> transforms;
  for (const Instance& instance : scene.instances) transforms.push_back(instance.transform);
  const glm::mat4 start = transforms[ball];
  const Camera camera = *scene.camera;
  StateAt stateAt = [&](HybridFrame& frame, float s) {
    transforms[ball] = glm::translate(glm::mat4(1.0f), glm::vec3(1.2f * s, 0.0f, 0.0f)) * start;
    frame.setInstanceTransforms(transforms);
    return camera;
  };
  expectNoGhost(runGhostTest(scene, stateAt));
}

// The camera dollies 1 m towards its target, low over the lacquered floor, in 16 frames and
// stops: every reflection on the floor moves across the screen with the view.
// Disabled until reflections-denoise lands and the numbers are understood: today the error after
// the stop is 6-17x the static error and grows over the 8 frames (docs/reflections.md, "Motion").
TEST(SpecularMotion, DISABLED_CameraDollyOverGlossyFloorLeavesNoGhostTrail) {
  Scene scene = *makeBuiltinScene("sunroom-glossy");
  const Camera start = *scene.camera;
  const glm::vec3 forward = glm::normalize(start.target - start.position);
  StateAt stateAt = [&](HybridFrame&, float s) {
    Camera camera = start;
    camera.position += forward * s;
    return camera;
  };
  expectNoGhost(runGhostTest(scene, stateAt));
}

// 1,000 frames of sunroom-glossy's animation (the ball, the cube, the panel, the camera sway and
// dolly) under a sun that circles the sky, with reflections traced: the composite and the
// reflection signal stay finite, and the validation layers stay silent. 48 x 27; the cache at
// one candidate ray and no validation ray per cell and frame (its cells, not the pixels, set
// the time on lavapipe; RestirGi.LongAnimatedRunStaysFinite covers the validation rays).
TEST(SpecularMotion, ThousandAnimatedFramesStayFinite) {
  Scene scene = *makeBuiltinScene("sunroom-glossy");
  vk::ContextOptions options = vk::contextOptionsFromEnvironment();
  options.validation = true;
  vk::Context context(options);
  GpuScene gpuScene(context, scene);
  HybridSettings settings = motionSettings();
  settings.width = 48;
  settings.height = 27;
  settings.cache.raysPerCell = 1;
  settings.cache.validationRaysPerCell = 0;
  HybridFrame frame(context, gpuScene, scene, settings);
  frame.requestDebugView("composite");
  frame.requestDebugView("reflections-upsample");
  ASSERT_TRUE(scene.animation.camera.has_value());
  std::vector<glm::mat4> transforms;
  for (const Instance& instance : scene.instances) transforms.push_back(instance.transform);
  size_t nonFinite = 0;
  for (int i = 0; i < 1000; ++i) {
    const float t = float(i) / 30.0f;
    evaluateTransforms(scene.animation, t, transforms);
    frame.setInstanceTransforms(transforms);
    Sun sun = scene.sun;
    const float a = 0.5f * t;
    sun.direction = glm::normalize(glm::vec3(std::cos(a), -0.6f, std::sin(a)));
    frame.setSunAndSky(sun, scene.sky);
    frame.render(evaluateCameraPath(*scene.animation.camera, t));
    if (i % 8 == 7) {
      nonFinite += countNonFinitePixels(frame.debugViewImage("composite"));
      nonFinite += countNonFinitePixels(frame.debugViewImage("reflections-upsample"));
    }
  }
  EXPECT_EQ(nonFinite, 0u);
  EXPECT_EQ(context.validationErrorCount(), 0u);
}

}  // namespace
}  // namespace bounce
