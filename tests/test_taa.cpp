// Temporal anti-aliasing (src/passes/taa.h, issue 21 item 6) on lavapipe:
//   - the jitter: Halton (2, 3) points inside the pixel, and a raster matrix that lands what the
//     jittered ray sees on the pixel centre;
//   - motion stays unjittered: on a static view gbuffer.velocity is zero whatever the jitter,
//     and under camera motion it is the seen point's own screen motion; a camera cut
//     (resetHistory) leaves nothing of the history;
//   - (a) on a static view the anti-aliased output converges toward `bounce reference`
//     (anti-aliased, a box filter over each pixel): the error of edge pixels at least 2x lower
//     than the pixel-centre composite's;
//   - (c) a moving object leaves no ghost trail: after it stops, the error of the pixels it
//     uncovered is back within 1.5x of a converged static view's in a few frames;
//   - the GI's temporal denoiser keeps its history under the jitter (Cornell box);
//   - (b) on the Cornell box with its noisy GI, the mean of flat regions is what a plain
//     running mean of the composite gives (disabled: not met, numbers at the test);
//   - (d) no output has a NaN or Inf.
// Set BOUNCE_TEST_IMAGES=DIR to write the images compared.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/packing.hpp>

#include "floor_and_card.h"
#include "frame/hybrid_frame.h"
#include "frame/presets.h"
#include "frame_texels.h"
#include "harness.h"
#include "passes/primary_view.h"
#include "passes/taa.h"
#include "reference/path_tracer.h"
#include "rt/gpu_scene.h"
#include "scene/load.h"
#include "scene/scene_options.h"
#include "tools/image_io.h"
#include "tools/metrics.h"
#include "vk/context.h"

namespace bounce {
namespace {

double luminance(const glm::vec4& c) {
  return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z;
}

using test::texels;

void writeTestImage(const std::string& name, const ImageRGBA32F& image, float exposure) {
  if (const char* dir = std::getenv("BOUNCE_TEST_IMAGES")) {
    writeImage(std::string(dir) + "/taa-" + name + ".exr", image);
    writePng(std::string(dir) + "/taa-" + name + ".png", image, exposure);
  }
}

// The scene lit by its sun alone (no sky light, no lamps, no emission): the frame without GI
// then computes what the one-bounce reference does, exactly at each sample point, so what
// differs from the anti-aliased reference is the sampling of each pixel.
Scene sunOnly(Scene scene) {
  scene.sky.model = SkyModel::Constant;
  scene.sky.radiance = glm::vec3(0.0f);
  scene.lights.clear();
  for (Material& material : scene.materials) {
    material.emissive = glm::vec3(0.0f);
    material.emissiveTexture = -1;
  }
  scene.sun.angularDiameterDegrees = 0.0f;
  return scene;
}

// Direct sun light at full resolution (hard shadows traced per pixel, no reflection rays): the
// frame of test_direct_lighting.cpp, which matches the pixel-centre reference.
HybridSettings directSettings(uint32_t width, uint32_t height, bool taa) {
  HybridSettings settings;
  settings.width = width;
  settings.height = height;
  settings.shadows.divisor = 1;
  settings.reflections.divisor = 0;
  settings.taa.enabled = taa;
  return settings;
}

ImageRGBA32F referenceImage(vk::Context& context, const GpuScene& gpuScene, const Scene& scene,
                            const Camera& camera, uint32_t width, uint32_t height, bool pixelCentre,
                            uint32_t spp) {
  ReferencePathTracer tracer(context, gpuScene, scene);
  ReferenceOptions options;
  options.width = width;
  options.height = height;
  options.samplesPerPixel = spp;
  options.maxBounces = 1;
  options.pixelCentre = pixelCentre;
  return tracer.render(camera, options).image;
}

// test::floorAndCardUnlit with a light grey card, lit by a sun without sky light.
Scene floorAndCard() {
  Scene scene = test::floorAndCardUnlit(glm::vec4(0.9f, 0.9f, 0.9f, 1.0f));
  scene.sun.direction = glm::normalize(glm::vec3(0.3f, -1.0f, -0.4f));
  scene.sky.model = SkyModel::Constant;
  scene.sky.radiance = glm::vec3(0.0f);
  validateScene(scene, "floor and card");
  return scene;
}

// ---- the jitter
// ----------------------------------------------------------------------------------

TEST(TaaJitter, HaltonPointsCoverThePixel) {
  const uint32_t phases = 8;
  glm::vec2 mean(0.0f);
  int inLeftHalf = 0, inTopHalf = 0;
  for (uint32_t i = 0; i < phases; ++i) {
    glm::vec2 j = taaJitter(i, phases);
    EXPECT_GE(j.x, -0.5f);
    EXPECT_LT(j.x, 0.5f);
    EXPECT_GE(j.y, -0.5f);
    EXPECT_LT(j.y, 0.5f);
    for (uint32_t k = 0; k < i; ++k) EXPECT_NE(taaJitter(k, phases), j) << i << " " << k;
    mean += j / float(phases);
    inLeftHalf += j.x < 0.0f;
    inTopHalf += j.y < 0.0f;
  }
  EXPECT_EQ(taaJitter(phases, phases), taaJitter(0, phases));  // the sequence repeats
  // Halton points 1..8: base 2 fills x exactly (four each side); base 3 nearly.
  EXPECT_EQ(inLeftHalf, 4);
  EXPECT_NEAR(inTopHalf, 4, 1);
  EXPECT_LT(glm::length(mean), 0.1f);
  EXPECT_EQ(taaJitter(5, 1), taaJitter(0, 1));
}

// The raster pass's matrix lands the point that the jittered ray through s + jitter sees on s.
TEST(TaaJitter, JitteredMatrixMatchesJitteredRays) {
  Camera camera{{0.3f, 1.2f, 3.0f}, {0.0f, 0.5f, 0.0f}, {0, 1, 0}, 45.0f};
  const glm::uvec2 res(64, 32);
  gpu::GpuCamera cam = makeGpuCamera(camera, res.x, res.y, Aabb{});
  const glm::mat4 m = jitteredViewProjection(viewProjection(cam, 0.01f), {0.3f, -0.2f}, res);
  for (glm::vec2 s : {glm::vec2(10.5f, 3.5f), glm::vec2(50.25f, 20.75f)}) {
    glm::vec3 dir = gpu::cameraRayDirection(cam, s + glm::vec2(0.3f, -0.2f), glm::vec2(res));
    glm::vec4 clip = m * glm::vec4(cam.position + 2.7f * dir, 1.0f);
    glm::vec2 pixel = (glm::vec2(clip) / clip.w * 0.5f + 0.5f) * glm::vec2(res);
    EXPECT_NEAR(pixel.x, s.x, 1e-3f);
    EXPECT_NEAR(pixel.y, s.y, 1e-3f);
  }
}

// ---- motion under the jitter
// ---------------------------------------------------------------------

// A static view: every frame sees the scene through another sub-pixel offset, yet nothing moved,
// so the velocity is zero (the GI and denoisers read history at the same pixel). Then the camera
// moves: the velocity is the seen point's unjittered motion, centre + jitter minus where last
// frame's unjittered camera saw that point.
TEST(Taa, VelocityIsUnjittered) {
  vk::Context context(vk::contextOptionsFromEnvironment({}));
  Scene scene = floorAndCard();
  GpuScene gpuScene(context, scene);
  const glm::uvec2 res(64, 48);
  HybridFrame frame(context, gpuScene, scene, directSettings(res.x, res.y, true));
  frame.requestDebugView("gbuffer.velocity");
  frame.requestDebugView("gbuffer.depth");
  frame.requestDebugView("vbuffer.ids");
  const Camera first = *scene.camera;
  float maxStaticSpeed = 0.0f;
  for (int i = 0; i < 4; ++i) {
    frame.render(first);
    if (i == 0) continue;  // no previous frame yet
    for (glm::u16vec2 v : texels<glm::u16vec2>(frame, "gbuffer.velocity"))
      maxStaticSpeed =
          std::max(maxStaticSpeed, std::hypot(glm::unpackHalf1x16(v.x), glm::unpackHalf1x16(v.y)));
  }
  Camera second = first;
  second.position += glm::vec3(0.25f, 0.08f, -0.3f);
  frame.render(second);  // frame 4: jitter taaJitter(4)
  const glm::vec2 jitter = taaJitter(4, frame.settings().taa.jitterPhases);
  std::vector<glm::u16vec2> velocity = texels<glm::u16vec2>(frame, "gbuffer.velocity");
  std::vector<float> depth = texels<float>(frame, "gbuffer.depth");
  std::vector<glm::uvec4> ids = texels<glm::uvec4>(frame, "vbuffer.ids");
  gpu::GpuCamera now = makeGpuCamera(second, res.x, res.y, gpuScene.bounds());
  gpu::GpuCamera before = makeGpuCamera(first, res.x, res.y, gpuScene.bounds());
  float maxError = 0.0f, meanSpeed = 0.0f;
  uint32_t count = 0;
  for (uint32_t y = 0; y < res.y; ++y)
    for (uint32_t x = 0; x < res.x; ++x) {
      size_t i = size_t(y) * res.x + x;
      if (ids[i].x == gpu::VBUFFER_NO_HIT) continue;
      glm::vec2 sample = glm::vec2(x + 0.5f, y + 0.5f) + jitter;
      glm::vec3 dir = gpu::cameraRayDirection(now, sample, glm::vec2(res));
      glm::vec3 p = now.position + dir * (depth[i] / glm::dot(dir, now.forward));
      glm::vec4 clip = viewProjection(before, 0.01f) * glm::vec4(p, 1.0f);
      glm::vec2 previous = (glm::vec2(clip) / clip.w * 0.5f + 0.5f) * glm::vec2(res);
      glm::vec2 v(glm::unpackHalf1x16(velocity[i].x), glm::unpackHalf1x16(velocity[i].y));
      maxError = std::max(maxError, glm::length(v - (sample - previous)));
      meanSpeed += glm::length(sample - previous);
      ++count;
    }
  ASSERT_GT(count, res.x * res.y / 2);
  meanSpeed /= float(count);
  std::printf(
      "jittered static view: max |velocity| %.5f px; moving camera: mean motion %.2f px, "
      "max velocity error %.4f px (jitter %.3f, %.3f)\n",
      maxStaticSpeed, meanSpeed, maxError, jitter.x, jitter.y);
  EXPECT_LT(maxStaticSpeed, 1e-3f);
  EXPECT_GT(meanSpeed, 1.0f);
  // RG16F and the depth round trip, as test_motion.cpp's bound.
  EXPECT_LT(maxError, 0.02f);

  // A camera cut: the frame after resetHistory() shows its own composite, nothing of before.
  frame.requestDebugView("composite");
  frame.requestDebugView("taa");
  frame.render(first);
  frame.resetHistory();
  frame.render(second);
  const ImageRGBA32F composite = frame.debugViewImage("composite");
  const ImageRGBA32F taa = frame.debugViewImage("taa");
  size_t differing = 0;
  for (size_t i = 0; i < composite.pixelCount(); ++i)
    for (int c = 0; c < 3; ++c) differing += composite.pixels[4 * i + c] != taa.pixels[4 * i + c];
  EXPECT_EQ(differing, 0u) << "history survived resetHistory()";
  EXPECT_EQ(countNonFinitePixels(taa), 0u);
  EXPECT_EQ(context.validationErrorCount(), 0u);
}

// ---- (a) convergence to the anti-aliased reference
// -----------------------------------------------

struct EdgeErrors {
  double pixelCentre = 0.0;  // mean |Y - Y_ref| of edge pixels, the --no-taa composite
  double taa = 0.0;          // the same, the taa output
  uint32_t edgePixels = 0;
};

// Edge pixels: where the anti-aliased reference differs from the pixel-centre reference by more
// than 10% (of the larger, floored at 5% of the mean): a pixel whose footprint is not one
// surface under one light. Both chosen from the references alone.
EdgeErrors edgeErrors(const ImageRGBA32F& pixelCentreFrame, const ImageRGBA32F& taaFrame,
                      const ImageRGBA32F& reference, const ImageRGBA32F& pixelCentreReference) {
  const double floor = 0.05 * test::meanLuminance(reference);
  EdgeErrors e;
  for (int y = 0; y < reference.height; ++y)
    for (int x = 0; x < reference.width; ++x) {
      const double r = luminance(reference.at(x, y)), c = luminance(pixelCentreReference.at(x, y));
      if (std::abs(r - c) <= 0.1 * std::max({r, c, floor})) continue;
      e.pixelCentre += std::abs(luminance(pixelCentreFrame.at(x, y)) - r);
      e.taa += std::abs(luminance(taaFrame.at(x, y)) - r);
      ++e.edgePixels;
    }
  e.pixelCentre /= std::max(1u, e.edgePixels);
  e.taa /= std::max(1u, e.edgePixels);
  return e;
}

// The pixel-centre composite (--no-taa) and the taa output after kFrames static frames, for
// each vbuffer mode, against one anti-aliased reference.
TEST(Taa, EdgesConvergeToAntiAliasedReference) {
  constexpr uint32_t kWidth = 96, kHeight = 64;
  constexpr int kFrames = 24;
  Scene scene = floorAndCard();
  const Camera camera = *scene.camera;
  vk::Context context(vk::contextOptionsFromEnvironment());
  GpuScene gpuScene(context, scene);
  const ImageRGBA32F reference =
      referenceImage(context, gpuScene, scene, camera, kWidth, kHeight, false, 256);
  const ImageRGBA32F centreReference =
      referenceImage(context, gpuScene, scene, camera, kWidth, kHeight, true, 1);
  writeTestImage("edges-reference", reference, 0.3f);
  const double mean = test::meanLuminance(reference);
  for (VBufferMode mode : {VBufferMode::Raster, VBufferMode::Trace}) {
    const std::string name = mode == VBufferMode::Raster ? "raster" : "trace";
    HybridSettings settings = directSettings(kWidth, kHeight, false);
    settings.vbuffer = mode;
    ImageRGBA32F pixelCentre;
    {
      HybridFrame frame(context, gpuScene, scene, settings);
      frame.requestDebugView("composite");
      for (int i = 0; i < 4; ++i) frame.render(camera);  // the shadow history converges
      pixelCentre = frame.debugViewImage("composite");
    }
    settings.taa.enabled = true;
    ImageRGBA32F taa;
    {
      HybridFrame frame(context, gpuScene, scene, settings);
      frame.requestDebugView("taa");
      for (int i = 0; i < kFrames; ++i) frame.render(camera);
      taa = frame.debugViewImage("taa");
    }
    writeTestImage("edges-" + name + "-pixel-centre", pixelCentre, 0.3f);
    writeTestImage("edges-" + name + "-taa", taa, 0.3f);
    EdgeErrors e = edgeErrors(pixelCentre, taa, reference, centreReference);
    std::printf(
        "floor and card %ux%u, %s, %d frames: %u edge pixels; mean |error| / mean luminance: "
        "pixel centre %.4f, taa %.4f (%.2fx lower); whole image relMSE pixel centre %.5f, taa "
        "%.5f\n",
        kWidth, kHeight, name.c_str(), kFrames, e.edgePixels, e.pixelCentre / mean, e.taa / mean,
        e.pixelCentre / e.taa, relativeMeanSquaredError(pixelCentre, reference),
        relativeMeanSquaredError(taa, reference));
    EXPECT_GT(e.edgePixels, 100u) << name;
    EXPECT_LE(2.0 * e.taa, e.pixelCentre) << name << ": the issue's gate, 2x lower error on edges";
    EXPECT_EQ(countNonFinitePixels(taa), 0u) << name;
  }
  EXPECT_EQ(context.validationErrorCount(), 0u);
}

// ---- (c) no ghost trail
// --------------------------------------------------------------------------

// The card slides sideways for kMoving frames and stops. The pixels it covered before it moved
// and no longer covers (its trail) must show the floor again: their error against the
// anti-aliased reference of the final pose is compared, frame by frame after the stop, with
// the same pixels' error in a static run that saw the card at its final pose all along.
TEST(Taa, MovingObjectLeavesNoGhostTrail) {
  constexpr uint32_t kWidth = 96, kHeight = 64;
  constexpr int kSettle = 12, kMoving = 8, kAfter = 6;
  const glm::vec3 step(0.07f, 0.0f, 0.0f);  // about 1.8 px a frame
  Scene scene = floorAndCard();
  vk::Context context(vk::contextOptionsFromEnvironment());
  GpuScene gpuScene(context, scene);
  const Camera camera = *scene.camera;
  const glm::mat4 start = scene.instances[1].transform;
  const glm::mat4 end = glm::translate(glm::mat4(1.0f), float(kMoving) * step) * start;
  std::vector<glm::mat4> transforms = {scene.instances[0].transform, start};
  HybridSettings settings = directSettings(kWidth, kHeight, true);
  // The point sun's shadow is exact every frame: without the shadow denoiser's running mean,
  // whose own lag would move the card's shadow late, what lags is taa's.
  settings.shadows.maxHistory = 1.0f;

  // The static run, the card at its final pose.
  ImageRGBA32F still;
  std::vector<glm::uvec4> idsEnd;
  {
    HybridFrame frame(context, gpuScene, scene, settings);
    frame.requestDebugView("taa");
    frame.requestDebugView("vbuffer.ids");
    transforms[1] = end;
    for (int i = 0; i < kSettle + kMoving + kAfter; ++i) {
      frame.setInstanceTransforms(transforms);
      frame.render(camera);
    }
    still = frame.debugViewImage("taa");
    idsEnd = texels<glm::uvec4>(frame, "vbuffer.ids");
  }
  // The reference at the final pose, where the static run left the GPU scene's instances.
  const ImageRGBA32F reference =
      referenceImage(context, gpuScene, scene, camera, kWidth, kHeight, false, 256);

  HybridFrame frame(context, gpuScene, scene, settings);
  frame.requestDebugView("taa");
  frame.requestDebugView("vbuffer.ids");
  transforms[1] = start;
  std::vector<glm::uvec4> idsStart;
  ImageRGBA32F beforeMotion;
  for (int i = 0; i < kSettle; ++i) {
    frame.setInstanceTransforms(transforms);
    frame.render(camera);
  }
  idsStart = texels<glm::uvec4>(frame, "vbuffer.ids");
  beforeMotion = frame.debugViewImage("taa");
  for (int i = 1; i <= kMoving; ++i) {
    transforms[1] = glm::translate(glm::mat4(1.0f), float(i) * step) * start;
    frame.setInstanceTransforms(transforms);
    frame.render(camera);
  }
  std::vector<size_t> trail;
  for (size_t i = 0; i < idsStart.size(); ++i)
    if (idsStart[i].x == 1u && idsEnd[i].x != 1u) trail.push_back(i);
  ASSERT_GT(trail.size(), 50u);
  auto trailError = [&](const ImageRGBA32F& image) {
    double sum = 0.0;
    for (size_t i : trail) {
      int x = int(i % kWidth), y = int(i / kWidth);
      sum += std::abs(luminance(image.at(x, y)) - luminance(reference.at(x, y)));
    }
    return sum / double(trail.size());
  };
  const double converged = trailError(still);
  const double ghost = trailError(beforeMotion);  // the card itself still there
  std::vector<double> after;
  bool finite = true;
  for (int i = 0; i < kAfter; ++i) {
    frame.setInstanceTransforms(transforms);
    frame.render(camera);
    ImageRGBA32F image = frame.debugViewImage("taa");
    finite = finite && countNonFinitePixels(image) == 0;
    after.push_back(trailError(image));
    if (i == 0) writeTestImage("ghost-first-frame-after-stop", image, 0.3f);
  }
  writeTestImage("ghost-still", still, 0.3f);
  writeTestImage("ghost-before-motion", beforeMotion, 0.3f);
  std::printf(
      "ghost trail: %zu pixels; mean |error|: card still there %.4f, converged static "
      "%.4f, frames after the stop:",
      trail.size(), ghost, converged);
  for (double e : after) std::printf(" %.4f", e);
  std::printf("\n");
  // Within 1.5x of the converged error in at most 3 frames after the stop, and stays there.
  for (int i = 2; i < kAfter; ++i) EXPECT_LE(after[size_t(i)], 1.5 * converged) << "frame " << i;
  EXPECT_TRUE(finite);
  EXPECT_EQ(context.validationErrorCount(), 0u);
}

// ---- (b) the mean of flat regions, and the GI's history under the jitter
// -------------------------

struct GiRun {
  std::vector<ImageRGBA32F> composites;  // every frame's
  ImageRGBA32F taa;                      // the last frame's (taa on)
  double meanDenoiseFrames = 0.0;        // gi.denoised's history length, surface pixels
  std::vector<glm::vec3> normals;        // geometric normal per pixel (0: sky)
  std::vector<bool> emissive;            // the pixel sees an emitter
};

GiRun runCornell(vk::Context& context, GpuScene& gpuScene, const Scene& scene, bool taa,
                 uint32_t width, uint32_t height, int frames) {
  HybridSettings settings = presetSettings(Preset::Desktop);
  settings.width = width;
  settings.height = height;
  settings.gi = GiMode::Evolve;
  settings.lambert = true;
  settings.taa.enabled = taa;
  HybridFrame frame(context, gpuScene, scene, settings);
  frame.requestDebugView("composite");
  frame.requestDebugView("gi.denoised");
  if (taa) frame.requestDebugView("taa");
  frame.requestDebugView("gbuffer.normals");
  frame.requestDebugView("gbuffer.emissive");
  GiRun run;
  const Camera camera = effectiveCamera(scene);
  for (int i = 0; i < frames; ++i) {
    frame.render(camera);
    run.composites.push_back(frame.debugViewImage("composite"));
  }
  if (taa) run.taa = frame.debugViewImage("taa");
  const ImageRGBA32F normals = frame.debugViewImage("gbuffer.normals");
  const ImageRGBA32F emission = frame.debugViewImage("gbuffer.emissive");
  for (size_t i = 0; i < normals.pixelCount(); ++i) {
    const glm::vec2 e(normals.pixels[4 * i + 2], normals.pixels[4 * i + 3]);
    run.normals.push_back(e == glm::vec2(0.0f) ? glm::vec3(0.0f) : test::decodeOctahedral(e));
    run.emissive.push_back(
        emission.pixels[4 * i] + emission.pixels[4 * i + 1] + emission.pixels[4 * i + 2] > 0.0f);
  }
  ImageRGBA32F denoised = frame.debugViewImage("gi.denoised");
  uint32_t count = 0;
  for (size_t i = 0; i < denoised.pixelCount(); ++i)
    if (denoised.pixels[4 * i + 3] > 0.0f) {
      run.meanDenoiseFrames += denoised.pixels[4 * i + 3];
      ++count;
    }
  run.meanDenoiseFrames /= std::max(1u, count);
  return run;
}

// The GI's temporal denoiser (gi-temporal-denoise) must keep its history under the jitter:
// its history test compares view depths, which the jitter moves by a fraction of a pixel's
// depth range. Measured (lavapipe, 16 frames, mean history length over surface pixels, with /
// without jitter): 2.13 / 3.33 at 32x32, 2.70 / 3.34 at 64x64, 3.24 / 3.30 at 128x128: its 3%
// depth tolerance is narrower than the depth a pixel spans on Cornell's side walls below about
// 100 pixels across (docs/frame.md#temporal-anti-aliasing). At 128x128 (10 frames here) the
// loss is within the gate.
TEST(Taa, GiDenoiserKeepsItsHistoryUnderJitter) {
  constexpr uint32_t kSide = 128;
  constexpr int kFrames = 10;
  const Scene scene = loadScene("cornell");
  vk::Context context(vk::contextOptionsFromEnvironment());
  GpuScene gpuScene(context, scene);
  GiRun jittered = runCornell(context, gpuScene, scene, true, kSide, kSide, kFrames);
  GiRun centred = runCornell(context, gpuScene, scene, false, kSide, kSide, kFrames);
  std::printf(
      "cornell %ux%u desktop, %d frames: gi.denoised mean history %.2f frames with "
      "jitter, %.2f without\n",
      kSide, kSide, kFrames, jittered.meanDenoiseFrames, centred.meanDenoiseFrames);
  EXPECT_GE(jittered.meanDenoiseFrames, 0.9 * centred.meanDenoiseFrames);
  EXPECT_EQ(countNonFinitePixels(jittered.taa), 0u);
  EXPECT_EQ(context.validationErrorCount(), 0u);
}

// (b) taa's output against what it would give without its clip, the plain running mean of the
// same composites (uniform over the first 1 / blend frames, then exponential; the view is
// static, so per pixel), over flat regions, within 2 %, after 64 frames. The composite must be
// stationary for the two to agree: Evolve's GI brightens the first frames (its cache and
// histories fill; the flat regions' composite mean is printed at frames 8, 16, 32 and 64), and
// the running mean keeps those dark frames while the clip drops them. After 16 frames the ratio
// was 1.061 (a gate written then, and long disabled, blamed the clip); after 32 it is 1.022,
// after 64 0.999 (lavapipe, 64x64 desktop; docs/frame.md).
TEST(Taa, KeepsTheMeanOfFlatRegions) {
  const uint32_t kSide = 64;
  const int kFrames = 64;
  const Scene scene = loadScene("cornell");
  vk::Context context(vk::contextOptionsFromEnvironment());
  GpuScene gpuScene(context, scene);
  GiRun jittered = runCornell(context, gpuScene, scene, true, kSide, kSide, kFrames);
  const float blend = TaaSettings{}.blend;
  ImageRGBA32F runningMean = jittered.composites[0];
  float n = 1.0f;
  for (size_t k = 1; k < jittered.composites.size(); ++k) {
    n = std::min(n + 1.0f, 1.0f / blend);
    for (size_t i = 0; i < runningMean.pixels.size(); ++i)
      runningMean.pixels[i] += (jittered.composites[k].pixels[i] - runningMean.pixels[i]) / n;
  }
  // Flat: the 5x5 neighbourhood on one plane (the same geometric normal) with no emitter in
  // it: walls, floor, ceiling and box faces away from their edges and the lamp. Chosen from
  // the geometry, not from either signal, so that the choice does not favour pixels whose
  // noise happened to run low or high.
  double sumTaa = 0.0, sumMean = 0.0;
  const std::array<int, 4> kConvergenceFrames = {8, 16, 32, 64};
  std::array<double, 4> composite = {};
  uint32_t flat = 0;
  for (int y = 2; y < int(kSide) - 2; ++y)
    for (int x = 2; x < int(kSide) - 2; ++x) {
      const glm::vec3 normal = jittered.normals[size_t(y) * kSide + x];
      bool isFlat = normal != glm::vec3(0.0f);
      for (int dy = -2; dy <= 2 && isFlat; ++dy)
        for (int dx = -2; dx <= 2 && isFlat; ++dx) {
          const size_t q = size_t(y + dy) * kSide + size_t(x + dx);
          isFlat = glm::dot(jittered.normals[q], normal) > 0.999f && !jittered.emissive[q];
        }
      if (!isFlat) continue;
      sumTaa += luminance(jittered.taa.at(x, y));
      sumMean += luminance(runningMean.at(x, y));
      for (size_t k = 0; k < composite.size(); ++k)
        composite[k] += luminance(jittered.composites[kConvergenceFrames[k] - 1].at(x, y));
      ++flat;
    }
  writeTestImage("cornell-taa", jittered.taa, 1.0f);
  writeTestImage("cornell-composite", jittered.composites.back(), 1.0f);
  const double ratio = sumTaa / sumMean;
  std::printf(
      "cornell %ux%u desktop, %d frames: %u flat pixels, taa / running mean of the "
      "composite %.4f; the composite's mean there at frames 8, 16, 32, 64: %.4f %.4f %.4f "
      "%.4f\n",
      kSide, kSide, kFrames, flat, ratio, composite[0] / flat, composite[1] / flat,
      composite[2] / flat, composite[3] / flat);
  EXPECT_GT(flat, kSide * kSide / 8);
  EXPECT_NEAR(ratio, 1.0, 0.02);
  EXPECT_EQ(countNonFinitePixels(jittered.taa), 0u);
  EXPECT_EQ(context.validationErrorCount(), 0u);
}

}  // namespace
}  // namespace bounce
