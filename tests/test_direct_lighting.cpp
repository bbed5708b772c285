// The hybrid frame's direct lighting (`--gi none`, black sky) against the reference path tracer
// limited to one scattering event (camera -> surface -> light), camera rays through pixel
// centres like the real-time frame's: the same view must agree within the relMSE stated below,
// with hard and with soft sun shadows, shadows at full and at the presets' half resolution.
// What is left over is known: half-resolution shadows are upsampled, so shadow edges move by up
// to a pixel; soft penumbrae come from a 16-frame running mean of one cone sample per frame.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <vector>

#include <gtest/gtest.h>

#include "frame/presets.h"
#include "harness.h"

#include "frame/hybrid_frame.h"
#include "reference/path_tracer.h"
#include "rt/gpu_scene.h"
#include "scene/animation.h"
#include "scene/load.h"
#include "scene/scene_options.h"
#include "tools/flip.h"
#include "tools/image_io.h"
#include "tools/metrics.h"
#include "vk/context.h"

namespace bounce {
namespace {

using test::meanLuminance;

struct DirectLightComparison {
  double relMse = 0.0;
  double meanRatio = 0.0;  // mean radiance, hybrid / reference
  double flipMean = 0.0;   // HDR-FLIP
  // relMSE of a second reference (another seed) against the first: the Monte Carlo noise floor
  // of the comparison. Only computed when the case asks for it.
  double referenceNoiseRelMse = 0.0;
};

struct DirectLightCase {
  std::string scene;
  float sunAngleDegrees = 0.0f;  // 0: a point sun, hard shadows
  uint32_t shadowDivisor = 1;    // shadows traced at resolution / divisor
  uint32_t width = 96;
  uint32_t height = 54;
  int frames = 4;  // enough for the shadow history to converge
  float shadowMaxHistory = 16.0f;
  bool measureReferenceNoise = false;
  uint32_t referenceSamples = 16;
};

DirectLightComparison compareDirectLight(const DirectLightCase& c) {
  const std::string& sceneName = c.scene;
  const float sunAngleDegrees = c.sunAngleDegrees;
  Scene scene = loadScene(sceneName);
  scene.sky.model = SkyModel::Constant;
  scene.sky.radiance = glm::vec3(0.0f);  // direct sun light only
  // ... and no local lights (city's street lamps): ReSTIR DI estimates those stochastically,
  // while the sun's full-resolution hard shadow is the one thing both sides compute exactly.
  scene.lights.clear();
  for (Material& material : scene.materials) {
    material.emissive = glm::vec3(0.0f);
    material.emissiveTexture = -1;
  }
  scene.sun.angularDiameterDegrees = sunAngleDegrees;
  Camera camera = effectiveCamera(scene);

  vk::Context context(vk::contextOptionsFromEnvironment());
  GpuScene gpuScene(context, scene);

  HybridSettings settings;
  settings.width = c.width;
  settings.height = c.height;
  settings.shadows.divisor = c.shadowDivisor;
  settings.shadows.maxHistory = c.shadowMaxHistory;
  // Direct light only, like the one-event reference: no reflection rays (their hits add a
  // second scattering event).
  settings.reflections.divisor = 0;
  HybridFrame frame(context, gpuScene, scene, settings);
  frame.requestDebugView("composite");
  for (int i = 0; i < c.frames; ++i) frame.render(camera);
  ImageRGBA32F hybrid = frame.debugViewImage("composite");

  ReferencePathTracer tracer(context, gpuScene, scene);
  ReferenceOptions options;
  options.width = c.width;
  options.height = c.height;
  options.samplesPerPixel = c.referenceSamples;
  options.maxBounces = 1;
  options.pixelCentre = true;
  ImageRGBA32F reference = tracer.render(camera, options).image;
  ImageRGBA32F secondReference;
  if (c.measureReferenceNoise) {
    options.seed = 2;
    secondReference = tracer.render(camera, options).image;
  }

  if (const char* dir = std::getenv("BOUNCE_TEST_IMAGES")) {  // for looking at the pair
    std::string stem = std::string(dir) + "/" + sceneName + "-" +
                       std::to_string(int(sunAngleDegrees)) + "deg-div" +
                       std::to_string(c.shadowDivisor);
    writeImage(stem + "-hybrid.exr", hybrid);
    writeImage(stem + "-reference.exr", reference);
    writePng(stem + "-hybrid.png", hybrid, 0.02f);
    writePng(stem + "-reference.png", reference, 0.02f);
  }
  EXPECT_EQ(countNonFinitePixels(hybrid), 0u);
  EXPECT_EQ(context.validationErrorCount(), 0u);
  DirectLightComparison result;
  result.relMse = relativeMeanSquaredError(hybrid, reference);
  result.flipMean = computeHdrFlip(hybrid, reference).statistics.mean;
  if (c.measureReferenceNoise)
    result.referenceNoiseRelMse = relativeMeanSquaredError(secondReference, reference);
  result.meanRatio = meanLuminance(hybrid) / meanLuminance(reference);
  std::printf(
      "%s %ux%u, sun %.2f deg, shadows at 1/%u res: relMSE %.4f, FLIP %.4f, mean "
      "hybrid/reference %.4f, reference noise relMSE %.4f\n",
      sceneName.c_str(), c.width, c.height, sunAngleDegrees, c.shadowDivisor, result.relMse,
      result.flipMean, result.meanRatio, result.referenceNoiseRelMse);
  return result;
}

// Measured on lavapipe (docs/frame.md): relMSE 0.0004 / 0.0000 / 0.0000 and mean
// ratios within 0.2 %: with full-resolution hard shadows the frame and the reference compute the
// same thing. The thresholds leave room for ray-offset differences at a few contact pixels; an
// energy bug (a missing 1/pi, a wrong cosine, a wrong sun normalisation) moves the mean ratio
// by far more than 1 %.
TEST(DirectLighting, HardShadowsMatchReference) {
  for (const char* name : {"sunroom", "city", "foliage"}) {
    DirectLightComparison c = compareDirectLight({.scene = name});
    EXPECT_LT(c.relMse, 0.005) << name;
    EXPECT_NEAR(c.meanRatio, 1.0, 0.01) << name;
  }
}

// The presets trace shadows at half resolution: edges then move by up to a pixel, which relMSE
// (per-pixel relative error against a black background) punishes without bound, so this case is
// judged by HDR-FLIP (measured 0.015 sunroom, 0.024 city at 384x216; full resolution gives 0.003
// / 0.005) and by energy (measured mean ratios 0.981, 0.994).
TEST(DirectLighting, HalfResolutionShadowsMatchReference) {
  for (const char* name : {"sunroom", "city"}) {
    DirectLightComparison c = compareDirectLight(
        {.scene = name, .shadowDivisor = 2, .width = 384, .height = 216, .referenceSamples = 4});
    EXPECT_LT(c.flipMean, 0.035) << name;
    EXPECT_NEAR(c.meanRatio, 1.0, 0.03) << name;
  }
}

// Soft shadows: the frame's 128-frame mean of one cone sample per pixel against 64 reference
// samples. In `sunroom` penumbrae are few and the error is small outright; under `foliage`'s
// leaves nearly every pixel is in penumbra and the error is Monte Carlo noise of both estimates,
// so it is held against the noise floor: another 64-sample reference differs from the first by
// relMSE n; an unbiased frame (128 samples) should differ by about 0.75 n, and a wrong cone
// distribution (too wide, too narrow, not uniform over the disc) by much more.
TEST(DirectLighting, SoftShadowsMatchReference) {
  const DirectLightCase soft{
      .sunAngleDegrees = 2.0f, .frames = 128, .shadowMaxHistory = 128.0f, .referenceSamples = 64};
  DirectLightCase sunroom = soft;
  sunroom.scene = "sunroom";
  DirectLightComparison c = compareDirectLight(sunroom);
  EXPECT_LT(c.relMse, 0.05);
  EXPECT_NEAR(c.meanRatio, 1.0, 0.03);

  DirectLightCase foliage = soft;
  foliage.scene = "foliage";
  foliage.measureReferenceNoise = true;
  c = compareDirectLight(foliage);
  EXPECT_LT(c.relMse, 1.5 * c.referenceNoiseRelMse);
  EXPECT_NEAR(c.meanRatio, 1.0, 0.03);
}

}  // namespace
}  // namespace bounce

namespace bounce {
namespace {

// The sun's visibility (`shadows-denoise`'s) after a camera move, against a still camera at the
// move's last pose: the desktop preset (soft shadows at half resolution), sunroom at 120x68, 48
// frames each. The view and the sun are still, so a temporal filter that follows the motion
// gives the still run's image; one that lags drags old light and shadow beside every edge.
std::vector<float> shadowVisibility(vk::Context& context, GpuScene& gpuScene, const Scene& scene,
                                    const CameraPath* path, const Camera& still) {
  HybridSettings settings = presetSettings(Preset::Desktop);
  settings.width = 120;
  settings.height = 68;
  HybridFrame frame(context, gpuScene, scene, settings);
  frame.requestDebugView("shadows-denoise");
  for (int i = 0; i < 48; ++i)
    frame.render(path ? evaluateCameraPath(*path, float(i) / 30.0f) : still);
  const ImageRGBA32F image = frame.debugViewImage("shadows-denoise");
  std::vector<float> visibility(image.pixelCount());
  for (size_t i = 0; i < visibility.size(); ++i) visibility[i] = image.pixels[4 * i];
  return visibility;
}

// A linear dolly and pan through sunroom over 48 frames at 30 fps (0.5 px a frame on average at
// 120x68; scripts/device/gi_path.json is the same path).
CameraPath sunroomDolly() {
  CameraKeyframe start;
  start.position = {7.7f, 1.7f, 5.7f};
  start.target = {2.5f, 0.6f, 2.4f};
  start.verticalFovDegrees = 65.0f;
  CameraKeyframe end = start;
  end.time = 47.0f / 30.0f;
  end.position = {6.4f, 1.45f, 4.9f};
  end.target = {2.5f, 0.7f, 3.7f};
  CameraPath path;
  path.catmullRom = false;
  path.keys = {start, end};
  return path;
}

// Whether a 120x68 visibility image is uniform within 0.05 over the (2 radius + 1)^2 pixels
// around (x, y), which lie inside it: not a shadow edge.
bool uniformAround(const std::vector<float>& image, int x, int y, int radius) {
  float lo = 1.0f, hi = 0.0f;
  for (int dy = -radius; dy <= radius; ++dy)
    for (int dx = -radius; dx <= radius; ++dx) {
      const float v = image[size_t(y + dy) * 120 + size_t(x + dx)];
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
  return hi - lo <= 0.05f;
}

// The mean |moved - still| of two visibility images (120x68): away from the still image's shadow
// edges (pixels whose 5x5 neighbourhood there is uniform within 0.05; their count in `away`)
// and over the whole image (`all`).
double differenceAwayFromEdges(const std::vector<float>& moved, const std::vector<float>& still,
                               size_t& away, double& all) {
  const int w = 120, h = 68;
  double awaySum = 0.0, allSum = 0.0;
  away = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t i = size_t(y) * w + x;
      const double difference = std::abs(double(moved[i]) - double(still[i]));
      allSum += difference;
      if (x < 2 || y < 2 || x >= w - 2 || y >= h - 2 || !uniformAround(still, x, y, 2)) continue;
      awaySum += difference;
      ++away;
    }
  all = allSum / double(moved.size());
  return awaySum / double(away);
}

// After the dolly, the visibility away from the still image's shadow edges (73 % of the view)
// differs from the still run's by at most 0.001 on average: no trail. Within 2 pixels of an
// edge, reprojecting a point-sampled hard edge blurs it by a pixel whatever the filter; that is
// reported, not gated. Measured: away from edges 0.0000 (0.0059 before the motion clamp, whose
// nearest-texel history trailed each edge by several pixels), the whole image 0.0195 (0.0401);
// docs/frame.md.
TEST(Shadows, CameraDollyLeavesNoTrail) {
  Scene scene = loadScene("sunroom");
  vk::Context context(vk::contextOptionsFromEnvironment());
  GpuScene gpuScene(context, scene);
  const CameraPath path = sunroomDolly();
  const Camera last = evaluateCameraPath(path, path.duration());
  const std::vector<float> moved = shadowVisibility(context, gpuScene, scene, &path, last);
  const std::vector<float> still = shadowVisibility(context, gpuScene, scene, nullptr, last);
  size_t away = 0;
  double all = 0.0;
  const double awayMean = differenceAwayFromEdges(moved, still, away, all);
  std::printf(
      "sunroom 120x68, 48 frames of a dolly against a still camera at its end: sun visibility "
      "mean |difference| %.4f away from shadow edges (%zu px), %.4f over the image\n",
      awayMean, away, all);
  EXPECT_GT(away, moved.size() / 2);
  EXPECT_LE(awayMean, 0.001);
  EXPECT_EQ(context.validationErrorCount(), 0u);
}

// The sun's visibility (`shadows-denoise`'s, desktop preset, sunroom 120x68, its own camera held
// still) after 48 frames whose objects stand at their scripted pose of time `before` (the yellow
// cube at rest in the sun patch, the blue panel closed) and, for the last `framesAfter`, of time
// 2 s (the cube slid 0.6 m towards the window, the panel swung open 80 degrees).
std::vector<float> movingCasterVisibility(vk::Context& context, GpuScene& gpuScene,
                                          const Scene& scene, float before, int framesAfter) {
  HybridSettings settings = presetSettings(Preset::Desktop);
  settings.width = 120;
  settings.height = 68;
  HybridFrame frame(context, gpuScene, scene, settings);
  frame.requestDebugView("shadows-denoise");
  const Camera camera = effectiveCamera(scene);
  std::vector<glm::mat4> transforms(scene.instances.size());
  for (size_t i = 0; i < transforms.size(); ++i) transforms[i] = scene.instances[i].transform;
  for (int i = 0; i < 48; ++i) {
    evaluateTransforms(scene.animation, i >= 48 - framesAfter ? 2.0f : before, {}, transforms);
    frame.setInstanceTransforms(transforms);
    frame.render(camera);
  }
  const ImageRGBA32F image = frame.debugViewImage("shadows-denoise");
  std::vector<float> visibility(image.pixelCount());
  for (size_t i = 0; i < visibility.size(); ++i) visibility[i] = image.pixels[4 * i];
  return visibility;
}

// Moving casters under a still camera (issue 21 item 7's ghosting): the floor under the cube
// does not move, so a clamp keyed to the pixel's own motion never ran there and a moving
// shadow trailed behind its caster (docs/frame.md, "Moving casters"). Here the objects jump to
// another pose after 46 still frames. Where the jump turned shadow into light or light into
// shadow (the visibility of the runs that stood at either pose throughout differs by more than
// a half) and the new pose's visibility is uniform over the pixel's 3x3 neighbourhood (not an
// edge), the visibility 2 frames after the jump must be within 0.05 of the new pose's on
// average (lavapipe: 0.0000 over 30 pixels; 0.239 with the clamp keyed to the pixel's motion
// alone). Measured in a frame: docs/frame.md.
TEST(Shadows, MovingCasterLeavesNoTrail) {
  Scene scene = loadScene("sunroom");
  ASSERT_FALSE(scene.animation.transforms.empty());
  vk::Context context(vk::contextOptionsFromEnvironment());
  GpuScene gpuScene(context, scene);
  const std::vector<float> jumped = movingCasterVisibility(context, gpuScene, scene, 0.0f, 2);
  const std::vector<float> after = movingCasterVisibility(context, gpuScene, scene, 2.0f, 0);
  const std::vector<float> before = movingCasterVisibility(context, gpuScene, scene, 0.0f, 0);
  const int w = 120, h = 68;
  double sum = 0.0;
  size_t changed = 0;
  for (int y = 2; y < h - 2; ++y)
    for (int x = 2; x < w - 2; ++x) {
      const size_t i = size_t(y) * w + x;
      if (std::abs(before[i] - after[i]) <= 0.5f || !uniformAround(after, x, y, 1)) continue;
      sum += std::abs(double(jumped[i]) - double(after[i]));
      ++changed;
    }
  size_t away = 0;
  double all = 0.0;
  const double awayMean = differenceAwayFromEdges(jumped, after, away, all);
  std::printf(
      "sunroom 120x68, objects moved 2 frames ago against objects still there: sun visibility "
      "mean |difference| %.4f where the move changed it (%zu px), %.4f away from shadow edges, "
      "%.4f over the image\n",
      sum / double(std::max<size_t>(changed, 1)), changed, awayMean, all);
  EXPECT_GT(changed, 20u);  // the move changes the shadows: the test has teeth
  EXPECT_LE(sum / double(std::max<size_t>(changed, 1)), 0.05);
  EXPECT_LE(awayMean, 0.001);
  EXPECT_EQ(context.validationErrorCount(), 0u);
}

}  // namespace
}  // namespace bounce
