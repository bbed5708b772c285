// `--gi gi10`, AMD's GI-1.0 (src/gi/gi10/gi10_gi.h; issue 23; research/gi10_lux_denoisers.md
// §4.2 T0, T9, T10):
//   - every pass produces output: the counters of probe rays, probes and cells are above zero,
//     the probe ray count is its budget, gi.diffuse is finite and non-zero, and gi10 changes
//     the composite against --gi none;
//   - white furnace: irradiance / pi within 3 % of the analytic 2;
//   - Cornell box against Cycles (4096 spp, 256x256), 64 static frames: HDR-FLIP <= 0.12 and
//     mean luminance within 5 %; no cache overflow;
//   - a few hundred animated frames stay finite with silent validation.
// Measured values: each test's comment and docs/gi/gi10.md.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "harness.h"
#include "restir_gi_common.h"

#include "frame/hybrid_frame.h"
#include "frame/presets.h"
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

HybridSettings gi10Settings(uint32_t width, uint32_t height, GiMode gi = GiMode::Gi10) {
  HybridSettings s = presetSettings(Preset::Desktop);
  s.width = width;
  s.height = height;
  s.shadows.divisor = 1;
  s.lambert = true;
  // Every material is Lambert: no glossy lobe for reflection rays to find (and their passes
  // would double the test's time on lavapipe).
  s.reflections.divisor = 0;
  s.gi = gi;
  return s;
}

double statistic(const std::vector<GiStatistic>& statistics, const std::string& name) {
  for (const GiStatistic& s : statistics)
    if (s.name == name) return s.value;
  ADD_FAILURE() << "no statistic " << name;
  return -1.0;
}

struct Gi10Run {
  vk::Context context;
  Scene scene;
  std::unique_ptr<GpuScene> gpuScene;
  std::unique_ptr<HybridFrame> frame;

  Gi10Run(Scene s, const HybridSettings& settings, bool validation = false)
      : context(contextOptions(validation)), scene(std::move(s)) {
    gpuScene = std::make_unique<GpuScene>(context, scene);
    frame = std::make_unique<HybridFrame>(context, *gpuScene, scene, settings);
  }
  static vk::ContextOptions contextOptions(bool validation) {
    vk::ContextOptions options = vk::contextOptionsFromEnvironment();
    if (validation) options.validation = true;
    return options;
  }
};

// Mean of the view `name` over the last `average` of `frames` frames of a static view.
ImageRGBA32F renderAveraged(Gi10Run& run, const Camera& camera, const std::string& name, int frames,
                            int average) {
  run.frame->requestDebugView(name);
  ImageRGBA32F sum;
  for (int i = 0; i < frames; ++i) {
    run.frame->render(camera);
    if (i < frames - average) continue;
    ImageRGBA32F image = run.frame->debugViewImage(name);
    if (sum.pixels.empty()) sum = ImageRGBA32F(image.width, image.height, glm::vec4(0.0f));
    for (size_t k = 0; k < image.pixels.size(); ++k)
      sum.pixels[k] += image.pixels[k] / float(average);
  }
  return sum;
}

void writeDebugPng(const ImageRGBA32F& image, const std::string& name, float scale) {
  ImageRGBA32F scaled = image;
  for (size_t i = 0; i < scaled.pixels.size(); ++i)
    scaled.pixels[i] = i % 4 == 3 ? 1.0f : scaled.pixels[i] * scale;
  writeImage(test::tempDir("gi10") + "/" + name + ".png", scaled);
}

// T0 and T10 on the Cornell box at 64x64 after 8 frames: every stage's counter above zero, the
// probe rays exactly the budget (64 per spawn tile that sees a surface: the box fills the view,
// so every one of the 4x4 spawn tiles), no overflow, gi.diffuse finite and non-zero, and the
// composite with gi10 brighter than with --gi none (its indirect light).
TEST(Gi10, EveryPassProducesOutput) {
  const uint32_t size = 64;
  Scene scene = loadScene("cornell");
  Camera camera = effectiveCamera(scene);
  Gi10Run run(scene, gi10Settings(size, size));
  run.frame->requestDebugView("composite");
  run.frame->requestDebugView("gi.diffuse");
  run.frame->requestDebugView("gi10.irradiance");
  for (int i = 0; i < 8; ++i) run.frame->render(camera);
  std::vector<GiStatistic> s = run.frame->giStatistics();
  for (const GiStatistic& x : s) std::printf("  %s %.0f\n", x.name.c_str(), x.value);
  const double spawnTiles = (size / 16) * (size / 16);
  EXPECT_EQ(statistic(s, "gi10_probe_rays"), spawnTiles * 64);
  EXPECT_EQ(statistic(s, "gi10_spawned_probes"), spawnTiles);
  EXPECT_GT(statistic(s, "gi10_reprojected_probes"), 0.0);
  EXPECT_GT(statistic(s, "gi10_cache_inserts"), 0.0);
  EXPECT_GT(statistic(s, "gi10_live_cells"), 0.0);
  EXPECT_GT(statistic(s, "gi10_feedback_hits"), 0.0);
  EXPECT_EQ(statistic(s, "gi10_cache_overflow"), 0.0);
  for (const char* view : {"gi.diffuse", "gi10.irradiance"}) {
    ImageRGBA32F image = run.frame->debugViewImage(view);
    EXPECT_EQ(countNonFinitePixels(image), 0u) << view;
    EXPECT_GT(meanLuminance(image), 0.0) << view;
    writeDebugPng(image, view, 1.0f);
  }
  ImageRGBA32F with = run.frame->debugViewImage("composite");

  Gi10Run none(scene, gi10Settings(size, size, GiMode::None));
  none.frame->requestDebugView("composite");
  for (int i = 0; i < 2; ++i) none.frame->render(camera);
  ImageRGBA32F without = none.frame->debugViewImage("composite");
  std::printf("cornell %ux%u composite mean: gi10 %.4f, none %.4f\n", size, size,
              meanLuminance(with), meanLuminance(without));
  EXPECT_GT(meanLuminance(with), 1.1 * meanLuminance(without));
  EXPECT_EQ(run.context.validationErrorCount(), 0u);
}

// White furnace (the built-in `furnace`: albedo 0.5, emission 1 everywhere): radiance
// Le / (1 - albedo) = 2 in every direction, so irradiance / pi = 2 at every pixel. Every bounce
// after the first reaches the probes through feedback (§1.6) and the cache; off-screen hits
// have no feedback, so the level is below 2 by what they miss (docs/gi/gi10.md).
TEST(Gi10, FurnaceMatchesAnalyticIrradiance) {
  Gi10Run run(loadScene("furnace"), gi10Settings(64, 48));
  Camera camera = effectiveCamera(run.scene);
  for (const char* view : {"gi10.irradiance", "gi10.cache-view", "gi10.probes-view"})
    run.frame->requestDebugView(view);
  ImageRGBA32F gi = renderAveraged(run, camera, "gi.diffuse", 96, 16);
  double mean = meanLuminance(gi);
  // The stages' levels, for docs/gi/gi10.md.
  for (const char* view : {"gi10.irradiance", "gi10.cache-view", "gi10.probes-view"})
    std::printf("  %s mean %.4f\n", view, meanLuminance(run.frame->debugViewImage(view)));
  std::printf("furnace 64x48, 96 frames (last 16 averaged): mean irradiance/pi %.4f (analytic 2)\n",
              mean);
  writeDebugPng(gi, "furnace", 0.4f);
  EXPECT_NEAR(mean, 2.0, 0.06);
  EXPECT_EQ(statistic(run.frame->giStatistics(), "gi10_cache_overflow"), 0.0);
}

// The Cornell box against Cycles (Blender 3.4.1, 4096 spp, 256x256, every material Lambert;
// tests/test_reference.cpp checks our path tracer against the same image): the frame's output
// after 64 static frames at 256x256 within HDR-FLIP 0.12 and a mean luminance within 5 %
// (issue 23's gates). The output is `taa`'s, what tonemap shows: Cycles filters each pixel over
// its footprint, so the composite's single sample at each pixel centre would count every
// aliased edge as error (the composite is printed too). AMD reports GI-1.1 darker than path
// tracing (the cache holds two bounces plus what feedback recovers). Measured: docs/gi/gi10.md.
TEST(Gi10, CornellBoxAgainstCycles) {
  const std::string dir = test::sharedDir();
  HybridSettings settings = gi10Settings(256, 256);
  settings.taa.enabled = true;
  Gi10Run run(loadScene(dir + "/scenes/cornell_box/cornell_box.gltf"), settings);
  Camera camera = effectiveCamera(run.scene);
  run.frame->requestDebugView("composite");
  ImageRGBA32F output = renderAveraged(run, camera, "taa", 64, 1);
  ImageRGBA32F composite = run.frame->debugViewImage("composite");
  ImageRGBA32F cycles = readImage(dir + "/references/cornell_box/cycles_4096spp.exr");
  FlipResult flip = computeHdrFlip(output, cycles);
  double ratio = meanLuminance(output) / meanLuminance(cycles);
  std::vector<GiStatistic> s = run.frame->giStatistics();
  std::printf(
      "cornell_box 256x256, 64 frames: HDR-FLIP %.4f, mean ratio %.4f (the composite at pixel "
      "centres: %.4f, %.4f), live cells %.0f, overflow %.0f\n",
      flip.statistics.mean, ratio, computeHdrFlip(composite, cycles).statistics.mean,
      meanLuminance(composite) / meanLuminance(cycles), statistic(s, "gi10_live_cells"),
      statistic(s, "gi10_cache_overflow"));
  writeImage(test::tempDir("gi10") + "/cornell_box.exr", output);
  EXPECT_EQ(countNonFinitePixels(output), 0u);
  EXPECT_LE(flip.statistics.mean, 0.12);
  EXPECT_NEAR(ratio, 1.0, 0.05);
  EXPECT_EQ(statistic(s, "gi10_cache_overflow"), 0.0);
}

// 1,000 animated frames (issue 23) of `sunroom` (its scripted door and cube, the camera swaying,
// the sun turning) at 24x16 with the validation layers on: gi.diffuse and the composite stay
// finite.
TEST(Gi10, AnimatedRunStaysFinite) {
  Scene scene = loadScene("sunroom");
  Camera camera = effectiveCamera(scene);
  Gi10Run run(scene, gi10Settings(24, 16), true);
  run.frame->requestDebugView("composite");
  run.frame->requestDebugView("gi.diffuse");
  CameraPath path = swayCameraPath(camera, 20.0f, 0.3f, 8.0f);
  std::vector<glm::mat4> transforms(scene.instances.size());
  for (size_t i = 0; i < transforms.size(); ++i) transforms[i] = scene.instances[i].transform;
  size_t nonFinite = 0;
  for (int i = 0; i < 1000; ++i) {
    float t = float(i) / 30.0f;
    evaluateTransforms(scene.animation, t, {}, transforms);
    run.frame->setInstanceTransforms(transforms);
    Sun sun = scene.sun;
    float a = 0.5f * t;
    sun.direction = glm::normalize(glm::vec3(std::cos(a), -0.8f, std::sin(a)));
    run.frame->setSunAndSky(sun, scene.sky);
    run.frame->render(evaluateCameraPath(path, t));
    if (i % 10 == 9) {
      nonFinite += countNonFinitePixels(run.frame->debugViewImage("composite"));
      nonFinite += countNonFinitePixels(run.frame->debugViewImage("gi.diffuse"));
    }
  }
  EXPECT_EQ(nonFinite, 0u);
  EXPECT_EQ(statistic(run.frame->giStatistics(), "gi10_cache_overflow"), 0.0);
  EXPECT_EQ(run.context.validationErrorCount(), 0u);
}

// Issue 23's comparison after a sun jump, run as RestirGi.DISABLED_SunJumpRecoversWithinTenFrames
// runs Evolve (test::runSunJump: 48 frames under the mirrored sun, the jump back, the composite's
// relMSE against a 2,048-spp reference of the final light; 64x48, the desktop preset), with the
// same bound: within 1.5x of converged (frames 49-64) by frames 8-10. DISABLED: not met. Measured
// 2.19x (frames 8-10 0.215 against 0.098; before the jump 0.567), and the error still falls at
// frame 64 (0.092): a lighting cut restarts the probes, the cache and the accumulation, so
// GI-1.0 converges from cold. Evolve in the same harness: 1.58x (0.052 against 0.033); Lux 1.52x.
// docs/gi/comparison.md.
TEST(Gi10, DISABLED_SunJumpRecoversWithinTenFrames) {
  const test::SunroomSunJump jump = test::runSunroomSunJump(gi10Settings(64, 48));
  EXPECT_GT(jump.run.before, 3.0 * jump.run.converged());  // a real change: the test has teeth
  EXPECT_LE(jump.run.recovered(), 1.5 * jump.run.converged());
  EXPECT_EQ(jump.validationErrors, 0u);
}

}  // namespace
}  // namespace bounce
