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
//     of --di off;
//   - the pool's size fills di-light-grid's workgroup: a multiple of 64 from 64 to 4096, anything
//     else refused by name.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "di_test_common.h"
#include "harness.h"

#include "core/error.h"
#include "di/di_light_grid.h"
#include "frame/hybrid_frame.h"
#include "lighting/light_table.h"
#include "rt/gpu_scene.h"
#include "scene/load.h"
#include "scene/scene_options.h"
#include "tools/metrics.h"
#include "vk/context.h"

namespace bounce {
namespace {

using test::cityAtNight;
using test::cityStreetCamera;
using test::compareWithDirectReference;
using test::DirectComparison;
using test::DirectComparisonRuns;
using test::directReference;
using test::diSettings;
using test::meanImage;
using test::oneFrameVariance;

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

// di-light-grid gives each of a cell's 64 threads an equal share of the pool, so a size that is
// not a multiple of 64 would silently draw fewer candidates than asked: it is refused, with the
// setting named and the range.
TEST(DiLightGrid, PoolSizeMustFillTheWorkgroup) {
  for (uint32_t accepted : {64u, 256u, 4096u}) {
    DiSettings s;
    s.lightGridBuildCandidates = accepted;
    EXPECT_NO_THROW(validate(s)) << accepted;
  }
  for (uint32_t refused : {0u, 8u, 100u, 4160u}) {
    DiSettings s;
    s.lightGridBuildCandidates = refused;
    try {
      validate(s);
      ADD_FAILURE() << refused << " accepted";
    } catch (const Error& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find("build candidates " + std::to_string(refused)), std::string::npos)
          << message;
      EXPECT_NE(message.find("multiple of 64"), std::string::npos) << message;
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
  const DirectComparisonRuns counts{runs, framesPerRun, batches, 128, 3.0};
  const DirectComparison c = compareWithDirectReference(context, gpuScene, scene, camera, frame,
                                                        width, height, counts, "grid");
  std::printf(
      "manylights %ux%u, light grid forced on, --di-unbiased, %d runs x %d frames: relMSE %.4f "
      "(noise's share %.4f), mean ratio %.4f, worst block %.2f SE (%zu of %zu beyond 3)\n",
      width, height, runs, framesPerRun, c.relMse, c.noiseShare, c.meanRatio, c.blocks.worstZ,
      c.blocks.outside, c.blockCount);
  EXPECT_EQ(c.blocks.outside, 0u);
  EXPECT_LE(c.relMse - c.noiseShare, 0.02);
  EXPECT_EQ(countNonFinitePixels(c.hybridMean), 0u);
  EXPECT_EQ(context.validationErrorCount(), 0u);
}

// The grid's purpose: a street point sees a handful of city's 3,072 local lights, which power
// draws from the whole city rarely pick; the point's cell holds lights near it. One frame of
// uniform DI (8 candidates, no reuse) over 32 independent frames on the avenue view: with the
// grid the per-pixel variance is lower than with the alias table alone (both unbiased: the same
// integral), and the grid is on by default there (3,072 local lights, above the threshold).
TEST(DiLightGrid, GridLowersOneFrameVarianceOnCityByNight) {
  const uint32_t width = 24, height = 14;
  const int runs = 32;
  Scene scene = cityAtNight(true);
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

// The grid's debug view (di.grid-cells, di-light-grid-view): declared only while requested, it
// colours each pixel by its cell, so the street view shows several cells, every pixel with a
// surface inside the grid lit and the sky black; a scene without the grid refuses it by name.
TEST(DiLightGrid, GridViewShowsTheCellsOnlyWhenRequested) {
  const uint32_t width = 48, height = 27;
  Scene scene = cityAtNight(true);
  const Camera camera = cityStreetCamera();
  vk::Context context(vk::contextOptionsFromEnvironment());
  GpuScene gpuScene(context, scene);
  HybridFrame frame(context, gpuScene, scene, diSettings(width, height, DiSettings{}));
  auto declares = [&](const char* pass) {
    const std::vector<std::string> names = frame.passNames();
    return std::find(names.begin(), names.end(), pass) != names.end();
  };
  frame.render(camera);
  EXPECT_FALSE(declares("di-light-grid-view"));
  frame.requestDebugView(kDiGridView);
  frame.requestDebugView("gbuffer.depth");
  frame.render(camera);
  EXPECT_TRUE(declares("di-light-grid-view"));
  const ImageRGBA32F view = frame.debugViewImage(kDiGridView);
  const ImageRGBA32F depth = frame.debugViewImage("gbuffer.depth");
  size_t surfaces = 0, litSurfaces = 0, litSky = 0;
  std::vector<uint32_t> colours;
  for (size_t i = 0; i < view.pixelCount(); ++i) {
    const float* p = &view.pixels[4 * i];
    const bool lit = p[0] > 0.0f || p[1] > 0.0f || p[2] > 0.0f;
    const bool surface = depth.pixels[4 * i] > 0.0f && std::isfinite(depth.pixels[4 * i]);
    surfaces += surface;
    litSurfaces += surface && lit;
    litSky += !surface && lit;
    if (lit)
      colours.push_back(uint32_t(p[0] * 255.0f) << 16 | uint32_t(p[1] * 255.0f) << 8 |
                        uint32_t(p[2] * 255.0f));
  }
  std::sort(colours.begin(), colours.end());
  const size_t distinct = size_t(std::unique(colours.begin(), colours.end()) - colours.begin());
  std::printf(
      "city at 22 h %ux%u, di.grid-cells: %zu of %zu surface pixels in a cell, %zu sky "
      "pixels coloured, %zu distinct colours\n",
      width, height, litSurfaces, surfaces, litSky, distinct);
  EXPECT_GT(surfaces, view.pixelCount() / 2);
  EXPECT_GT(litSurfaces, surfaces * 9 / 10);  // the street view lies within the 160 m grid
  EXPECT_EQ(litSky, 0u);
  EXPECT_GE(distinct, 4u);
  EXPECT_EQ(countNonFinitePixels(view), 0u);
  frame.clearDebugViews();
  frame.render(camera);
  EXPECT_FALSE(declares("di-light-grid-view"));
  EXPECT_EQ(context.validationErrorCount(), 0u);

  Scene room = loadScene("manylights");  // 64 lights: below the grid's threshold
  GpuScene roomGpu(context, room);
  HybridFrame roomFrame(context, roomGpu, room, diSettings(16, 16, DiSettings{}));
  roomFrame.requestDebugView(kDiGridView);
  try {
    roomFrame.render(effectiveCamera(room));
    ADD_FAILURE() << "di.grid-cells accepted without a light grid";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(kDiGridView), std::string::npos) << e.what();
  }
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
