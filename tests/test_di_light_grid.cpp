// ReSTIR DI's world-space light grid (ReGIR; src/di/di_light_grid.h, shaders/di/light_grid.glsl,
// docs/di.md) and the frame without DI lights:
//   - RGB9E5, the emitters' mean emission the targets read: positive stays positive, 9 bits;
//   - unbiased with the grid: manylights with the grid forced on (threshold 0, small cells, so
//     that cells hold different lights), the unbiased configuration's mean over independent runs
//     against the reference path tracer limited to direct light: every 8x8 block within 3
//     standard errors, image relMSE (less the noise's share) at most 0.02, as the alias table's
//     own test (test_restir_di.cpp);
//   - the grid finds the lights a point sees: on city by night, one frame of uniform DI (no
//     reuse) varies less with the grid than with the alias table alone at the same candidates;
//   - no lights, no DI: a scene without DI lights runs no di-* pass, and its frame is the frame
//     of --di off.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "harness.h"

#include "di/di_light_grid.h"
#include "frame/hybrid_frame.h"
#include "frame/presets.h"
#include "lighting/light_table.h"
#include "reference/path_tracer.h"
#include "rt/gpu_scene.h"
#include "scene/load.h"
#include "scene/scene_options.h"
#include "scene/time_of_day.h"
#include "tools/metrics.h"
#include "vk/context.h"

namespace bounce {
namespace {

double pixelLuminance(const ImageRGBA32F& image, size_t i) {
  return 0.2126 * image.pixels[4 * i] + 0.7152 * image.pixels[4 * i + 1] +
         0.0722 * image.pixels[4 * i + 2];
}

// The hybrid frame lit by DI alone: no GI, no reflection rays, full-resolution shadows.
HybridSettings diSettings(uint32_t width, uint32_t height, const DiSettings& di) {
  HybridSettings settings = presetSettings(Preset::Desktop);
  settings.width = width;
  settings.height = height;
  settings.shadows.divisor = 1;
  settings.reflections.divisor = 0;
  settings.gi = GiMode::None;
  settings.di = di;
  return settings;
}

ImageRGBA32F meanImage(const std::vector<ImageRGBA32F>& images) {
  ImageRGBA32F mean = images.at(0);
  for (size_t k = 1; k < images.size(); ++k)
    for (size_t i = 0; i < mean.pixels.size(); ++i) mean.pixels[i] += images[k].pixels[i];
  for (float& v : mean.pixels) v /= float(images.size());
  return mean;
}

// Each 8x8 block's mean luminance in each of a set of independent images: its mean over the
// images and the standard error of that mean.
struct BlockMeans {
  std::vector<std::vector<double>> perImage;  // [image][block]

  void add(const ImageRGBA32F& image) {
    const uint32_t bx = image.width / 8, by = image.height / 8;
    std::vector<double> blocks(size_t(bx) * by, 0.0);
    for (uint32_t y = 0; y < by * 8; ++y)
      for (uint32_t x = 0; x < bx * 8; ++x)
        blocks[(y / 8) * bx + x / 8] += pixelLuminance(image, size_t(y) * image.width + x) / 64.0;
    perImage.push_back(blocks);
  }
  double mean(size_t b) const {
    double s = 0.0;
    for (const auto& v : perImage) s += v[b];
    return s / double(perImage.size());
  }
  double standardError(size_t b) const {
    const double m = mean(b), n = double(perImage.size());
    double s = 0.0;
    for (const auto& v : perImage) s += (v[b] - m) * (v[b] - m);
    return std::sqrt(s / (n - 1.0) / n);
  }
};

// The relMSE noise alone gives, expected (as test_restir_di.cpp's): per pixel and channel, the
// variance of both means over the reference's square.
double noiseRelMse(const std::vector<ImageRGBA32F>& a, const std::vector<ImageRGBA32F>& b,
                   const ImageRGBA32F& referenceMean) {
  auto varianceOfMean = [](const std::vector<ImageRGBA32F>& images, size_t k) {
    double sum = 0.0, sumSq = 0.0;
    for (const ImageRGBA32F& image : images) {
      sum += image.pixels[k];
      sumSq += double(image.pixels[k]) * image.pixels[k];
    }
    const double n = double(images.size()), m = sum / n;
    return std::max(sumSq - n * m * m, 0.0) / (n - 1.0) / n;
  };
  double total = 0.0;
  for (size_t i = 0; i < referenceMean.pixelCount(); ++i)
    for (size_t c = 0; c < 3; ++c) {
      const size_t k = 4 * i + c;
      const double r = referenceMean.pixels[k];
      total += (varianceOfMean(a, k) + varianceOfMean(b, k)) / (r * r + kRelMseEpsilon);
    }
  return total / double(3 * referenceMean.pixelCount());
}

TEST(DiLightGrid, Rgb9e5KeepsPositiveChannelsPositive) {
  const glm::vec3 colours[] = {{1.0f, 0.484f, 0.155f}, {3.64f, 1.76f, 0.564f}, {1e-6f, 0.0f, 5.0f},
                               {65000.0f, 1.0f, 0.0f}, {1e-30f, 0.0f, 0.0f},   {0.0f, 0.0f, 0.0f}};
  for (const glm::vec3& c : colours) {
    const glm::vec3 d = decodeRgb9e5(encodeRgb9e5(c));
    const float largest = std::max(c.x, std::max(c.y, c.z));
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(d[k] > 0.0f, c[k] > 0.0f) << "channel " << k << " of " << c[k];
      // 9-bit mantissas under the largest channel's exponent: within one step, at most
      // largest / 256 (a positive channel below half a step is rounded up to one).
      if (largest > 1e-6f) EXPECT_NEAR(d[k], c[k], largest / 256.0f) << "channel " << k;
    }
  }
}

// Issue 20's unbiased test with the grid as the candidate source: manylights (64 point lights in
// a room), threshold 0 so the grid is on, 16^3 cells of 0.5 m with 8 slots (the room is ~10 m:
// cells differ, and points beyond the 8 m grid take the alias table's candidates only), the
// unbiased configuration, 16 independent runs x 4 frames against the reference with one
// scattering event in 8 batches of 128 spp. A wrong MIS weight between grid and alias
// candidates, or a slot's W taken for a pdf, shifts block means by many standard errors.
TEST(DiLightGrid, UnbiasedWithTheGridMatchesDirectLightReference) {
  const uint32_t width = 32, height = 24;
  const int runs = 16, framesPerRun = 4, batches = 8;
  Scene scene = loadScene("manylights");
  Camera camera = effectiveCamera(scene);
  vk::Context context(vk::contextOptionsFromEnvironment());
  GpuScene gpuScene(context, scene);
  DiSettings di = DiSettings::unbiasedConfiguration();
  di.lightGridThreshold = 0;
  di.lightGridCellSize = 0.5f;
  di.lightGridCellsX = di.lightGridCellsY = di.lightGridCellsZ = 16;
  di.lightGridSlots = 8;
  HybridFrame frame(context, gpuScene, scene, diSettings(width, height, di));
  frame.requestDebugView("di-shade");
  BlockMeans hybrid;
  std::vector<ImageRGBA32F> runMeans;
  for (int run = 0; run < runs; ++run) {
    frame.resetHistory();
    std::vector<ImageRGBA32F> frames;
    for (int i = 0; i < framesPerRun; ++i) {
      frame.render(camera);
      frames.push_back(frame.debugViewImage("di-shade"));
    }
    runMeans.push_back(meanImage(frames));
    hybrid.add(runMeans.back());
  }
  const ImageRGBA32F hybridMean = meanImage(runMeans);

  ReferencePathTracer tracer(context, gpuScene, scene);
  BlockMeans reference;
  std::vector<ImageRGBA32F> referenceBatches;
  for (int b = 0; b < batches; ++b) {
    ReferenceOptions options;
    options.width = width;
    options.height = height;
    options.samplesPerPixel = 128;
    options.maxBounces = 1;
    options.pixelCentre = true;
    options.seed = uint32_t(1 + b);
    referenceBatches.push_back(tracer.render(camera, options).image);
    reference.add(referenceBatches.back());
  }
  const ImageRGBA32F referenceMean = meanImage(referenceBatches);

  double worstZ = 0.0;
  size_t outside = 0;
  const size_t blocks = hybrid.perImage.at(0).size();
  for (size_t b = 0; b < blocks; ++b) {
    const double se = std::hypot(hybrid.standardError(b), reference.standardError(b));
    const double z = std::abs(hybrid.mean(b) - reference.mean(b)) / std::max(se, 1e-12);
    worstZ = std::max(worstZ, z);
    if (z > 3.0) {
      ++outside;
      std::printf("  block %zu: grid %.4f +- %.4f, reference %.4f +- %.4f (%.1f SE)\n", b,
                  hybrid.mean(b), hybrid.standardError(b), reference.mean(b),
                  reference.standardError(b), z);
    }
  }
  const double relMse = relativeMeanSquaredError(hybridMean, referenceMean);
  const double noise = noiseRelMse(runMeans, referenceBatches, referenceMean);
  const double ratio = test::meanLuminance(hybridMean) / test::meanLuminance(referenceMean);
  std::printf(
      "manylights %ux%u, light grid forced on, --di-unbiased, %d runs x %d frames: relMSE %.4f "
      "(noise's share %.4f), mean ratio %.4f, worst block %.2f SE (%zu of %zu beyond 3)\n",
      width, height, runs, framesPerRun, relMse, noise, ratio, worstZ, outside, blocks);
  EXPECT_EQ(outside, 0u);
  EXPECT_LE(relMse - noise, 0.02);
  EXPECT_EQ(countNonFinitePixels(hybridMean), 0u);
  EXPECT_EQ(context.validationErrorCount(), 0u);
}

// `city` at 22 h: the street lights are its only DI lights.
Scene cityAtNight() {
  Scene scene = loadScene("city");
  const Sun daySun = scene.sun;
  const Sky daySky = scene.sky;
  applyTimeOfDay(22.0f, daySun, daySky, scene.sun, scene.sky);
  return scene;
}

// The avenue view of test_restir_di.cpp's city tests.
Camera cityStreetCamera() {
  Camera camera;
  camera.position = {3.0f, 5.0f, 170.0f};
  camera.target = {0.0f, 0.0f, 110.0f};
  camera.verticalFovDegrees = 60.0f;
  return camera;
}

// Per-pixel variance (luminance) of one uniform-DI frame over `runs` independent frames,
// averaged over the pixels.
double oneFrameVariance(HybridFrame& frame, const Camera& camera, int runs) {
  std::vector<double> sum, sumSq;
  for (int run = 0; run < runs; ++run) {
    frame.render(camera);
    const ImageRGBA32F image = frame.debugViewImage("di-shade");
    if (sum.empty()) sum.assign(image.pixelCount(), 0.0), sumSq.assign(image.pixelCount(), 0.0);
    for (size_t i = 0; i < image.pixelCount(); ++i) {
      const double v = pixelLuminance(image, i);
      sum[i] += v;
      sumSq[i] += v * v;
    }
  }
  double total = 0.0;
  for (size_t i = 0; i < sum.size(); ++i) {
    const double m = sum[i] / runs;
    total += std::max(sumSq[i] - runs * m * m, 0.0) / double(runs - 1);
  }
  return total / double(sum.size());
}

// The grid's purpose: a street point sees a handful of city's 3,072 local lights, which power
// draws from the whole city rarely pick; the point's cell holds lights near it. One frame of
// uniform DI (8 candidates, no reuse) over 32 independent frames on the avenue view: with the
// grid the per-pixel variance is lower than with the alias table alone (both unbiased: the same
// integral), and the grid is on by default there (3,072 local lights, above the threshold).
TEST(DiLightGrid, GridLowersOneFrameVarianceOnCityByNight) {
  const uint32_t width = 24, height = 14;
  const int runs = 32;
  Scene scene = cityAtNight();
  const Camera camera = cityStreetCamera();
  vk::Context context(vk::contextOptionsFromEnvironment());
  GpuScene gpuScene(context, scene);
  DiSettings grid;
  grid.mode = DiMode::Uniform;
  DiSettings alias = grid;
  alias.lightGridThreshold = ~0u;
  HybridFrame gridFrame(context, gpuScene, scene, diSettings(width, height, grid));
  gridFrame.requestDebugView("di-shade");
  const double gridVariance = oneFrameVariance(gridFrame, camera, runs);
  HybridFrame aliasFrame(context, gpuScene, scene, diSettings(width, height, alias));
  aliasFrame.requestDebugView("di-shade");
  const double aliasVariance = oneFrameVariance(aliasFrame, camera, runs);
  std::printf(
      "city at 22 h %ux%u, uniform DI, one frame over %d runs: variance with the grid %.4g, alias "
      "table alone %.4g: %.1fx lower\n",
      width, height, runs, gridVariance, aliasVariance, aliasVariance / gridVariance);
  EXPECT_LT(gridVariance, aliasVariance);
  EXPECT_EQ(context.validationErrorCount(), 0u);
}

// A scene without DI lights (sunroom-glossy: the sun and the sky only) runs no di-* pass, and
// its composite is the --di off frame's, texel for texel.
TEST(DiLightGrid, NoLightsRunNoDiPass) {
  const uint32_t width = 24, height = 16;
  Scene scene = loadScene("sunroom-glossy");
  Camera camera = effectiveCamera(scene);
  vk::Context context(vk::contextOptionsFromEnvironment());
  GpuScene gpuScene(context, scene);
  HybridFrame restir(context, gpuScene, scene, diSettings(width, height, DiSettings{}));
  restir.requestDebugView("composite");
  size_t diPasses = 0, passes = 0;
  for (int i = 0; i < 2; ++i)
    for (const vk::PassTiming& t : restir.render(camera)) {
      ++passes;
      if (t.name.rfind("di-", 0) == 0) ++diPasses;
    }
  DiSettings offSettings;
  offSettings.mode = DiMode::Off;
  HybridFrame off(context, gpuScene, scene, diSettings(width, height, offSettings));
  off.requestDebugView("composite");
  for (int i = 0; i < 2; ++i) off.render(camera);
  const ImageRGBA32F a = restir.debugViewImage("composite");
  const ImageRGBA32F b = off.debugViewImage("composite");
  std::printf("sunroom-glossy: %zu di-* passes of %zu timed; composite mean %.5g (--di off %.5g)\n",
              diPasses, passes, test::meanLuminance(a), test::meanLuminance(b));
  EXPECT_EQ(diPasses, 0u);
  EXPECT_EQ(a.pixels, b.pixels);
  EXPECT_EQ(context.validationErrorCount(), 0u);
}

}  // namespace
}  // namespace bounce
