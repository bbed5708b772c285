// The reference path tracer (src/reference/) against answers known without it: the white
// furnace (Le / (1 - a) everywhere), a sun-lit Lambert plane (E cos(theta) albedo / pi), point
// and spot lights (I cos / d^2 times the glTF falloff), the Preetham zenith luminance, and the
// Cornell box rendered by Cycles (an independent renderer). Also: one-sided emission that
// follows mirroring, determinism, no NaN, the `bounce reference` command line, and the light
// table it samples (src/lighting/light_table.h, shared with the real-time frame).
//
// Noise: every tolerance below is several standard deviations of the Monte-Carlo error at the
// sample counts used (measured, see the comments), so a pass is not luck and a bias of the
// size a typical bug causes (a missing bounce, a wrong pdf, a lost pi) fails.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <numbers>
#include <optional>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "core/error.h"
#include "harness.h"
#include "lighting/light_table.h"
#include "reference/path_tracer.h"
#include "rt/gpu_scene.h"
#include "scene/load.h"
#include "scene/procedural/furnace.h"
#include "scene/procedural/mesh_builder.h"
#include "scene/scene_options.h"
#include "tools/image_io.h"
#include "tools/metrics.h"
#include "vk/context.h"

namespace bounce {
namespace {

using test::directionalAlbedo;
using test::gltfBrdf;

constexpr float kPi = std::numbers::pi_v<float>;

// One device for the whole file: creating one per render costs time (validation layers) and
// some drivers refuse new instances after a few dozen in one process.
vk::Context& testContext() {
  static vk::Context context(vk::contextOptionsFromEnvironment());
  return context;
}

// Renders `scene` and checks what every render must satisfy: no validation error, no NaN or
// infinite pixel, no dropped sample.
ReferenceResult renderReference(const Scene& scene, const ReferenceOptions& options,
                                std::optional<Camera> camera = std::nullopt) {
  vk::Context& context = testContext();
  const uint32_t errorsBefore = context.validationErrorCount();
  GpuScene gpuScene(context, scene);
  ReferencePathTracer tracer(context, gpuScene, scene);
  ReferenceResult result = tracer.render(camera ? *camera : effectiveCamera(scene), options);
  EXPECT_EQ(context.validationErrorCount(), errorsBefore);
  EXPECT_EQ(countNonFinitePixels(result.image), 0u);
  EXPECT_EQ(result.droppedSamples, 0u);
  EXPECT_EQ(result.samplesPerPixel, options.samplesPerPixel);
  return result;
}

ReferenceOptions smallOptions(uint32_t width, uint32_t height, uint32_t spp) {
  ReferenceOptions o;
  o.width = width;
  o.height = height;
  o.samplesPerPixel = spp;
  return o;
}

glm::dvec3 meanColor(const ImageRGBA32F& image) {
  glm::dvec3 sum(0.0);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) sum += glm::dvec3(glm::vec3(image.at(x, y)));
  return sum / double(image.pixelCount());
}

// Mean over pixels and channels of (a - b)^2.
double meanSquaredDifference(const ImageRGBA32F& a, const ImageRGBA32F& b) {
  double sum = 0.0;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      glm::vec3 d = glm::vec3(a.at(x, y)) - glm::vec3(b.at(x, y));
      sum += double(glm::dot(d, d));
    }
  return sum / (3.0 * double(a.pixelCount()));
}

ImageRGBA32F constantImage(int width, int height, const glm::vec3& value) {
  return ImageRGBA32F(width, height, glm::vec4(value, 1.0f));
}

// Box-filters by an integer factor: with exactly matching pixel footprints, a W/f x H/f render
// is an estimate of the same image as a W x H one downsampled so.
ImageRGBA32F boxDownsample(const ImageRGBA32F& image, int factor) {
  ImageRGBA32F out(image.width / factor, image.height / factor);
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x) {
      glm::vec4 sum(0.0f);
      for (int j = 0; j < factor; ++j)
        for (int i = 0; i < factor; ++i) sum += image.at(x * factor + i, y * factor + j);
      glm::vec4 mean = sum / float(factor * factor);
      out.set(x, y, glm::vec4(glm::vec3(mean), 1.0f));
    }
  return out;
}

ImageRGBA32F average(const ImageRGBA32F& a, const ImageRGBA32F& b) {
  ImageRGBA32F out(a.width, a.height);
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) out.set(x, y, 0.5f * (a.at(x, y) + b.at(x, y)));
  return out;
}

// A camera straight above `target`, looking down (-Y), image top towards -Z.
Camera cameraLookingDown(const glm::vec3& target, float height, float vfovDegrees) {
  Camera c;
  c.position = target + glm::vec3(0.0f, height, 0.0f);
  c.target = target;
  c.up = glm::vec3(0.0f, 0.0f, -1.0f);
  c.verticalFovDegrees = vfovDegrees;
  return c;
}

// One large Lambert square at y = 0 facing up (its front face), nothing else: no sky, no sun.
Scene planeScene(const glm::vec3& albedo, float halfSize = 100.0f) {
  Scene scene;
  scene.name = "plane";
  uint32_t material = procedural::addMaterial(scene, procedural::lambertMaterial("plane", albedo));
  Geometry g;
  g.material = material;
  procedural::addQuadFacing(g, {0, 1, 0}, {-halfSize, 0, halfSize}, {halfSize, 0, halfSize},
                            {halfSize, 0, -halfSize}, {-halfSize, 0, -halfSize});
  Mesh mesh;
  mesh.name = "plane";
  mesh.geometries.push_back(std::move(g));
  procedural::addMeshInstance(scene, std::move(mesh));
  scene.sun.irradiance = 0.0f;
  scene.sky.radiance = glm::vec3(0.0f);
  validateScene(scene, "test plane");
  return scene;
}

// ---- the light table (CPU) ---------------------------------------------------------------------

// The exact probability with which the alias table picks each entry.
std::vector<double> aliasProbabilities(const std::vector<gpu::GpuLightAlias>& table) {
  std::vector<double> p(table.size(), 0.0);
  const double n = double(table.size());
  for (size_t i = 0; i < table.size(); ++i) {
    p[i] += double(table[i].threshold) / n;
    p[table[i].alias] += (1.0 - double(table[i].threshold)) / n;
  }
  return p;
}

TEST(LightTable, AliasTablePicksInProportionToWeight) {
  const std::vector<std::vector<double>> cases = {
      {1.0}, {1.0, 1.0, 1.0}, {5.0, 0.0, 1.0, 2.0}, {1e-6, 1.0, 1e6, 3.0, 0.0, 7.5}};
  for (const std::vector<double>& weights : cases) {
    std::vector<gpu::GpuLightAlias> table = buildAliasTable(weights);
    ASSERT_EQ(table.size(), weights.size());
    double sum = 0.0;
    for (double w : weights) sum += w;
    std::vector<double> p = aliasProbabilities(table);
    for (size_t i = 0; i < weights.size(); ++i) {
      EXPECT_NEAR(p[i], weights[i] / sum, 1e-6) << "entry " << i;
      EXPECT_NEAR(table[i].pmf, weights[i] / sum, 1e-6) << "entry " << i;
      EXPECT_LT(table[i].alias, table.size());
      if (weights[i] == 0.0)
        EXPECT_EQ(table[i].threshold, 0.0f) << "zero weight must never be kept";
    }
  }
  EXPECT_THROW(buildAliasTable(std::vector<double>{0.0, 0.0}), Error);
  EXPECT_THROW(buildAliasTable(std::vector<double>{1.0, -1.0}), Error);
}

TEST(LightTable, CornellLightIsOneDownwardQuad) {
  Scene scene = loadScene(test::sharedDir() + "/scenes/cornell_box/cornell_box.gltf");
  rt::SceneBvh bvh = rt::buildSceneBvh(scene);
  LightTable lights = buildLightTable(scene, bvh);
  ASSERT_EQ(lights.emissiveTriangles.size(), 2u);
  EXPECT_TRUE(lights.punctualLights.empty());
  EXPECT_TRUE(lights.distantLights.empty());  // no sun in the file
  float area = 0.0f;
  for (const auto& t : lights.emissiveTriangles) {
    EXPECT_NEAR(t.frontNormal.y, -1.0f, 1e-6f) << "the light faces down";
    area += t.area;
  }
  EXPECT_NEAR(area, 0.130f * 0.105f, 1e-6f);
  const double expectedPower = std::numbers::pi * area * luminance({17.0f, 12.0f, 4.0f});
  EXPECT_NEAR(lights.totalLocalPower, expectedPower, 1e-4 * expectedPower);
}

TEST(LightTable, PunctualAndDistantLightsAreConverted) {
  Scene scene = planeScene(glm::vec3(0.5f));
  scene.sun = Sun{glm::normalize(glm::vec3(1, -1, 0)), 3.0f, {1.0f, 0.5f, 0.25f}, 10.0f};
  PunctualLight point;
  point.intensity = 2.0f;
  point.color = {1.0f, 1.0f, 1.0f};
  PunctualLight spot = point;
  spot.type = PunctualLight::Type::Spot;
  spot.outerConeAngle = 0.5f;
  PunctualLight directional = point;
  directional.type = PunctualLight::Type::Directional;
  scene.lights = {point, spot, directional};
  LightTable lights = buildLightTable(scene, rt::buildSceneBvh(scene));
  ASSERT_EQ(lights.punctualLights.size(), 2u);
  ASSERT_EQ(lights.distantLights.size(), 2u);  // the sun and the directional light
  EXPECT_NEAR(lights.totalLocalPower,
              4.0 * std::numbers::pi * 2.0 + 2.0 * std::numbers::pi * (1.0 - std::cos(0.5)) * 2.0,
              1e-4);
  // The sun's cone: radiance E / (pi sin^2), integrated over the cone's solid angle.
  const double c = std::cos(5.0 * std::numbers::pi / 180.0);
  EXPECT_NEAR(lights.distantLights[0].coneWeight.x, 3.0 * 2.0 / (1.0 + c), 1e-5);
  EXPECT_NEAR(lights.distantLights[0].towardLight.y, std::sqrt(0.5), 1e-6);
  EXPECT_EQ(lights.distantLights[1].cosHalfAngle, 1.0f);  // a delta direction
}

// ---- analytic scenes on the GPU ----------------------------------------------------------------

// Le / (1 - a) everywhere, for a closed Lambert box of albedo a emitting Le: the whole transport
// (BRDF sampling, light sampling of emissive triangles with MIS, Russian roulette) must neither
// lose nor create energy. Two seeds also give the pixels' noise: the spread of the image around
// the exact value must be that noise and nothing more (no structure, no bias per pixel).
TEST(Reference, WhiteFurnaceConvergesToTheGeometricSeries) {
  struct Case {
    float albedo;
    glm::vec3 emission;
    uint32_t spp;
  };
  // Measured per-sample standard deviation: about 0.35 Le/(1-a) for a = 0.5 and 0.45 for
  // a = 0.8, so the image means (32 x 32 pixels) are within 0.1% and 0.15% (one sigma).
  for (const Case& c :
       {Case{0.5f, glm::vec3(1.0f), 32u}, Case{0.8f, glm::vec3(0.2f, 0.4f, 0.6f), 32u}}) {
    SCOPED_TRACE(testing::Message() << "albedo " << c.albedo);
    Scene scene = makeFurnaceScene(c.albedo, c.emission);
    ReferenceOptions o = smallOptions(32, 32, c.spp);
    o.lambert = true;
    o.maxBounces = 1024;  // Russian roulette ends the paths; a^1024 is nothing
    ReferenceResult a = renderReference(scene, o);
    o.seed = 2;
    ReferenceResult b = renderReference(scene, o);
    const glm::vec3 expected = c.emission / (1.0f - c.albedo);
    ImageRGBA32F exact = constantImage(32, 32, expected);
    const glm::dvec3 mean = meanColor(average(a.image, b.image));
    for (int ch = 0; ch < 3; ++ch)
      EXPECT_NEAR(mean[ch] / expected[ch], 1.0, 0.01) << "channel " << ch;

    const double noise = meanSquaredDifference(a.image, b.image) / 2.0;  // per image
    const double spread =
        (meanSquaredDifference(a.image, exact) + meanSquaredDifference(b.image, exact)) / 2.0;
    std::printf("furnace a=%.1f: mean %.4f %.4f %.4f (exact %.4f %.4f %.4f), spread/noise %.3f\n",
                c.albedo, mean.x, mean.y, mean.z, expected.x, expected.y, expected.z,
                spread / noise);
    EXPECT_GT(noise, 0.0);
    // 1024 pixels x 3 channels: the ratio of two variance estimates is within ~10% by chance.
    EXPECT_NEAR(spread / noise, 1.0, 0.25);
  }
}

// A Lambert plane of albedo rho under a sun of irradiance E at angle theta from the normal has
// radiance E cos(theta) rho / pi, whatever the sun's angular size (the disc's radiance is
// normalised so that its irradiance on a facing surface is E), and nothing bounces back.
TEST(Reference, SunLitLambertPlaneHasRadianceECosThetaAlbedoOverPi) {
  const glm::vec3 albedo(0.5f, 0.6f, 0.7f);
  const float thetaDegrees = 60.0f;
  const float theta = glm::radians(thetaDegrees);
  Scene scene = planeScene(albedo);
  Camera camera = cameraLookingDown({0, 0, 0}, 5.0f, 40.0f);
  struct Case {
    float angularDiameter;
    uint32_t maxBounces;
    uint32_t spp;
    double pixelTolerance;
  };
  // The delta sun has no noise at all; the 10-degree disc varies cos(theta) per sample by up
  // to +-15%, about 4% per pixel at 16 samples (the image mean: 0.3%).
  for (const Case& c : {Case{0.0f, 1, 2, 1e-4}, Case{0.0f, 4, 2, 1e-4}, Case{10.0f, 2, 16, 0.2}}) {
    SCOPED_TRACE(testing::Message()
                 << "sun " << c.angularDiameter << " deg, " << c.maxBounces << " bounces");
    scene.sun =
        Sun{{std::sin(theta), -std::cos(theta), 0.0f}, 2.0f, {1.0f, 0.8f, 0.6f}, c.angularDiameter};
    ReferenceOptions o = smallOptions(16, 16, c.spp);
    o.maxBounces = c.maxBounces;
    o.lambert = true;
    ReferenceResult r = renderReference(scene, o, camera);
    const glm::vec3 expected =
        scene.sun.irradiance * scene.sun.color * std::cos(theta) * albedo / kPi;
    const glm::dvec3 mean = meanColor(r.image);
    for (int ch = 0; ch < 3; ++ch)
      EXPECT_NEAR(mean[ch] / expected[ch], 1.0, 0.01) << "channel " << ch;
    for (int y = 0; y < r.image.height; ++y)
      for (int x = 0; x < r.image.width; ++x)
        for (int ch = 0; ch < 3; ++ch)
          ASSERT_NEAR(r.image.at(x, y)[ch] / expected[ch], 1.0, c.pixelTolerance) << x << "," << y;
  }
  // --lambert changes nothing on a Lambert plane; a sun below the horizon lights nothing.
  scene.sun = Sun{{0.0f, 1.0f, 0.0f}, 2.0f, glm::vec3(1.0f), 0.0f};
  EXPECT_EQ(meanColor(renderReference(scene, smallOptions(8, 8, 1), camera).image),
            glm::dvec3(0.0));
}

// KHR_lights_punctual, candela read as W/sr: a point light at height h over a Lambert plane
// gives radiance I rho h / (pi d^3) at horizontal distance r (d^2 = h^2 + r^2); a spot
// multiplies in the glTF smooth falloff clamp((cos - cos_outer) / (cos_inner - cos_outer))^2.
TEST(Reference, PointAndSpotLightsFollowInverseSquareAndGltfFalloff) {
  const float rho = 0.8f, h = 2.0f, intensity = 10.0f;
  const float cosInner = std::cos(0.35f), cosOuter = std::cos(0.5f);
  Scene scene = planeScene(glm::vec3(rho));
  const int size = 48;
  const float vfov = 70.0f;
  Camera camera = cameraLookingDown({0, 0, 0}, 4.0f, vfov);
  for (PunctualLight::Type type : {PunctualLight::Type::Point, PunctualLight::Type::Spot}) {
    const bool spot = type == PunctualLight::Type::Spot;
    SCOPED_TRACE(spot ? "spot" : "point");
    PunctualLight light;
    light.type = type;
    light.intensity = intensity;
    light.color = {1.0f, 0.5f, 0.25f};
    light.position = {0.0f, h, 0.0f};
    light.direction = {0.0f, -1.0f, 0.0f};
    light.innerConeAngle = 0.35f;
    light.outerConeAngle = 0.5f;
    scene.lights = {light};
    ReferenceOptions o = smallOptions(size, size, 96);
    o.lambert = true;
    ReferenceResult r = renderReference(scene, o, camera);
    // Radiance at the plane point a camera ray through image point (u, v) sees (the camera
    // looks down -Y from height 4, image top towards -Z), averaged over each pixel like the box
    // filter does (16 x 16 points), since the spot's falloff has kinks at its cone edges.
    const float tanHalf = std::tan(glm::radians(vfov) * 0.5f);
    auto radianceAt = [&](float u, float v) {
      float px = (2.0f * u / size - 1.0f) * tanHalf * 4.0f;
      float pz = (2.0f * v / size - 1.0f) * tanHalf * 4.0f;
      float d = std::sqrt(h * h + px * px + pz * pz);
      float falloff = 1.0f;
      if (spot) {
        float a = std::clamp((h / d - cosOuter) / (cosInner - cosOuter), 0.0f, 1.0f);
        falloff = a * a;
      }
      return intensity * rho * h / (kPi * d * d * d) * falloff;
    };
    double worst = 0.0, peak = 0.0;
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x) {
        double expected = 0.0;
        for (int j = 0; j < 16; ++j)
          for (int i = 0; i < 16; ++i)
            expected += radianceAt(x + (i + 0.5f) / 16, y + (j + 0.5f) / 16);
        expected /= 256.0;
        peak = std::max(peak, expected);
        worst = std::max(worst, std::abs(double(r.image.at(x, y).x) - expected));
        // Colour: the light's (1, 0.5, 0.25) on a grey plane.
        EXPECT_NEAR(r.image.at(x, y).y, 0.5f * r.image.at(x, y).x,
                    1e-5f + 1e-4f * r.image.at(x, y).x);
      }
    // What remains is the noise of 96 stratified points per pixel where the radiance changes
    // fast within a pixel (measured: 0.1% of the peak for the point light, 0.8% at the spot's
    // cone edge; it falls about as 1 / samples).
    EXPECT_LT(worst / peak, 0.015) << "worst " << worst << " peak " << peak;
    std::printf("%s light: worst pixel error %.4f of the peak\n", spot ? "spot" : "point",
                worst / peak);
  }
}

// Emission comes from the glTF front face only, also for an instance whose transform mirrors
// (whose front face is then clockwise in world space, glTF 2.0 §3.7.4): light sampling and BRDF
// hits must agree with this.
TEST(Reference, EmissionIsOneSidedAndFollowsMirroring) {
  Scene scene;
  scene.name = "emitter";
  Material m = procedural::lambertMaterial("emitter", glm::vec3(0.0f));
  m.emissive = {2.0f, 3.0f, 4.0f};
  Geometry g;
  g.material = procedural::addMaterial(scene, m);
  procedural::addQuadFacing(g, {0, 0, 1}, {-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0});
  Mesh mesh;
  mesh.name = "emitter";
  mesh.geometries.push_back(std::move(g));
  uint32_t meshIndex = procedural::addMesh(scene, std::move(mesh));
  procedural::addInstance(scene, meshIndex, glm::mat4(1.0f), "plain");
  procedural::addInstance(scene, meshIndex,
                          glm::scale(procedural::translation({5, 0, 0}), glm::vec3(-1, 1, 1)),
                          "mirrored");
  validateScene(scene, "emitter test");
  for (float x : {0.0f, 5.0f}) {
    Camera front{{x, 0, 3}, {x, 0, 0}, {0, 1, 0}, 20.0f};
    Camera back{{x, 0, -3}, {x, 0, 0}, {0, 1, 0}, 20.0f};
    ReferenceResult seen = renderReference(scene, smallOptions(4, 4, 1), front);
    ReferenceResult behind = renderReference(scene, smallOptions(4, 4, 1), back);
    EXPECT_EQ(glm::vec3(seen.image.at(2, 2)), glm::vec3(2.0f, 3.0f, 4.0f))
        << "instance at x = " << x;
    EXPECT_EQ(glm::vec3(behind.image.at(2, 2)), glm::vec3(0.0f)) << "instance at x = " << x;
  }
  // Light sampling uses the same side.
  LightTable lights = buildLightTable(scene, rt::buildSceneBvh(scene));
  ASSERT_EQ(lights.emissiveTriangles.size(), 4u);
  for (const auto& t : lights.emissiveTriangles) EXPECT_NEAR(t.frontNormal.z, 1.0f, 1e-6f);
}

// A plane of a glTF material seen from angle theta_o through a tiny field of view, (1) under a
// delta sun in the mirror direction, where the radiance is E cos(theta_i) f(wo, wi): the
// evaluation light sampling uses; (2) under a constant sky of radiance 1 and nothing else,
// where it is the directional albedo, reached by BRDF sampling alone: the sampled directions'
// weights f cos / pdf must average to the integral of f cos, which fails for a pdf that is not
// the density the sampler draws from.
TEST(Reference, GltfBrdfMatchesTheSpecificationWhenLitAndWhenSampled) {
  struct Case {
    float metallic, roughness;
  };
  const glm::vec3 c(0.9f, 0.6f, 0.3f);
  for (const Case& m : {Case{0.0f, 0.5f}, Case{1.0f, 0.3f}, Case{0.5f, 0.8f}, Case{1.0f, 1.0f}}) {
    for (float thetaDegrees : {20.0f, 65.0f}) {
      SCOPED_TRACE(testing::Message() << "metallic " << m.metallic << " roughness " << m.roughness
                                      << " view " << thetaDegrees << " deg");
      Scene scene;
      scene.name = "brdf";
      Material material = procedural::lambertMaterial("glossy", c);
      material.metallic = m.metallic;
      material.roughness = m.roughness;
      Geometry g;
      g.material = procedural::addMaterial(scene, material);
      procedural::addQuadFacing(g, {0, 1, 0}, {-100, 0, 100}, {100, 0, 100}, {100, 0, -100},
                                {-100, 0, -100});
      Mesh mesh;
      mesh.name = "plane";
      mesh.geometries.push_back(std::move(g));
      procedural::addMeshInstance(scene, std::move(mesh));
      const float theta = glm::radians(thetaDegrees);
      const glm::vec3 wo(std::sin(theta), std::cos(theta), 0.0f);
      Camera camera{5.0f * wo, {0, 0, 0}, {0, 1, 0}, 0.5f};

      const glm::vec3 wi(-wo.x, wo.y, 0.0f);  // the mirror direction
      scene.sun = Sun{-wi, 2.0f, glm::vec3(1.0f), 0.0f};
      scene.sky.radiance = glm::vec3(0.0f);
      ReferenceOptions o = smallOptions(4, 4, 1);
      o.maxBounces = 1;
      glm::vec3 lit = glm::vec3(meanColor(renderReference(scene, o, camera).image));
      glm::vec3 expectedLit = 2.0f * wi.y * gltfBrdf(c, m.metallic, m.roughness, wo, wi);
      for (int ch = 0; ch < 3; ++ch)
        EXPECT_NEAR(lit[ch] / expectedLit[ch], 1.0, 0.01) << "sun, channel " << ch;

      scene.sun.irradiance = 0.0f;
      scene.sky.radiance = glm::vec3(1.0f);
      o = smallOptions(16, 16, 256);
      o.maxBounces = 1;
      glm::vec3 sampled = glm::vec3(meanColor(renderReference(scene, o, camera).image));
      glm::vec3 albedo = directionalAlbedo(c, m.metallic, m.roughness, wo);
      std::printf(
          "metallic %.1f roughness %.1f view %2.0f: lit/expected %.4f, sky-lit %.4f %.4f %.4f "
          "albedo %.4f %.4f %.4f\n",
          m.metallic, m.roughness, thetaDegrees, lit.x / expectedLit.x, sampled.x, sampled.y,
          sampled.z, albedo.x, albedo.y, albedo.z);
      // The weights vary by up to 90% (relative standard deviation, metallic at roughness 1), so
      // 65k samples leave 0.35% noise: 1.5% is four sigma.
      for (int ch = 0; ch < 3; ++ch)
        EXPECT_NEAR(sampled[ch] / albedo[ch], 1.0, 0.015) << "sky, channel " << ch;
    }
  }
}

// An alpha-tested emitter whose alpha is below its cutoff is not there: the camera sees through
// it, BRDF rays pass it, and light sampling (which picks points on emissive triangles without
// tracing to them first) must not count it either.
TEST(Reference, CutOutEmittersEmitNothing) {
  Scene scene = planeScene(glm::vec3(0.8f));
  Material m = procedural::lambertMaterial("cut-out emitter", glm::vec3(0.5f));
  m.emissive = {5.0f, 5.0f, 5.0f};
  m.alphaMode = AlphaMode::Mask;
  m.alphaCutoff = 0.5f;
  m.baseColor.w = 0.2f;
  Geometry g;
  g.material = procedural::addMaterial(scene, m);
  procedural::addQuadFacing(g, {0, -1, 0}, {-1, 1, -1}, {1, 1, -1}, {1, 1, 1}, {-1, 1, 1});
  Mesh mesh;
  mesh.name = "emitter";
  mesh.geometries.push_back(std::move(g));
  procedural::addMeshInstance(scene, std::move(mesh));
  validateScene(scene, "cut-out emitter test");
  ReferenceOptions o = smallOptions(8, 8, 4);
  o.maxBounces = 3;
  ReferenceResult r = renderReference(scene, o, cameraLookingDown({0, 0, 0}, 0.5f, 60.0f));
  EXPECT_EQ(meanColor(r.image), glm::dvec3(0.0));
  // The same emitter, opaque, lights the plane.
  scene.materials.back().alphaMode = AlphaMode::Opaque;
  ReferenceResult lit = renderReference(scene, o, cameraLookingDown({0, 0, 0}, 0.5f, 60.0f));
  EXPECT_GT(meanColor(lit.image).x, 0.1);
}

// Preetham et al. 1999: looking straight up, the sky has the zenith luminance
// Y_z = (4.0453 T - 4.9710) tan(chi) - 0.2155 T + 2.4192 kcd/m^2, chi = (4/9 - T/120)(pi - 2
// theta_s), scaled by E / kDaylightSunKilolux; it is bluish there, and brighter towards the sun.
TEST(Reference, DaylightSkyHasThePreethamZenithLuminance) {
  Scene scene = planeScene(glm::vec3(0.5f), 1.0f);
  const float sunElevation = glm::radians(40.0f);
  const float turbidity = 3.0f;
  scene.sun =
      Sun{{0.0f, -std::sin(sunElevation), -std::cos(sunElevation)}, 50.0f, glm::vec3(1.0f), 0.53f};
  scene.sky = parseSky("daylight:3");
  ASSERT_EQ(scene.sky.model, SkyModel::Daylight);
  ASSERT_EQ(scene.sky.turbidity, turbidity);
  Camera up{{0, 10, 0}, {0, 11, 0}, {0, 0, -1}, 1.0f};
  ReferenceResult zenith = renderReference(scene, smallOptions(4, 4, 1), up);
  const float thetaSun = kPi / 2 - sunElevation;
  const float chi = (4.0f / 9.0f - turbidity / 120.0f) * (kPi - 2.0f * thetaSun);
  const float yz = (4.0453f * turbidity - 4.9710f) * std::tan(chi) - 0.2155f * turbidity + 2.4192f;
  const glm::vec3 c = glm::vec3(zenith.image.at(2, 2));
  EXPECT_NEAR(luminance(c), yz * daylightSkyScale(scene.sun),
              0.01f * yz * daylightSkyScale(scene.sun));
  EXPECT_GT(c.z, c.x) << "a clear zenith is blue";
  // Low in the sky towards the sun (+Z: its light travels towards -Z) against the opposite.
  Camera towardSun{{0, 10, 0}, {0, 10.3f, 1}, {0, 1, 0}, 1.0f};
  Camera awayFromSun{{0, 10, 0}, {0, 10.3f, -1}, {0, 1, 0}, 1.0f};
  float toward =
      luminance(glm::vec3(renderReference(scene, smallOptions(4, 4, 1), towardSun).image.at(2, 2)));
  float away = luminance(
      glm::vec3(renderReference(scene, smallOptions(4, 4, 1), awayFromSun).image.at(2, 2)));
  EXPECT_GT(toward, 1.5f * away);
  EXPECT_THROW(parseSky("daylight:1"), Error);
  EXPECT_THROW(parseSky("daylight:x"), Error);
  EXPECT_THROW(parseSky("daylights"), Error);
  EXPECT_EQ(parseSky("1,2,3").radiance, glm::vec3(1, 2, 3));
  EXPECT_EQ(parseSky("1,2,3").model, SkyModel::Constant);
}

// ---- an independent renderer -------------------------------------------------------------------

// The Cornell box against Cycles (Blender 3.4.1, 4096 spp, 256 x 256, every material Lambert,
// front-face emission, max 12 bounces): we render 64 x 64, so each of our pixels covers exactly
// a 4 x 4 block of Cycles' pixels, and compare with Cycles box-downsampled. Cycles' "12 bounces"
// count the scattering events after the first hit (0 = direct lighting only), i.e. our 13.
// Two seeds give our own noise; Cycles' (4e-5 at full resolution, shared/references/README.md)
// is 16x smaller after downsampling and negligible.
TEST(Reference, CornellBoxAgreesWithCycles) {
  const std::string dir = test::sharedDir();
  Scene scene = loadScene(dir + "/scenes/cornell_box/cornell_box.gltf");
  ImageRGBA32F cycles =
      boxDownsample(readImage(dir + "/references/cornell_box/cycles_4096spp.exr"), 4);
  ReferenceOptions o = smallOptions(64, 64, 128);
  o.lambert = true;
  o.maxBounces = 13;
  ReferenceResult a = renderReference(scene, o);
  o.seed = 2;
  ReferenceResult b = renderReference(scene, o);
  ImageRGBA32F ours = average(a.image, b.image);

  const double relMse = relativeMeanSquaredError(ours, cycles);
  // Each image's noise relMSE is half that of their difference (measured against Cycles'
  // values, as relMSE is); the average of the two has half again.
  double differenceRelMse = 0.0;
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x)
      for (int ch = 0; ch < 3; ++ch) {
        double d = a.image.at(x, y)[ch] - b.image.at(x, y)[ch];
        double r = cycles.at(x, y)[ch];
        differenceRelMse += d * d / (r * r + kRelMseEpsilon);
      }
  differenceRelMse /= 3.0 * 64 * 64;
  const double ourNoise = differenceRelMse / 4.0;
  const glm::dvec3 meanOurs = meanColor(ours), meanCycles = meanColor(cycles);
  std::printf(
      "cornell vs cycles (64x64, 2 x %u spp): relMSE %.5f, our noise %.5f, remainder %.5f; "
      "mean ratio %.4f %.4f %.4f; %.1f ms/spp\n",
      o.samplesPerPixel, relMse, ourNoise, relMse - ourNoise, meanOurs.x / meanCycles.x,
      meanOurs.y / meanCycles.y, meanOurs.z / meanCycles.z,
      (a.gpuMilliseconds > 0 ? a.gpuMilliseconds : 1e3 * a.seconds) / a.samplesPerPixel);
  EXPECT_LE(relMse, 0.01);
  // What is left after our noise must be small too: a bias of a few percent anywhere would
  // show here long before it moves the 1% threshold.
  EXPECT_LE(relMse - ourNoise, 0.002);
  // Energy: the mean of the image (dominated by the light and the lit walls) within 1%.
  for (int ch = 0; ch < 3; ++ch)
    EXPECT_NEAR(meanOurs[ch] / meanCycles[ch], 1.0, 0.01) << "channel " << ch;
}

// ---- determinism and robustness ----------------------------------------------------------------

TEST(Reference, SameSeedSameImageWhateverTheBatching) {
  Scene scene = loadScene("cornell");
  ReferenceOptions o = smallOptions(16, 12, 6);
  o.batchSeconds = 1e-9;  // one sample per batch
  ReferenceResult a = renderReference(scene, o);
  EXPECT_EQ(a.batches, 6u);
  o.batchSeconds = 1e9;  // as large as the growth rule allows (1, 4, then the last 1)
  ReferenceResult b = renderReference(scene, o);
  EXPECT_LT(b.batches, 6u);
  ASSERT_EQ(a.image.pixels.size(), b.image.pixels.size());
  EXPECT_EQ(std::memcmp(a.image.pixels.data(), b.image.pixels.data(),
                        a.image.pixels.size() * sizeof(float)),
            0)
      << "same seed, same device: bit-identical";
  o.seed = 7;
  ReferenceResult c = renderReference(scene, o);
  EXPECT_GT(meanSquaredDifference(a.image, c.image), 0.0) << "another seed, another image";
}

// Every built-in scene, with its glossy and metallic materials, alpha cut-outs, sun, sky and
// point lights: finite everywhere (renderReference checks), not black, with the daylight sky
// too.
TEST(Reference, BuiltinScenesRenderFinite) {
  for (std::string name : {"sunroom", "foliage", "manylights", "city"}) {
    SCOPED_TRACE(name);
    Scene scene = loadScene(name);
    if (name == "foliage") scene.sky = parseSky("daylight");
    ReferenceResult r = renderReference(scene, smallOptions(12, 8, 2));
    EXPECT_GT(luminance(glm::vec3(meanColor(r.image))), 0.0f);
  }
}

TEST(Reference, RejectsOptionsOutOfRange) {
  Scene scene = loadScene("cornell");
  vk::Context& context = testContext();
  GpuScene gpuScene(context, scene);
  ReferencePathTracer tracer(context, gpuScene, scene);
  ReferenceOptions o = smallOptions(8, 8, 0);
  EXPECT_THROW(tracer.render(effectiveCamera(scene), o), Error);
  o.samplesPerPixel = 1;
  o.maxBounces = 5000;
  EXPECT_THROW(tracer.render(effectiveCamera(scene), o), Error);
  o.maxBounces = 2;
  o.timeLimitSeconds = -1.0;
  EXPECT_THROW(tracer.render(effectiveCamera(scene), o), Error);
}

TEST(Reference, TimeLimitStopsAfterTheBatchThatCrossesIt) {
  Scene scene = loadScene("cornell");
  ReferenceOptions o = smallOptions(16, 16, 1u << 20);
  o.timeLimitSeconds = 0.3;
  o.batchSeconds = 0.05;
  vk::Context& context = testContext();
  GpuScene gpuScene(context, scene);
  ReferencePathTracer tracer(context, gpuScene, scene);
  ReferenceResult r = tracer.render(effectiveCamera(scene), o);
  EXPECT_TRUE(r.stoppedByTimeLimit);
  EXPECT_GE(r.seconds, 0.3);
  EXPECT_LT(r.seconds, 2.0);
  EXPECT_GT(r.samplesPerPixel, 1u);
  EXPECT_LT(r.samplesPerPixel, 1u << 20);
  EXPECT_EQ(countNonFinitePixels(r.image), 0u);
}

// ---- the command line --------------------------------------------------------------------------

TEST(ReferenceCli, WritesExrAndPngAndReportsSamples) {
  const std::string dir = test::tempDir("reference-cli");
  for (std::string ext : {"exr", "png"}) {
    const std::string out = dir + "/cornell." + ext;
    test::CommandResult r =
        test::runCommand(test::bounceExe() +
                             " reference --validate --scene cornell "
                             "--res 24x16 --spp 3 --max-bounces 3 --seed 5 --out " +
                             out,
                         120);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("3 spp"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(" on "), std::string::npos) << "names the device\n" << r.output;
    ImageRGBA32F image = readImage(out);
    EXPECT_EQ(image.width, 24);
    EXPECT_EQ(image.height, 16);
    EXPECT_EQ(countNonFinitePixels(image), 0u);
    EXPECT_GT(luminance(glm::vec3(meanColor(image))), 0.0f);
  }
  // --exposure scales what a PNG shows: two stops down, a quarter (before the sRGB curve).
  test::CommandResult dark =
      test::runCommand(test::bounceExe() +
                           " reference --scene cornell --res 24x16 "
                           "--spp 3 --max-bounces 3 --seed 5 --exposure -2 --out " +
                           dir + "/dark.png",
                       120);
  ASSERT_EQ(dark.exitCode, 0) << dark.output;
  glm::dvec3 bright = meanColor(readImage(dir + "/cornell.png"));
  glm::dvec3 darker = meanColor(readImage(dir + "/dark.png"));
  EXPECT_LT(darker.x, 0.5 * bright.x);
  test::CommandResult timed = test::runCommand(test::bounceExe() +
                                                   " reference --scene cornell --res 8x8 "
                                                   "--time-limit 0.2 --out " +
                                                   dir + "/timed.exr",
                                               120);
  ASSERT_EQ(timed.exitCode, 0) << timed.output;
  EXPECT_NE(timed.output.find("stopped by --time-limit"), std::string::npos) << timed.output;
}

TEST(ReferenceCli, BadOptionsGetAClearError) {
  const std::string dir = test::tempDir("reference-cli-bad");
  struct Bad {
    std::string args;
    std::string expected;
  };
  const std::vector<Bad> cases = {
      {"--spp 0", "--spp"},
      {"--spp -3", "--spp"},
      {"--max-bounces -1", "--max-bounces"},
      {"--max-bounces 100000", "--max-bounces"},
      {"--seed -1", "--seed"},
      {"--time-limit -2", "--time-limit"},
      {"--scene nosuchscene", "not a built-in scene"},
      {"--scene " + dir + "/missing.gltf", "missing.gltf"},
      {"--sky daylight:50", "--sky"},
      {"--out " + dir + "/image.bmp", "--out"},
      {"--exposure nan", "--exposure"},
  };
  for (const Bad& c : cases) {
    std::string args = " reference --res 8x8 " + c.args;
    if (c.args.find("--spp") == std::string::npos) args += " --spp 1";
    if (c.args.find("--out") == std::string::npos) args += " --out " + dir + "/x.exr";
    test::CommandResult r = test::runCommand(test::bounceExe() + args, 60);
    EXPECT_GE(r.exitCode, 1) << c.args << "\n" << r.output;
    EXPECT_LE(r.exitCode, 4) << c.args << " (crash or hang?)\n" << r.output;
    EXPECT_NE(r.output.find(c.expected), std::string::npos)
        << c.args << ": message should mention '" << c.expected << "'\n"
        << r.output;
  }
}

}  // namespace
}  // namespace bounce
