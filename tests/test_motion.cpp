// Motion and time on lavapipe at small resolutions:
//   - animation math: slerp along the shorter arc, STEP keys, looping, Catmull-Rom through keys;
//   - reprojection: last frame's composite, fetched where this frame's velocity points, matches
//     this frame's composite on every pixel that is not disoccluded (static scene, moving
//     camera, a hard-shadowed sun so both frames are deterministic);
//   - a moving object's velocity is its analytic screen motion;
//   - 100 animated frames allocate nothing after frame 3; 20 animated frames of every built-in
//     scene at both presets' settings leave the validation layers (synchronization included)
//     silent;
//   - a camera cut resets history (shadow frame count back to 1), no NaN, no black frame;
//   - camera-path JSON errors name the file and the field;
//   - the sun is up at noon and down at midnight; the night frame is finite, not black, darker.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/packing.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "core/error.h"
#include "floor_and_card.h"
#include "frame/animation_player.h"
#include "frame/hybrid_frame.h"
#include "frame/presets.h"
#include "frame_texels.h"
#include "harness.h"
#include "passes/primary_view.h"
#include "rt/gpu_scene.h"
#include "scene/animation.h"
#include "scene/load.h"
#include "scene/scene_options.h"
#include "scene/time_of_day.h"
#include "shared/camera.h"
#include "vk/context.h"

namespace bounce {
namespace {

using test::texels;

float luminance(const glm::vec4& c) {
  return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z;
}

std::string errorOf(const std::string& json) {
  try {
    parseCameraPathJson(json, "paths/test.json");
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

// ---- animation math ---------------------------------------------------------------------------

TEST(Animation, ChannelsInterpolateLikeGltf) {
  Channel<glm::quat> r;
  r.times = {0.0f, 1.0f};
  glm::quat a = glm::angleAxis(glm::radians(10.0f), glm::vec3(0, 1, 0));
  glm::quat b =
      -glm::angleAxis(glm::radians(50.0f), glm::vec3(0, 1, 0));  // same rotation, far sign
  r.values = {a, b};
  glm::quat mid = sampleChannel(r, 0.5f, glm::quat(1, 0, 0, 0));
  // The shorter arc: 30 degrees about +Y, not a turn through the other side.
  EXPECT_NEAR(std::abs(glm::dot(mid, glm::angleAxis(glm::radians(30.0f), glm::vec3(0, 1, 0)))),
              1.0f, 1e-5f);

  Channel<glm::vec3> t;
  t.times = {1.0f, 2.0f};
  t.values = {glm::vec3(0.0f), glm::vec3(2.0f)};
  EXPECT_EQ(sampleChannel(t, 0.0f, glm::vec3(9.0f)), glm::vec3(0.0f));  // holds before the keys
  EXPECT_EQ(sampleChannel(t, 1.25f, glm::vec3(9.0f)), glm::vec3(0.5f));
  EXPECT_EQ(sampleChannel(t, 5.0f, glm::vec3(9.0f)), glm::vec3(2.0f));  // and after
  t.interpolation = Interpolation::Step;
  EXPECT_EQ(sampleChannel(t, 1.9f, glm::vec3(9.0f)), glm::vec3(0.0f));

  SceneAnimation animation;
  TransformTrack track;
  track.translation = {{0.0f, 2.0f}, {glm::vec3(0.0f), glm::vec3(4.0f, 0.0f, 0.0f)}};
  animation.transforms.push_back(track);
  std::vector<glm::mat4> transforms(1);
  evaluateTransforms(animation, 2.5f, {}, transforms);  // loops: 2.5 s -> 0.5 s
  EXPECT_NEAR(transforms[0][3].x, 1.0f, 1e-6f);
}

TEST(Animation, CameraPathPassesThroughItsKeysAndCuts) {
  CameraPath path = parseCameraPathJson(R"({"keyframes": [
      {"time": 0, "position": [0, 0, 5], "target": [0, 0, 0], "vfov": 40},
      {"time": 1, "position": [1, 0, 5], "target": [0, 0, 0], "vfov": 50},
      {"time": 2, "position": [2, 1, 5], "target": [0, 0, 0]},
      {"time": 3, "position": [9, 9, 9], "target": [0, 0, 0], "cut": true}]})",
                                        "inline");
  Camera c = evaluateCameraPath(path, 1.0f);
  EXPECT_NEAR(glm::length(c.position - glm::vec3(1, 0, 5)), 0.0f, 1e-5f);
  EXPECT_FLOAT_EQ(c.verticalFovDegrees, 50.0f);
  EXPECT_FLOAT_EQ(evaluateCameraPath(path, 0.5f).verticalFovDegrees, 45.0f);
  // Up to a cut key the view holds the previous key, then jumps.
  EXPECT_NEAR(glm::length(evaluateCameraPath(path, 2.9f).position - glm::vec3(2, 1, 5)), 0.0f,
              1e-5f);
  EXPECT_FALSE(cameraCutBetween(path, 0.0f, 2.9f));
  EXPECT_TRUE(cameraCutBetween(path, 2.9f, 3.0f));
}

TEST(Animation, CameraPathJsonErrorsNameFileAndField) {
  std::string bad = errorOf("{\"keyframes\": [");
  EXPECT_NE(bad.find("paths/test.json"), std::string::npos) << bad;
  EXPECT_NE(bad.find("not valid JSON"), std::string::npos) << bad;

  std::string missing = errorOf(R"({"keyframes": [{"time": 0, "target": [0, 0, 0]}]})");
  EXPECT_NE(missing.find("paths/test.json"), std::string::npos) << missing;
  EXPECT_NE(missing.find("keyframes[0]"), std::string::npos) << missing;
  EXPECT_NE(missing.find("\"position\""), std::string::npos) << missing;

  std::string order = errorOf(R"({"keyframes": [
      {"time": 1, "position": [0, 0, 5], "target": [0, 0, 0]},
      {"time": 1, "position": [1, 0, 5], "target": [0, 0, 0]}]})");
  EXPECT_NE(order.find("keyframes[1].time"), std::string::npos) << order;
  EXPECT_NE(order.find("does not increase"), std::string::npos) << order;

  std::string shape =
      errorOf(R"({"keyframes": [{"time": 0, "position": [0, 5], "target": [0, 0, 0]}]})");
  EXPECT_NE(shape.find("keyframes[0].position must be an array of 3 numbers"), std::string::npos)
      << shape;
  EXPECT_NE(errorOf(R"({"frames": []})").find("missing field \"keyframes\""), std::string::npos);

  try {
    loadCameraPath("/nonexistent/path.json");
    FAIL() << "no error for a missing file";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/path.json"), std::string::npos);
  }
}

TEST(Animation, RenderVerbReportsCameraPathErrorsAndPlaysAnimations) {
  std::string dir = test::tempDir("motion-cli");
  std::string bad = dir + "/bad_path.json";
  std::ofstream(bad) << R"({"keyframes": [{"time": 0, "position": [0, 1, 5]}]})";
  test::CommandResult r =
      test::runCommand(test::bounceExe() + " render --res 16x8 --camera-path '" + bad +
                       "' --out '" + dir + "/bad.png'");
  EXPECT_EQ(r.exitCode, 1) << r.output;
  EXPECT_NE(r.output.find("bad_path.json: keyframes[0]: missing field \"target\""),
            std::string::npos)
      << r.output;
  r = test::runCommand(test::bounceExe() + " render --res 32x16 --animate --frames 4 --fps 2 " +
                       "--day-cycle 8 --time-of-day 17 --out '" + dir + "/frames/'");
  EXPECT_EQ(r.exitCode, 0) << r.output;
  EXPECT_TRUE(std::filesystem::exists(dir + "/frames/frame_0003.png")) << r.output;
  r = test::runCommand(test::bounceExe() + " render --res 16x8 --time-of-day 25 --out '" + dir +
                       "/x.png'");
  EXPECT_EQ(r.exitCode, 1) << r.output;
  EXPECT_NE(r.output.find("--time-of-day 25"), std::string::npos) << r.output;
}

TEST(Animation, SunIsUpAtNoonAndDownAtMidnight) {
  EXPECT_NEAR(sunElevationDegrees(12.0f), 45.0f, 1e-3f);  // 45 N at an equinox
  EXPECT_NEAR(sunElevationDegrees(0.0f), -45.0f, 1e-3f);
  EXPECT_NEAR(sunElevationDegrees(6.0f), 0.0f, 1e-3f);
  EXPECT_GT(towardSunAt(9.0f).x, 0.0f);   // morning sun in the east (+X)
  EXPECT_GT(towardSunAt(12.0f).z, 0.0f);  // noon sun in the south (+Z)
  TimeOfDayTrack track{18.0f, 10.0f};
  EXPECT_NEAR(track.hoursAt(5.0f), 6.0f, 1e-4f);  // 18 h + 12 h wraps to 6 h
}

// HybridFrame::setSunAndSky's lighting cuts (LightingCutDetector): a day that passes in 10
// seconds at 60 frames per second (0.6 degrees of sun per frame, sunrise and sunset fades
// included) is motion in every frame; a 3-hour jump, a sun switched off, a sky 3x brighter
// are cuts; a negative threshold never cuts.
TEST(Animation, LightingCutsAreJumpsNotMotion) {
  Scene scene = loadScene("sunroom");
  Sun sun;
  Sky sky;
  applyTimeOfDay(8.0f, scene.sun, scene.sky, sun, sky);
  LightingCutDetector day(sun, sky, 5.0f);
  int cuts = 0;
  for (int frame = 1; frame <= 600; ++frame) {
    applyTimeOfDay(8.0f + 24.0f * float(frame) / 600.0f, scene.sun, scene.sky, sun, sky);
    cuts += day.next(sun, sky) ? 1 : 0;
  }
  EXPECT_EQ(cuts, 0);

  Sun morning, afternoon;
  Sky morningSky, afternoonSky;
  applyTimeOfDay(9.0f, scene.sun, scene.sky, morning, morningSky);
  applyTimeOfDay(12.0f, scene.sun, scene.sky, afternoon, afternoonSky);
  LightingCutDetector jump(morning, morningSky, 5.0f);
  EXPECT_TRUE(jump.next(afternoon, afternoonSky));
  EXPECT_FALSE(jump.next(afternoon, afternoonSky));  // the same light again: no cut
  Sun off = afternoon;
  off.irradiance = 0.0f;
  EXPECT_TRUE(jump.next(off, afternoonSky));
  Sky bright = afternoonSky;
  bright.radiance = 3.0f * glm::max(afternoonSky.radiance, glm::vec3(0.1f));
  EXPECT_TRUE(jump.next(off, bright));

  Sun turned = morning;
  turned.direction = glm::rotate(glm::mat4(1.0f), glm::radians(1.0f), glm::vec3(0, 1, 0)) *
                     glm::vec4(morning.direction, 0.0f);
  LightingCutDetector small(morning, morningSky, 5.0f);
  EXPECT_FALSE(small.next(turned, morningSky));
  LightingCutDetector never(morning, morningSky, -1.0f);
  EXPECT_FALSE(never.next(afternoon, afternoonSky));
}

// ---- GPU ----------------------------------------------------------------------------------------

HybridSettings smallSettings(uint32_t width, uint32_t height) {
  HybridSettings settings;
  settings.width = width;
  settings.height = height;
  return settings;
}

// The world position a gbuffer pixel shows, from its view depth.
glm::vec3 pixelPosition(const gpu::GpuCamera& cam, glm::vec2 centre, glm::uvec2 res, float depth) {
  glm::vec3 dir = gpu::cameraRayDirection(cam, centre, glm::vec2(res));
  return cam.position + dir * (depth / glm::dot(dir, cam.forward));
}

glm::vec2 projectToPixel(const gpu::GpuCamera& cam, glm::uvec2 res, const glm::vec3& p) {
  glm::vec4 clip = viewProjection(cam, 0.01f) * glm::vec4(p, 1.0f);
  return (glm::vec2(clip) / clip.w * 0.5f + 0.5f) * glm::vec2(res);
}

// test::floorAndCardUnlit with a grey card, lit by a point sun (hard shadows).
Scene floorAndCard() {
  Scene scene = test::floorAndCardUnlit(glm::vec4(0.5f));
  scene.sun.angularDiameterDegrees = 0.0f;
  validateScene(scene, "floor and card");
  return scene;
}

// Last frame's four texels around `previous` (a pixel position): whether they all saw the
// point p (by view depth, so a disocclusion fails), the bilinear fetch's relative error
// against `now`, and whether `now` lies within the taps' range widened by 2%.
struct TapSample {
  bool offscreen = false;
  bool bracketed = false;
  float relativeError = 0.0f;
};

bool bracketedByTaps(const ImageRGBA32F& before, const std::vector<float>& depthBefore,
                     glm::uvec2 res, glm::vec2 previous, const glm::vec3& p,
                     const gpu::GpuCamera& camA, float now, TapSample& out,
                     bool checkDepth = true) {
  out = {};
  glm::vec2 u = previous - 0.5f;
  glm::ivec2 base = glm::ivec2(glm::floor(u));
  glm::vec2 t = u - glm::vec2(base);
  if (base.x < 0 || base.y < 0 || base.x + 1 >= int(res.x) || base.y + 1 >= int(res.y)) {
    out.offscreen = true;
    return false;
  }
  // Inverse view depth is linear in screen space on a plane, so its bilinear mix over the taps
  // must give the point's depth last frame; a tap on another surface breaks that. Each tap
  // must also be near that depth (no mix of foreground and background).
  float expectedDepth = glm::dot(p - camA.position, camA.forward);
  bool occluded = false;
  float inverseDepth = 0.0f, fetched = 0.0f, lo = 3e38f, hi = 0.0f;
  for (int k = 0; k < 4; ++k) {
    glm::ivec2 tap = base + glm::ivec2(k & 1, k >> 1);
    float d = depthBefore[size_t(tap.y) * res.x + tap.x];
    occluded |= !(std::abs(d - expectedDepth) < 0.1f * expectedDepth);
    float w = ((k & 1) ? t.x : 1.0f - t.x) * ((k >> 1) ? t.y : 1.0f - t.y);
    inverseDepth += w / std::max(d, 1e-6f);
    float value = luminance(before.at(tap.x, tap.y));
    fetched += w * value;
    lo = std::min(lo, value);
    hi = std::max(hi, value);
  }
  occluded |= std::abs(inverseDepth * expectedDepth - 1.0f) > 0.01f;
  if (checkDepth && occluded) return false;
  out.relativeError = std::abs(fetched - now) / std::max(now, 1e-3f);
  out.bracketed = now >= lo * 0.98f - 1e-4f && now <= hi * 1.02f + 1e-4f;
  return true;
}

TEST(Motion, LastCompositeReprojectedByVelocityMatchesThisCompositeOutsideDisocclusions) {
  vk::Context context(vk::contextOptionsFromEnvironment({}));
  Scene scene = floorAndCard();  // sun angle 0: hard shadows, every frame the same
  GpuScene gpuScene(context, scene);
  HybridSettings settings = smallSettings(128, 72);
  settings.skyAmbientStrength = 1.0f;
  settings.shadows.divisor = 1;  // a half-res shadow grid shifts against the scene as it moves
  HybridFrame frame(context, gpuScene, scene, settings);
  for (const char* view : {"composite", "gbuffer.depth", "gbuffer.velocity", "gbuffer.flags"})
    frame.requestDebugView(view);
  const glm::uvec2 res(settings.width, settings.height);
  Camera a = effectiveCamera(scene);
  Camera b = a;
  b.position += glm::vec3(0.3f, 0.1f, -0.2f);  // several pixels of motion and parallax
  b.target += glm::vec3(0.05f, 0.0f, 0.0f);
  for (int i = 0; i < 3; ++i) frame.render(a);
  ImageRGBA32F before = frame.debugViewImage("composite");
  std::vector<float> depthBefore = texels<float>(frame, "gbuffer.depth");
  frame.render(b);
  ImageRGBA32F after = frame.debugViewImage("composite");
  std::vector<float> depthAfter = texels<float>(frame, "gbuffer.depth");
  std::vector<glm::u16vec2> velocity = texels<glm::u16vec2>(frame, "gbuffer.velocity");
  std::vector<uint32_t> flags = texels<uint32_t>(frame, "gbuffer.flags");
  gpu::GpuCamera camA = makeGpuCamera(a, res.x, res.y, gpuScene.bounds());
  gpu::GpuCamera camB = makeGpuCamera(b, res.x, res.y, gpuScene.bounds());

  uint32_t compared = 0, within = 0, withinStill = 0, moved = 0, surface = 0, offscreen = 0,
           disoccluded = 0;
  TapSample sample;
  std::vector<float> errors;
  for (uint32_t y = 0; y < res.y; ++y)
    for (uint32_t x = 0; x < res.x; ++x) {
      size_t i = size_t(y) * res.x + x;
      if (!(flags[i] & gpu::GBUFFER_FLAG_SURFACE)) continue;
      ++surface;
      glm::vec2 v(glm::unpackHalf1x16(velocity[i].x), glm::unpackHalf1x16(velocity[i].y));
      glm::vec2 centre(x + 0.5f, y + 0.5f);
      glm::vec2 previous = centre - v;
      // The velocity is exact for a static scene: last frame's camera sees the point there.
      glm::vec3 p = pixelPosition(camB, centre, res, depthAfter[i]);
      glm::vec2 expected = projectToPixel(camA, res, p);
      ASSERT_NEAR(previous.x, expected.x, 0.02f) << x << "," << y;
      ASSERT_NEAR(previous.y, expected.y, 0.02f) << x << "," << y;
      moved += glm::length(v) > 0.5f;
      // Bilinear fetch of last frame's composite; disoccluded (some tap saw another surface)
      // or off-screen pixels are left out.
      if (!bracketedByTaps(before, depthBefore, res, previous, p, camA, luminance(after.at(x, y)),
                           sample)) {
        ++(sample.offscreen ? offscreen : disoccluded);
        continue;
      }
      errors.push_back(sample.relativeError);
      ++compared;
      within += sample.bracketed;
      // Control: as if nothing had moved, the taps around the same pixel last frame.
      TapSample still;
      withinStill += bracketedByTaps(before, depthBefore, res, centre, p, camA,
                                     luminance(after.at(x, y)), still, false) &&
                     still.bracketed;
    }
  std::printf("reprojection: %u surface pixels: %u off-screen last frame, %u disoccluded\n",
              surface, offscreen, disoccluded);
  ASSERT_GT(compared, surface / 2) << "too few comparable pixels";
  EXPECT_GT(moved, compared / 2) << "the camera motion should move most pixels";
  std::nth_element(errors.begin(), errors.begin() + errors.size() / 2, errors.end());
  float median = errors[errors.size() / 2];
  std::printf(
      "reprojection: %u pixels compared, %u bracketed by their taps (%u without "
      "reprojection), median relative error of the bilinear fetch %.4f\n",
      compared, within, withinStill, median);
  // Tolerance: this frame's value must lie within the range of the four texels the velocity
  // points between, widened by 2% (texture filtering, RG16F velocity), on 98.5% of pixels (the
  // rest sit on the card's hard shadow edge, where the shadow history's running mean blends
  // last frame's edge with this one's: temporal accumulation, not reprojection); a bilinear
  // fetch itself is off by more where the texture is minified near the horizon and along hard
  // shadow edges, so it only has to agree to 1% at the median.
  EXPECT_GE(double(within) / compared, 0.985);
  EXPECT_LT(median, 0.01f);
  // Without reprojection most pixels fail: the check has teeth.
  EXPECT_LT(withinStill, compared / 2);
  EXPECT_EQ(context.validationErrorCount(), 0u);
}

TEST(Motion, MovingObjectVelocityIsItsAnalyticScreenMotion) {
  vk::Context context(vk::contextOptionsFromEnvironment({}));
  Scene scene = floorAndCard();
  GpuScene gpuScene(context, scene);
  HybridSettings settings = smallSettings(96, 64);
  HybridFrame frame(context, gpuScene, scene, settings);
  frame.requestDebugView("vbuffer.ids");
  frame.requestDebugView("gbuffer.depth");
  frame.requestDebugView("gbuffer.velocity");
  const glm::mat4 rest = scene.instances[1].transform;
  // Moves right and towards the camera while turning 10 degrees: not a pure screen shift.
  const glm::mat4 moved = glm::translate(glm::mat4(1.0f), {0.12f, 0.03f, 0.2f}) * rest *
                          glm::rotate(glm::mat4(1.0f), glm::radians(10.0f), {0, 1, 0});
  std::vector<glm::mat4> transforms = {scene.instances[0].transform, rest};
  frame.setInstanceTransforms(transforms);
  frame.render(*scene.camera);
  transforms[1] = moved;
  frame.setInstanceTransforms(transforms);
  frame.render(*scene.camera);

  std::vector<glm::uvec4> ids = texels<glm::uvec4>(frame, "vbuffer.ids");
  std::vector<float> depth = texels<float>(frame, "gbuffer.depth");
  std::vector<glm::u16vec2> velocity = texels<glm::u16vec2>(frame, "gbuffer.velocity");
  const glm::uvec2 res(settings.width, settings.height);
  gpu::GpuCamera cam = makeGpuCamera(*scene.camera, res.x, res.y, gpuScene.bounds());
  uint32_t cardPixels = 0;
  float maxError = 0.0f, maxFloorSpeed = 0.0f, meanCardSpeed = 0.0f;
  for (uint32_t y = 0; y < res.y; ++y)
    for (uint32_t x = 0; x < res.x; ++x) {
      size_t i = size_t(y) * res.x + x;
      if (ids[i].x == gpu::VBUFFER_NO_HIT) continue;
      glm::vec2 v(glm::unpackHalf1x16(velocity[i].x), glm::unpackHalf1x16(velocity[i].y));
      if (ids[i].x == 0) {
        maxFloorSpeed = std::max(maxFloorSpeed, glm::length(v));
        continue;
      }
      glm::vec2 centre(x + 0.5f, y + 0.5f);
      glm::vec3 p = pixelPosition(cam, centre, res, depth[i]);
      glm::vec3 before = glm::vec3(rest * glm::inverse(moved) * glm::vec4(p, 1.0f));
      glm::vec2 expected = centre - projectToPixel(cam, res, before);
      maxError = std::max(maxError, glm::length(v - expected));
      meanCardSpeed += glm::length(expected);
      ++cardPixels;
    }
  ASSERT_GT(cardPixels, 100u);
  meanCardSpeed /= float(cardPixels);
  std::printf("moving card: %u pixels, mean motion %.2f px, max velocity error %.4f px\n",
              cardPixels, meanCardSpeed, maxError);
  EXPECT_GT(meanCardSpeed, 2.0f);
  // RG16F holds a few pixels to ~0.004 px; the depth round trip adds a little.
  EXPECT_LT(maxError, 0.02f);
  EXPECT_LT(maxFloorSpeed, 1e-3f);  // the camera did not move (rounding only)

  // The card stops: next frame nothing on screen moves.
  frame.render(*scene.camera);
  float maxSpeed = 0.0f;
  for (glm::u16vec2 v : texels<glm::u16vec2>(frame, "gbuffer.velocity"))
    maxSpeed = std::max(maxSpeed, std::hypot(glm::unpackHalf1x16(v.x), glm::unpackHalf1x16(v.y)));
  EXPECT_LT(maxSpeed, 1e-3f) << "a stopped object keeps its motion vectors";
  EXPECT_EQ(context.validationErrorCount(), 0u);
}

TEST(Motion, HundredAnimatedFramesAllocateNothingAfterFrameThree) {
  vk::Context context(vk::contextOptionsFromEnvironment({}));
  Scene scene = loadScene("sunroom");
  ASSERT_FALSE(scene.animation.transforms.empty());
  ASSERT_TRUE(scene.animation.camera.has_value());
  GpuScene gpuScene(context, scene);
  HybridFrame frame(context, gpuScene, scene, smallSettings(64, 30));
  frame.requestDebugView("composite");
  AnimationPlayer player(scene, scene.animation);
  uint64_t allocations = 0;
  for (uint32_t i = 0; i < 100; ++i) {
    frame.render(player.apply(frame, float(i) / 30.0f));
    if (i == 3) allocations = context.allocationCount();
    if (i > 3) ASSERT_EQ(context.allocationCount(), allocations) << "frame " << i;
  }
  EXPECT_EQ(context.validationErrorCount(), 0u);
}

// 20 animated frames (the scene's motion or a sway, a moving sun) of a built-in scene under
// the validation layers with synchronization validation: no NaN, silent layers, and no device
// allocation after the 3rd frame (the frame graph allocates everything up front). One case per
// scene and preset, so that CTest spreads them over the cores. Scenes of over a million
// triangles find their primary hits by tracing (the presets' other vbuffer mode): lavapipe
// rasterises every triangle on the CPU whatever the image size, and city-10k's raster vbuffer
// alone took 12.6 s a frame at 64x30 (3 minutes a case); the raster path is the same code on
// the smaller scenes.
void expectAnimatedFramesClean(const std::string& name, Preset preset) {
  vk::Context context(
      vk::contextOptionsFromEnvironment({.validation = true, .synchronizationValidation = true}));
  ASSERT_TRUE(context.validationEnabled()) << "the Khronos validation layer is missing";
  Scene scene = loadScene(name);
  GpuScene gpuScene(context, scene);
  HybridSettings settings = presetSettings(preset);
  settings.width = 64;
  settings.height = 30;
  if (scene.triangleCount() > 1'000'000) settings.vbuffer = VBufferMode::Trace;
  HybridFrame frame(context, gpuScene, scene, settings);
  frame.requestDebugView("composite");
  SceneAnimation animation = scene.animation;
  if (!animation.camera)
    animation.camera = swayCameraPath(effectiveCamera(scene), 4.0f, 0.3f, 8.0f);
  animation.timeOfDay = TimeOfDayTrack{16.0f, 60.0f};  // the sun moves too
  AnimationPlayer player(scene, animation);
  uint64_t allocationsAfterFrame2 = 0;
  for (uint32_t i = 0; i < 20; ++i) {
    std::vector<vk::PassTiming> timings = frame.render(player.apply(frame, float(i) / 10.0f));
    if (i == 2) allocationsAfterFrame2 = context.allocationCount();
    if (i > 2) EXPECT_EQ(context.allocationCount(), allocationsAfterFrame2) << "frame " << i;
    if (context.info().timestampPeriodNs > 0.0f) EXPECT_FALSE(timings.empty());
  }
  ImageRGBA32F hdr = frame.debugViewImage("composite");
  uint32_t nonFinite = 0;
  for (float v : hdr.pixels) nonFinite += !std::isfinite(v);
  EXPECT_EQ(nonFinite, 0u);
  EXPECT_EQ(context.validationErrorCount(), 0u);
}

class TwentyAnimatedFrames : public ::testing::TestWithParam<std::string> {};

TEST_P(TwentyAnimatedFrames, AreCleanAtMobileSettings) {
  expectAnimatedFramesClean(GetParam(), Preset::Mobile);
}

TEST_P(TwentyAnimatedFrames, AreCleanAtDesktopSettings) {
  expectAnimatedFramesClean(GetParam(), Preset::Desktop);
}

// Every built-in scene; '-' is not allowed in a test name.
INSTANTIATE_TEST_SUITE_P(BuiltinScenes, TwentyAnimatedFrames,
                         ::testing::ValuesIn(builtinSceneNames()),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           std::string name = info.param;
                           std::replace(name.begin(), name.end(), '-', '_');
                           return name;
                         });

TEST(Motion, CameraCutResetsHistory) {
  vk::Context context(vk::contextOptionsFromEnvironment({}));
  Scene scene = loadScene("sunroom");
  GpuScene gpuScene(context, scene);
  HybridFrame frame(context, gpuScene, scene, smallSettings(64, 30));
  frame.requestDebugView("shadows.visibility");
  frame.requestDebugView("composite");
  Camera c = effectiveCamera(scene);
  SceneAnimation animation;
  animation.camera = CameraPath{};
  animation.camera->keys = {
      {0.0f, c.position, c.target, c.verticalFovDegrees, false},
      {1.0f, c.position + glm::vec3(0.02f, 0, 0), c.target, c.verticalFovDegrees, false},
      // The other side of the room, looking back: a cut.
      {1.5f, glm::vec3(2.0f, 1.5f, 2.0f), c.position, 60.0f, true},
      {3.0f, glm::vec3(2.1f, 1.5f, 2.0f), c.position, 60.0f, false}};
  AnimationPlayer player(scene, animation);
  auto maxFrames = [&] {
    float m = 0.0f;
    for (glm::u16vec2 v : texels<glm::u16vec2>(frame, "shadows.visibility"))
      m = std::max(m, glm::unpackHalf1x16(v.y));
    return m;
  };
  for (uint32_t i = 0; i < 20; ++i) {
    float t = float(i) / 10.0f;
    frame.render(player.apply(frame, t));
    EXPECT_EQ(player.lastWasCut(), i == 15) << "frame " << i;
    if (i == 14) EXPECT_GT(maxFrames(), 10.0f);
    if (i == 15) EXPECT_EQ(maxFrames(), 1.0f) << "history survived the cut";
    if (i == 16) EXPECT_EQ(maxFrames(), 2.0f);
    ImageRGBA32F hdr = frame.debugViewImage("composite");
    double sum = 0.0;
    uint32_t nonFinite = 0;
    for (size_t p = 0; p < hdr.pixelCount(); ++p) {
      glm::vec4 v = glm::make_vec4(hdr.pixels.data() + 4 * p);
      nonFinite += !std::isfinite(v.x + v.y + v.z);
      sum += luminance(v);
    }
    EXPECT_EQ(nonFinite, 0u) << "frame " << i;
    EXPECT_GT(sum / double(hdr.pixelCount()), 1e-3) << "black frame " << i;
  }
  EXPECT_EQ(context.validationErrorCount(), 0u);
}

TEST(Motion, NightIsDarkerThanNoonButNotBlackOrNaN) {
  vk::Context context(vk::contextOptionsFromEnvironment({}));
  Scene scene = loadScene("sunroom");
  GpuScene gpuScene(context, scene);
  HybridSettings settings = smallSettings(64, 30);
  settings.skyAmbientStrength = 1.0f;
  HybridFrame frame(context, gpuScene, scene, settings);
  frame.requestDebugView("composite");
  auto meanAt = [&](float hours) {
    SceneAnimation animation;
    animation.timeOfDay = TimeOfDayTrack{hours, 0.0f};
    AnimationPlayer player(scene, animation);
    for (int i = 0; i < 3; ++i) frame.render(player.apply(frame, 0.0f));
    ImageRGBA32F hdr = frame.debugViewImage("composite");
    double sum = 0.0;
    for (size_t p = 0; p < hdr.pixelCount(); ++p) {
      glm::vec4 v = glm::make_vec4(hdr.pixels.data() + 4 * p);
      EXPECT_TRUE(std::isfinite(v.x + v.y + v.z)) << hours << " h";
      sum += luminance(v);
    }
    return sum / double(hdr.pixelCount());
  };
  double noon = meanAt(12.0f), midnight = meanAt(0.0f);
  std::printf("mean radiance: noon %.4f, midnight %.6f\n", noon, midnight);
  EXPECT_GT(midnight, 0.0);
  EXPECT_LT(midnight, 0.05 * noon);
  EXPECT_EQ(context.validationErrorCount(), 0u);
}

}  // namespace
}  // namespace bounce
