// Evolve's clipmap irradiance cache (src/gi/evolve/cache/clipmap_cache.h) through `--gi cache` on
// lavapipe, at small resolutions. gi.diffuse is irradiance / pi from everything but the sun's
// and punctual lights' direct light at the point itself, so it is compared with a path-traced
// estimate of exactly that (shaders/gi/evolve/reference_irradiance.comp: the same tracer and
// direct-light sample, cosine-distributed rays, Lambert surfaces, no cache).
//   - furnace: converges to Le / (1 - albedo) = 2 within 2%;
//   - cornell, sunroom: agrees with the path-traced irradiance at points over the view (lit and
//     shadowed, both sides of the room) and holds more than the single-bounce light;
//   - lifetimes: cells unused for 4 frames are freed, not before; the live count stays under
//     the cap in a fly-through of `city` (and under a lowered cap that the fly-through
//     exhausts); scrolling frees only cells that left their window and keeps the rest;
//   - no NaN/Inf in any entry or cell after 1,000 frames of the animated sunroom;
//   - scheduling: the same cells, entries and composite on 1 and on 4 lavapipe threads;
//   - validation layers silent throughout.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "frame/presets.h"
#include "harness.h"

#include "frame/animation_player.h"
#include "frame/hybrid_frame.h"
#include "lighting/gpu_light_tables.h"
#include "passes/image_pass.h"
#include "passes/primary_view.h"
#include "rt/gpu_scene.h"
#include "scene/load.h"
#include "scene/scene_options.h"
#include "shared/camera.h"
#include "shared/clipmap_cache_io.h"
#include "vk/context.h"

namespace bounce {
namespace {

using test::decodeOctahedral;
using test::meanLuminance;

struct CacheRun {
  vk::Context context;
  Scene scene;
  std::unique_ptr<GpuScene> gpuScene;
  std::unique_ptr<HybridFrame> frame;

  CacheRun(const std::string& name, const HybridSettings& settings)
      : context(vk::contextOptionsFromEnvironment({})), scene(loadScene(name)) {
    gpuScene = std::make_unique<GpuScene>(context, scene);
    frame = std::make_unique<HybridFrame>(context, *gpuScene, scene, settings);
  }
};

HybridSettings cacheSettings(uint32_t width, uint32_t height, Preset preset) {
  HybridSettings s = presetSettings(preset);
  s.width = width;
  s.height = height;
  s.gi = GiMode::Cache;
  s.lambert = true;
  return s;
}

double statistic(const std::vector<GiStatistic>& statistics, const std::string& name) {
  for (const GiStatistic& s : statistics)
    if (s.name == name) return s.value;
  ADD_FAILURE() << "no statistic " << name;
  return -1.0;
}

float luminance(const glm::vec3& c) {
  return glm::dot(c, glm::vec3(0.2126f, 0.7152f, 0.0722f));
}

// The frame constants the reference estimator needs (sun, sky, Lambert); the test scenes have
// no KHR lights.
gpu::FrameConstants referenceFrameConstants(const Scene& scene) {
  gpu::FrameConstants c{};
  c.towardSun = -glm::normalize(scene.sun.direction);
  c.sunCosHalfAngle = std::cos(glm::radians(0.5f * scene.sun.angularDiameterDegrees));
  c.sunIrradiance = scene.sun.irradiance * scene.sun.color;
  c.skyModel =
      scene.sky.model == SkyModel::Daylight ? gpu::FRAME_SKY_DAYLIGHT : gpu::FRAME_SKY_CONSTANT;
  c.skyRadiance = scene.sky.radiance;
  c.skyTurbidity = scene.sky.turbidity;
  c.skyScale = daylightSkyScale(scene.sun);
  c.flags = gpu::FRAME_FLAG_LAMBERT;
  return c;
}

// Path-traced irradiance / pi at probes (see the top of the file): 64 threads x `samples`.
std::vector<glm::vec3> referenceIrradiance(CacheRun& run,
                                           const std::vector<gpu::IrradianceProbe>& probes,
                                           uint32_t samplesPerThread, uint32_t maxBounces) {
  vk::Context& context = run.context;
  ComputePass pass(context, *run.gpuScene, "gi/evolve/reference_irradiance", 0,
                   sizeof(gpu::ReferenceIrradianceConstants));
  gpu::FrameConstants constants = referenceFrameConstants(run.scene);
  GpuLightTables lights(context, *run.gpuScene, run.scene);
  vk::Buffer frame = vk::uploadBuffer(context, std::as_bytes(std::span(&constants, 1)),
                                      VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "test.frame");
  vk::Buffer probeBuffer = vk::uploadBuffer(context, std::as_bytes(std::span(probes)),
                                            VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "test.probes");
  size_t count = probes.size() * gpu::CLIPMAP_GROUP_SIZE;
  vk::Buffer sums(context, count * sizeof(glm::vec4),
                  VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT |
                      VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                  vk::MemoryUse::DeviceOnly, "test.sums");
  // A few samples per thread and dispatch: lavapipe ends an invocation's loops after 65,535
  // iterations in all (traversal included), which 96 multi-bounce paths in one thread exceed.
  const uint32_t samplesPerDispatch = 4;
  std::vector<glm::vec4> total(count, glm::vec4(0.0f));
  std::vector<glm::vec4> out(count);
  for (uint32_t batch = 0; batch * samplesPerDispatch < samplesPerThread; ++batch) {
    gpu::ReferenceIrradianceConstants push{
        frame.address(),         probeBuffer.address(), sums.address(), lights.address(),
        uint32_t(probes.size()), samplesPerDispatch,    maxBounces,     12345u + batch};
    context.submitAndWait([&](VkCommandBuffer cmd) {
      // Zeroed first, so a thread that never wrote its sum shows as w = 0 (checked below).
      vkCmdFillBuffer(cmd, sums.handle(), 0, VK_WHOLE_SIZE, 0u);
      VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER, nullptr,
                              VK_ACCESS_TRANSFER_WRITE_BIT,
                              VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT};
      vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT,
                           VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 1, &barrier, 0, nullptr, 0,
                           nullptr);
      pass.bind(cmd, push);
      vkCmdDispatch(cmd, uint32_t(probes.size()), 1, 1);
    });
    vk::downloadBuffer(context, sums, std::as_writable_bytes(std::span(out)));
    for (size_t i = 0; i < count; ++i) total[i] += out[i];
  }
  const float expectedSamples =
      float((samplesPerThread + samplesPerDispatch - 1) / samplesPerDispatch * samplesPerDispatch);
  std::vector<glm::vec3> result(probes.size(), glm::vec3(0.0f));
  for (size_t p = 0; p < probes.size(); ++p) {
    double samples = 0.0;
    for (uint32_t t = 0; t < gpu::CLIPMAP_GROUP_SIZE; ++t) {
      const glm::vec4& sum = total[p * gpu::CLIPMAP_GROUP_SIZE + t];
      EXPECT_EQ(sum.w, expectedSamples)
          << "reference thread " << t << " of probe " << p << " did not finish";
      result[p] += glm::vec3(sum);
      samples += sum.w;
    }
    result[p] /= float(samples);
  }
  return result;
}

// Mean gi.diffuse per pixel over the last `average` of `frames` frames of a static view.
ImageRGBA32F renderAveraged(CacheRun& run, const Camera& camera, int frames, int average) {
  run.frame->requestDebugView("gi-cache-lookup");
  ImageRGBA32F sum;
  for (int i = 0; i < frames; ++i) {
    run.frame->render(camera);
    if (i < frames - average) continue;
    ImageRGBA32F gi = run.frame->debugViewImage("gi-cache-lookup");
    size_t bad = 0;
    for (int y = 0; y < gi.height; ++y)
      for (int x = 0; x < gi.width; ++x) {
        glm::vec4 p = gi.at(x, y);
        // gi-cache-lookup writes alpha 1 everywhere: alpha 0 is a pixel it never stored.
        if (!std::isfinite(p.x + p.y + p.z) || std::min({p.x, p.y, p.z}) < 0.0f || p.w != 1.0f)
          ++bad;
      }
    EXPECT_EQ(bad, 0u) << "frame " << i << ": negative, non-finite or unwritten gi.diffuse pixels";
    if (sum.pixels.empty()) sum = ImageRGBA32F(gi.width, gi.height, glm::vec4(0.0f));
    for (size_t k = 0; k < gi.pixels.size(); ++k) sum.pixels[k] += gi.pixels[k] / float(average);
  }
  return sum;
}

TEST(ClipmapCache, FurnaceConvergesToAnalyticIrradiance) {
  // Albedo 0.5, emission 1 everywhere: radiance Le / (1 - a) = 2 in every direction, so
  // irradiance / pi = 2 at every point. Desktop rays (4 + 4 validation per cell per frame).
  CacheRun run("furnace", cacheSettings(24, 16, Preset::Desktop));
  Camera camera = effectiveCamera(run.scene);
  ImageRGBA32F gi = renderAveraged(run, camera, 96, 16);
  double sum = 0.0;
  int pixels = 0;
  float lowest = 1e9f, highest = 0.0f;
  for (int y = 0; y < gi.height; ++y)
    for (int x = 0; x < gi.width; ++x) {
      float v = luminance(glm::vec3(gi.at(x, y)));
      sum += v;
      lowest = std::min(lowest, v);
      highest = std::max(highest, v);
      ++pixels;
    }
  double mean = sum / pixels;
  std::printf(
      "furnace 24x16, 96 frames (last 16 averaged): mean irradiance/pi %.4f (analytic 2), pixels "
      "%.3f..%.3f\n",
      mean, lowest, highest);
  EXPECT_NEAR(mean, 2.0, 0.04);
  EXPECT_GT(lowest, 2.0 * 0.9);
  EXPECT_LT(highest, 2.0 * 1.1);
  EXPECT_EQ(run.context.validationErrorCount(), 0u);
}

// The first frames of a cache (and those after a lighting cut) are a full refresh
// (ClipmapCacheSettings::fullRefreshFrames): every cell traces all 16 entries each frame,
// fullRefreshBounces (3) times, so light crosses three bounces per frame. On `sunroom`, lit
// through one window, most of the light is several bounces deep. Mean of gi-cache-lookup over
// frames 5-8 and 13-16 against frames 49-64 of the same run (the converged level).
// The levels vary from run to run (cells are allocated in a racing order). They also varied
// with the CPU lavapipe runs on until the cell wobble's sine got its phase reduced to one period
// first (cache_lookup.glsl): without AVX/FMA the converged level came out ~3 % higher and the
// early frames ~2 % lower. Measured, frames 5-8 | 13-16, before that change:
//   with AVX2 + FMA (this workstation, 8 runs): three bounces per frame 0.92-0.98 | 0.97-1.04,
//     one bounce 0.70-0.75 | 0.92-1.01, no refresh (desktop: each entry refreshed every 4
//     frames, diluted by its running mean) 0.48-0.57 | 0.66-0.73;
//   without AVX (CI's machine; GALLIUM_OVERRIDE_CPU_CAPS=sse4.1 reproduces its numbers, 5
//     runs): three bounces 0.89-0.94 | 0.94-0.96, one bounce 0.71-0.74 | 0.90-0.94, no
//     refresh 0.50-0.51 | 0.66-0.68;
// after it: three bounces 0.94-0.98 with AVX2 (2 runs), 0.935-0.948 without AVX (3 runs).
// Bounds, below the lowest seen by about the spread of a run: three bounces >= 0.85 by frames
// 5-8 and at most half of one bounce's shortfall there (measured 0.12-0.39 of it); one bounce
// >= 0.85 by frames 13-16 and at least 0.05 behind three bounces at frames 5-8; no refresh at
// least 0.1 behind one bounce at frames 13-16.
TEST(ClipmapCache, FullRefreshRebuildsMultiBounceLightWithinSixteenFrames) {
  struct Levels {
    double frames5to8, frames13to16;
  };
  auto run = [](uint32_t refreshFrames, uint32_t bounces, double& converged) {
    HybridSettings settings = cacheSettings(32, 18, Preset::Desktop);
    settings.cache.fullRefreshFrames = refreshFrames;
    settings.cache.fullRefreshBounces = bounces;
    CacheRun r("sunroom", settings);
    Camera camera = effectiveCamera(r.scene);
    double a = meanLuminance(renderAveraged(r, camera, 8, 4));
    double b = meanLuminance(renderAveraged(r, camera, 8, 4));
    if (converged <= 0.0) converged = meanLuminance(renderAveraged(r, camera, 48, 16));
    EXPECT_EQ(r.context.validationErrorCount(), 0u);
    return Levels{a / converged, b / converged};
  };
  double converged = 0.0;
  Levels three = run(16, 3, converged);
  Levels one = run(16, 1, converged);
  Levels none = run(0, 1, converged);
  std::printf(
      "sunroom cache, mean of frames 5-8 | 13-16 / frames 49-64: 3 bounces per refresh "
      "frame %.3f | %.3f, 1 bounce %.3f | %.3f, no refresh %.3f | %.3f\n",
      three.frames5to8, three.frames13to16, one.frames5to8, one.frames13to16, none.frames5to8,
      none.frames13to16);
  EXPECT_GE(three.frames5to8, 0.85);
  EXPECT_LE(1.0 - three.frames5to8, 0.5 * (1.0 - one.frames5to8));
  EXPECT_GE(one.frames13to16, 0.85);
  EXPECT_LE(one.frames5to8, three.frames5to8 - 0.05);
  EXPECT_LE(none.frames13to16, one.frames13to16 - 0.1);
}

struct Agreement {
  std::vector<float> cache, multi, single;
  std::vector<bool> sunlit;
};

// The luminance of gi.diffuse around pixel (x, y): the mean over the 3x3 neighbours on the same
// surface (view depth within 5 %, normals within ~25 degrees). A cell's reservoirs change slowly,
// so averaging frames alone leaves per-pixel noise of ~15 % that says nothing about the cache's
// bias, which is what the points are for; the cells are far wider than 3 pixels here.
float localMean(const ImageRGBA32F& gi, const ImageRGBA32F& depth, const ImageRGBA32F& normals,
                int x, int y) {
  const float z = depth.at(x, y).x;
  const glm::vec3 n = decodeOctahedral(glm::vec2(normals.at(x, y)));
  float sum = 0.0f;
  int count = 0;
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      int u = x + dx, v = y + dy;
      if (u < 0 || v < 0 || u >= gi.width || v >= gi.height) continue;
      float zn = depth.at(u, v).x;
      if (!(std::abs(zn - z) < 0.05f * z)) continue;
      if (glm::dot(decodeOctahedral(glm::vec2(normals.at(u, v))), n) < 0.9f) continue;
      sum += luminance(glm::vec3(gi.at(u, v)));
      ++count;
    }
  return sum / float(count);  // count >= 1: the centre always qualifies
}

// gi.diffuse (averaged over frames) and the path-traced irradiance / pi at a grid of pixels.
Agreement measureAgreement(const std::string& sceneName, uint32_t width, uint32_t height,
                           int frames) {
  CacheRun run(sceneName, cacheSettings(width, height, Preset::Desktop));
  Camera camera = effectiveCamera(run.scene);
  run.frame->requestDebugView("gbuffer.depth");
  run.frame->requestDebugView("gbuffer.normals");
  run.frame->requestDebugView("shadows.visibility");
  ImageRGBA32F gi = renderAveraged(run, camera, frames, 32);
  ImageRGBA32F depth = run.frame->debugViewImage("gbuffer.depth");
  ImageRGBA32F normals = run.frame->debugViewImage("gbuffer.normals");
  ImageRGBA32F shadows = run.frame->debugViewImage("shadows.visibility");
  gpu::GpuCamera cam = makeGpuCamera(camera, width, height, run.gpuScene->bounds());

  std::vector<gpu::IrradianceProbe> probes;
  Agreement a;
  auto addProbe = [&](int x, int y) {
    glm::vec2 pixel(x + 0.5f, y + 0.5f);
    glm::vec3 dir = gpu::cameraRayDirection(cam, pixel, glm::vec2(width, height));
    gpu::IrradianceProbe p{};
    p.position = cam.position + dir * (depth.at(x, y).x / glm::dot(dir, cam.forward));
    p.normal = decodeOctahedral(glm::vec2(normals.at(x, y)));
    probes.push_back(p);
    a.cache.push_back(localMean(gi, depth, normals, x, y));
    a.sunlit.push_back(shadows.at(x, y).x > 0.5f);
  };
  // A grid over the view (mostly shadowed surfaces in these rooms) ...
  const int columns = 6, rows = 4;
  for (int j = 0; j < rows; ++j)
    for (int i = 0; i < columns; ++i) {
      int x = int((i + 0.5f) / columns * width), y = int((j + 0.5f) / rows * height);
      if (depth.at(x, y).x > 0.0f) addProbe(x, y);
    }
  // ... plus up to 4 sunlit pixels spread over the sunlit area, away from shadow edges.
  std::vector<glm::ivec2> lit;
  for (int y = 1; y + 1 < int(height); y += 2)
    for (int x = 1; x + 1 < int(width); x += 2) {
      bool inside = depth.at(x, y).x > 0.0f;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) inside = inside && shadows.at(x + dx, y + dy).x > 0.99f;
      if (inside) lit.push_back({x, y});
    }
  const size_t extraLit = std::min<size_t>(4, lit.size());
  for (size_t k = 0; k < extraLit; ++k) {
    glm::ivec2 q = lit[(2 * k + 1) * lit.size() / (2 * extraLit)];
    addProbe(q.x, q.y);
  }
  for (glm::vec3 v : referenceIrradiance(run, probes, 48, 16)) a.multi.push_back(luminance(v));
  for (glm::vec3 v : referenceIrradiance(run, probes, 48, 1)) a.single.push_back(luminance(v));
  EXPECT_EQ(run.context.validationErrorCount(), 0u);
  return a;
}

// Tolerances: a cell averages irradiance over a cube about 1/14 of its distance to the camera
// wide and L1 SH smooths the directional distribution, so a point's value is the cell's local
// average, which differs from the point's own irradiance where light changes fast within a
// cell. And a point's error moves between runs: a cell takes its ray origin (and the normal of
// its irradiance scale) from whichever lookup allocated it first, which lavapipe's thread
// timing decides, so the same point lands 5 % off in one run and 30 % in another. So, per
// point: the mean error over points within 15 %, 80 % of the points within 25 % of their value
// (errors with a floor of 15 % of the mean over points, so near-black points do not dominate)
// and every point within a factor of two (100 %), which catches a black or doubled cell; and
// the mean over points, where these errors largely cancel, within 12 %. Measured (lavapipe,
// alone and beside other tests): `cornell` mean error 9-11 %, 21-24 of 24 points within 25 %,
// worst 22-35 %, mean 0.128-0.131 vs 0.138; `sunroom` mean error 8-11 %, 24-27 of 27 within
// 25 %, mean 0.95-1.00 vs 0.96, its worst point (on the ceiling beside the window wall next to
// the sunlit patch, where the light changes fast across the cell) 36-89 %.
// The cache must also hold at least half of the light that bounces more than once (reference
// with 16 bounces minus reference with 1).
void checkAgreement(const std::string& sceneName, const Agreement& a) {
  ASSERT_GE(a.cache.size(), 12u) << "too few surface points in view";
  double meanCache = 0, meanMulti = 0, meanSingle = 0;
  for (size_t i = 0; i < a.cache.size(); ++i) {
    meanCache += a.cache[i] / a.cache.size();
    meanMulti += a.multi[i] / a.cache.size();
    meanSingle += a.single[i] / a.cache.size();
  }
  int sunlit = 0, within25 = 0;
  double worst = 0.0, meanError = 0.0;
  for (size_t i = 0; i < a.cache.size(); ++i) {
    double error =
        std::abs(a.cache[i] - a.multi[i]) / std::max(double(a.multi[i]), 0.15 * meanMulti);
    worst = std::max(worst, error);
    meanError += error / a.cache.size();
    sunlit += a.sunlit[i] ? 1 : 0;
    std::printf(
        "  %s point %2zu (%s): cache %.4f  path-traced %.4f (single bounce %.4f)  error %.1f%%\n",
        sceneName.c_str(), i, a.sunlit[i] ? "sunlit  " : "shadowed", a.cache[i], a.multi[i],
        a.single[i], 100.0 * error);
    EXPECT_LT(error, 1.0) << sceneName << " point " << i;
    within25 += error < 0.25 ? 1 : 0;
  }
  std::printf(
      "%s: %zu points (%d sunlit): mean cache %.4f, path-traced %.4f, single bounce %.4f; "
      "mean error %.1f%%, worst point %.1f%%, %d within 25%%\n",
      sceneName.c_str(), a.cache.size(), sunlit, meanCache, meanMulti, meanSingle,
      100.0 * meanError, 100.0 * worst, within25);
  EXPECT_LE(meanError, 0.15) << sceneName;
  EXPECT_GE(within25, int(std::ceil(0.8 * a.cache.size()))) << sceneName;
  EXPECT_NEAR(meanCache / meanMulti, 1.0, 0.12) << sceneName;
  EXPECT_GT(meanMulti, 1.1 * meanSingle) << sceneName << ": the view has little multi-bounce light";
  EXPECT_GT(meanCache - meanSingle, 0.5 * (meanMulti - meanSingle)) << sceneName;
}

// The Cornell box is lit by a small emissive quad: the cache reaches it by NEE from its rays'
// hits (src/lighting/gpu_light_tables.h), and its L1 SH is normalised to the exact cosine at the
// cell's normal (cache_build_sh.comp); without the two it was 23 % dark with single points off
// by up to 2x.
TEST(ClipmapCache, CornellAgreesWithPathTracedIrradiance) {
  checkAgreement("cornell", measureAgreement("cornell", 48, 48, 128));
}

TEST(ClipmapCache, SunroomAgreesWithPathTracedIrradiance) {
  Agreement a = measureAgreement("sunroom", 64, 36, 96);
  int sunlit = int(std::count(a.sunlit.begin(), a.sunlit.end(), true));
  EXPECT_GE(sunlit, 2) << "the points should include sunlit ones";
  EXPECT_GE(int(a.sunlit.size()) - sunlit, 2) << "the points should include shadowed ones";
  checkAgreement("sunroom", a);
}

// A frame that is declared but never run (what `render --view` does to learn the pass names)
// must not use up the cache's pending reset: the first frame that runs empties the cache.
// Before this was fixed, the first frame ran on whatever the driver's fresh memory held, and on
// lavapipe about half the runs started with a garbage live-cell count (10^8-10^9) and failed
// every allocation. The reset's presence is checked directly (deterministic); the counters
// after it catch the garbage when the memory happens to hold it.
TEST(ClipmapCache, DeclaringAFrameWithoutRunningItKeepsThePendingReset) {
  CacheRun run("cornell", cacheSettings(32, 32, Preset::Mobile));
  const std::vector<std::string> declaredOnly = run.frame->passNames();
  ASSERT_NE(std::find(declaredOnly.begin(), declaredOnly.end(), "cache-reset"), declaredOnly.end());
  Camera camera = effectiveCamera(run.scene);
  run.frame->render(camera);
  const std::vector<std::string> ran = run.frame->passNames();
  EXPECT_NE(std::find(ran.begin(), ran.end(), "cache-reset"), ran.end())
      << "the first frame that ran did not reset the cache";
  EXPECT_EQ(statistic(run.frame->giStatistics(), "cache.allocation-failures"), 0.0);
  EXPECT_LE(statistic(run.frame->giStatistics(), "cache.live-cells"),
            double(run.frame->settings().cache.maxLiveCells));
  run.frame->render(camera);
  const std::vector<std::string> second = run.frame->passNames();
  EXPECT_EQ(std::find(second.begin(), second.end(), "cache-reset"), second.end())
      << "the cache resets every frame";
  EXPECT_EQ(run.context.validationErrorCount(), 0u);
}

TEST(ClipmapCache, UnusedCellsAreFreedAfterFourFrames) {
  // The Cornell box is open at the front: turned round, the camera sees only the (black) sky,
  // so no pixel looks the cache up, while its position (and so every cascade window) stays.
  CacheRun run("cornell", cacheSettings(32, 32, Preset::Mobile));
  Camera camera = effectiveCamera(run.scene);
  for (int i = 0; i < 12; ++i) run.frame->render(camera);
  double liveBefore = statistic(run.frame->giStatistics(), "cache.live-cells");
  ASSERT_GT(liveBefore, 10.0);
  Camera away = camera;
  away.target = camera.position + (camera.position - camera.target);
  std::vector<double> live;
  for (int i = 0; i < 10; ++i) {
    run.frame->render(away);
    live.push_back(statistic(run.frame->giStatistics(), "cache.live-cells"));
  }
  std::printf("live cells: %.0f while seen; after turning away:", liveBefore);
  for (double v : live) std::printf(" %.0f", v);
  std::printf("\n");
  // Frames 0..3 away: cells seen last are stale 1..4 frames, still alive until the 4th.
  for (int i = 0; i < 3; ++i) EXPECT_GE(live[i], 0.5 * liveBefore) << "away frame " << i;
  // Consumer-used cells (touch level 1) go at the start of away frame 4; the cells their rays
  // kept alive (level 2) one frame later, and so on down to level CLIPMAP_TOUCH_LEVELS, whose
  // rays keep nothing alive: all gone by away frame 4 + CLIPMAP_TOUCH_LEVELS - 1.
  EXPECT_LT(live[4], live[3]);
  const int allGone = 4 + int(gpu::CLIPMAP_TOUCH_LEVELS) - 1;
  for (int i = allGone; i < int(live.size()); ++i) EXPECT_EQ(live[i], 0.0) << "away frame " << i;
  EXPECT_EQ(run.context.validationErrorCount(), 0u);
}

TEST(ClipmapCache, CityFlyThroughStaysUnderTheCap) {
  Scene city = loadScene("city");
  Camera start = effectiveCamera(city);
  glm::vec3 forward = glm::normalize(start.target - start.position);
  const int frames = 12;  // 240 m: every cascade up to 2.56 m cells scrolls (CI time)
  for (uint32_t cap : {gpu::CLIPMAP_MAX_CELLS, 400u}) {
    HybridSettings settings = cacheSettings(40, 24, Preset::Mobile);
    settings.cache.maxLiveCells = cap;
    CacheRun run("city", settings);
    double most = 0.0, failures = 0.0, frees = 0.0;
    for (int i = 0; i < frames; ++i) {
      Camera camera = start;
      camera.position += forward * (20.0f * float(i));  // 20 m per frame along the avenue
      camera.target = camera.position + forward;
      run.frame->render(camera);
      std::vector<GiStatistic> s = run.frame->giStatistics();
      most = std::max(most, statistic(s, "cache.live-cells"));
      failures += statistic(s, "cache.allocation-failures");
      frees += statistic(s, "cache.frees");
    }
    std::printf(
        "city fly-through 40x24, %d frames, cap %u: at most %.0f live cells, %.0f frees, "
        "%.0f failed allocations\n",
        frames, cap, most, frees, failures);
    EXPECT_LE(most, double(cap));
    EXPECT_GT(frees, 0.0) << "flying through should free cells";
    if (cap < gpu::CLIPMAP_MAX_CELLS) {
      EXPECT_GT(failures, 0.0) << "the lowered cap should run out";
      EXPECT_EQ(most, double(cap));
    }
    EXPECT_EQ(run.context.validationErrorCount(), 0u);
  }
}

TEST(ClipmapCache, ScrollingKeepsCellsInsideTheirWindows) {
  CacheRun run("sunroom", cacheSettings(32, 18, Preset::Desktop));
  Camera camera = effectiveCamera(run.scene);
  ImageRGBA32F still = renderAveraged(run, camera, 48, 8);
  double liveStill = statistic(run.frame->giStatistics(), "cache.live-cells");
  // Sideways by 3 cm a frame: each cascade window scrolls by whole cells now and then.
  glm::vec3 side = glm::normalize(glm::cross(camera.target - camera.position, camera.up));
  double scrollFrees = 0.0, worstShare = 0.0;
  double meanMoving = 0.0, meanStill = 0.0;
  const int frames = 16;
  for (int i = 1; i <= frames; ++i) {
    Camera moved = camera;
    moved.position += side * (0.03f * float(i));
    moved.target += side * (0.03f * float(i));
    run.frame->render(moved);
    std::vector<GiStatistic> s = run.frame->giStatistics();
    double freed = statistic(s, "cache.frees-by-scrolling");
    scrollFrees += freed;
    worstShare = std::max(worstShare, freed / std::max(1.0, statistic(s, "cache.live-cells")));
    if (i == frames) {
      ImageRGBA32F gi = run.frame->debugViewImage("gi-cache-lookup");
      for (size_t k = 0; k < gi.pixelCount(); ++k) {
        meanMoving += luminance(glm::vec3(gi.at(int(k) % gi.width, int(k) / gi.width)));
        meanStill += luminance(glm::vec3(still.at(int(k) % gi.width, int(k) / gi.width)));
      }
    }
  }
  std::printf(
      "scrolling: %.0f live cells still, %.0f freed by scrolling over %d frames (at most "
      "%.1f%% in a frame); mean gi.diffuse %.4f still, %.4f moved\n",
      liveStill, scrollFrees, frames, 100.0 * worstShare, meanStill / still.pixelCount(),
      meanMoving / still.pixelCount());
  EXPECT_GT(scrollFrees, 0.0) << "the windows should have scrolled";
  // A window moves by one cell layer at a time: 1/32 of its cells, far fewer of the live ones.
  EXPECT_LT(worstShare, 0.10);
  // Cells that stayed inside keep their SH: no dip of the GI after moving 48 cm.
  EXPECT_NEAR(meanMoving / meanStill, 1.0, 0.1);
  EXPECT_EQ(run.context.validationErrorCount(), 0u);
}

template <typename T>
std::vector<T> viewAs(const graph::DebugView& view) {
  std::vector<T> out(view.bytes.size() / sizeof(T));
  std::memcpy(out.data(), view.bytes.data(), out.size() * sizeof(T));
  return out;
}

// The llvmpipe rasterizer threads of this process (lavapipe names them llvmpipe-N); 0 on a GPU.
int llvmpipeThreads() {
  int count = 0;
  for (const auto& task : std::filesystem::directory_iterator("/proc/self/task")) {
    std::ifstream comm(task.path() / "comm");
    std::string name;
    if (std::getline(comm, name) && name.rfind("llvmpipe", 0) == 0) ++count;
  }
  return count;
}

// A run's live cells and their entries, by cascade and coordinates (and entry): a cell's pool
// index depends on the order in which lookups allocated it, which may differ.
struct CacheState {
  std::map<std::array<int, 4>, gpu::ClipmapCell> cells;
  std::map<std::array<int, 5>, gpu::ClipmapEntry> entries;
};

CacheState cacheState(const HybridFrame& frame) {
  CacheState out;
  const auto cells = viewAs<gpu::ClipmapCell>(frame.graph().readDebugView("cache.cells"));
  const auto entries = viewAs<gpu::ClipmapEntry>(frame.graph().readDebugView("cache.entries"));
  for (size_t i = 0; i < cells.size(); ++i) {
    const gpu::ClipmapCell& c = cells[i];
    if (!(c.flags & gpu::CLIPMAP_CELL_ALIVE)) continue;
    out.cells[{c.coord.w, c.coord.x, c.coord.y, c.coord.z}] = c;
    for (uint32_t e = 0; e < gpu::CLIPMAP_ENTRIES; ++e)
      out.entries[{c.coord.w, c.coord.x, c.coord.y, c.coord.z, int(e)}] =
          entries[i * gpu::CLIPMAP_ENTRIES + e];
  }
  return out;
}

bool sameCell(const gpu::ClipmapCell& a, const gpu::ClipmapCell& b) {
  return a.origin == b.origin && a.normal == b.normal && a.shR == b.shR && a.shG == b.shG &&
         a.shB == b.shB && a.flags == b.flags && a.validEntries == b.validEntries &&
         a.originCloseness == b.originCloseness && a.irradianceScale == b.irradianceScale &&
         a.age == b.age;
}

bool sameEntry(const gpu::ClipmapEntry& a, const gpu::ClipmapEntry& b) {
  return a.radiance == b.radiance && a.M == b.M && a.direction == b.direction && a.W == b.W &&
         a.origin == b.origin && a.weightSum == b.weightSum && a.hitDistance == b.hitDistance;
}

// Keys of `a` missing from `b` or whose values differ.
template <typename Key, typename Value, typename Same>
size_t differences(const std::map<Key, Value>& a, const std::map<Key, Value>& b, Same same) {
  size_t count = 0;
  for (const auto& [key, value] : a) {
    auto it = b.find(key);
    if (it == b.end() || !same(value, it->second)) ++count;
  }
  return count;
}

// The cache's results do not depend on thread scheduling: the ReSTIR GI chain (desktop preset,
// the cache as its third vertex on) over 8 frames of sunroom at 32x24, once on one lavapipe
// thread and once on four (LP_NUM_THREADS, which lavapipe reads when the device is created:
// the test counts the threads), gives the same live cells and entries (keyed by coordinates:
// pool indices may differ) and the same composite, bit for bit: nothing in the chain adds
// floats atomically. 8 frames take in the first frames after the full refresh (validation
// rays; with CLIPMAP_ELECT_CENTRE, origins moving closer to their centres), where a tie between
// equally close candidates once made 87 to 4,821 of 5,441 cells differ (docs/gi/clipmap-cache.md,
// "Deterministic cells"). About 31 s of CPU (user time of both runs); 100-374 s of wall
// time here on a machine loaded by other builds. On a GPU LP_NUM_THREADS does nothing and the two
// runs compare two schedules of the same device.
TEST(ClipmapCache, ResultsDoNotDependOnThreadScheduling) {
  HybridSettings settings = presetSettings(Preset::Desktop);
  settings.width = 32;
  settings.height = 24;
  settings.lambert = true;
  settings.gi = GiMode::Evolve;
  struct Result {
    CacheState cache;
    ImageRGBA32F composite;
    int threads = 0;
  };
  auto run = [&](const char* threads) {
    setenv("LP_NUM_THREADS", threads, 1);
    CacheRun r("sunroom", settings);
    Result out;
    out.threads = llvmpipeThreads();
    Camera camera = effectiveCamera(r.scene);
    for (const char* view : {"composite", "cache.cells", "cache.entries"})
      r.frame->requestDebugView(view);
    for (int i = 0; i < 8; ++i) r.frame->render(camera);
    out.cache = cacheState(*r.frame);
    out.composite = r.frame->debugViewImage("composite");
    EXPECT_EQ(r.context.validationErrorCount(), 0u);
    return out;
  };
  const char* previous = std::getenv("LP_NUM_THREADS");
  const std::string saved = previous ? previous : "";
  const Result one = run("1"), four = run("4");
  if (previous)
    setenv("LP_NUM_THREADS", saved.c_str(), 1);
  else
    unsetenv("LP_NUM_THREADS");

  const size_t cells = differences(one.cache.cells, four.cache.cells, sameCell);
  const size_t entries = differences(one.cache.entries, four.cache.entries, sameEntry);
  size_t channels = 0;
  for (size_t i = 0; i < one.composite.pixels.size(); ++i)
    if (one.composite.pixels[i] != four.composite.pixels[i]) ++channels;
  std::printf(
      "sunroom 32x24, 8 frames, llvmpipe threads %d vs %d: %zu vs %zu live cells, %zu differ "
      "or are missing, %zu entries differ; composite: %zu channels differ\n",
      one.threads, four.threads, one.cache.cells.size(), four.cache.cells.size(), cells, entries,
      channels);
  EXPECT_GT(one.cache.cells.size(), 100u);
  EXPECT_EQ(one.cache.cells.size(), four.cache.cells.size());
  EXPECT_EQ(cells, 0u);
  EXPECT_EQ(entries, 0u);
  EXPECT_EQ(channels, 0u);
}

TEST(ClipmapCache, NoNanAfterThousandAnimatedFrames) {
  // A pool of 512 cells (the room alone keeps ~2,800 alive, which made this test take 270 s on
  // lavapipe): the NaN checks then also cover cells recycled under pool pressure.
  HybridSettings settings = cacheSettings(16, 12, Preset::Mobile);
  settings.cache.maxLiveCells = 512;
  CacheRun run("sunroom", settings);
  AnimationPlayer player(run.scene, run.scene.animation);
  const int frames = 1000;
  for (int i = 0; i < frames; ++i) {
    if (i == frames - 1) {
      run.frame->requestDebugView("cache.entries");
      run.frame->requestDebugView("cache.cells");
    }
    run.frame->render(player.apply(*run.frame, float(i) / 30.0f));
  }
  std::vector<gpu::ClipmapEntry> entries =
      viewAs<gpu::ClipmapEntry>(run.frame->graph().readDebugView("cache.entries"));
  std::vector<gpu::ClipmapCell> cells =
      viewAs<gpu::ClipmapCell>(run.frame->graph().readDebugView("cache.cells"));
  ASSERT_EQ(cells.size(), size_t(gpu::CLIPMAP_MAX_CELLS));
  auto finite = [](const glm::vec4& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z) && std::isfinite(v.w);
  };
  size_t live = 0, bad = 0, sampled = 0;
  for (size_t c = 0; c < cells.size(); ++c) {
    if (!(cells[c].flags & gpu::CLIPMAP_CELL_ALIVE)) continue;
    ++live;
    if (!finite(cells[c].shR) || !finite(cells[c].shG) || !finite(cells[c].shB)) ++bad;
    for (uint32_t e = 0; e < gpu::CLIPMAP_ENTRIES; ++e) {
      const gpu::ClipmapEntry& x = entries[c * gpu::CLIPMAP_ENTRIES + e];
      if (x.M > 0.0f) ++sampled;
      if (!finite(glm::vec4(x.radiance, x.M)) || !finite(glm::vec4(x.direction, x.W)) ||
          !finite(glm::vec4(x.origin, x.weightSum)) || !std::isfinite(x.hitDistance))
        ++bad;
    }
  }
  std::printf(
      "animated sunroom 16x12, %d frames: %zu live cells, %zu sampled entries, %zu "
      "non-finite\n",
      frames, live, sampled, bad);
  EXPECT_GT(live, 0u);
  EXPECT_GT(sampled, live * 8);
  EXPECT_EQ(bad, 0u);
  EXPECT_EQ(run.context.validationErrorCount(), 0u);
}

}  // namespace
}  // namespace bounce
