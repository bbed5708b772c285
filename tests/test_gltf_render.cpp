// A user's own glTF renders right on the first try (issue 18), checked through the `bounce`
// program on files written by the test: an unlit file gets the default daylight (and an explicit
// --sky keeps it dark), vertex colours multiply the base colour in the reference path tracer and
// in the real-time G-buffer, a file whose only triangles are degenerate renders as sky, and a mesh
// under an animated parent moves when the animation plays (issue 22).
//
// The expected values are physics, not snapshots: a Lambert surface of albedo rho under a
// constant sky of radiance L (and nothing else in the scene) reflects exactly rho L; under a sun
// of irradiance E at elevation h it reflects at least rho E sin(h) / pi.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>

#include <gtest/gtest.h>
#include <glm/gtc/type_precision.hpp>
#include <nlohmann/json.hpp>

#include "gltf_writer.h"
#include "harness.h"
#include "scene/default_light.h"
#include "scene/time_of_day.h"
#include "tools/image_io.h"
#include "tools/metrics.h"

namespace bounce {
namespace {

using nlohmann::json;
using test::GltfWriter;
namespace fs = std::filesystem;

constexpr double kPi = std::numbers::pi;

class GltfRenderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir = test::tempDir(std::string("gltf-render-") +
                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
  }
  void TearDown() override { fs::remove_all(dir); }

  // Runs `bounce <arguments> --out <dir>/<name>.exr`, expects exit code 0 and returns the image;
  // `output` gets what the program printed.
  ImageRGBA32F run(const std::string& arguments, const std::string& name, std::string* output) {
    const std::string out = dir + "/" + name + ".exr";
    test::CommandResult r =
        test::runCommand(test::bounceExe() + " " + arguments + " --out " + out, 600);
    EXPECT_EQ(r.exitCode, 0) << arguments << "\n" << r.output;
    if (output) *output = r.output;
    if (r.exitCode != 0 || !fs::exists(out)) return ImageRGBA32F(1, 1);
    return readImage(out);
  }

  std::string dir;
};

glm::dvec3 meanColor(const ImageRGBA32F& image) {
  glm::dvec3 sum(0.0);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) sum += glm::dvec3(glm::vec3(image.at(x, y)));
  return sum / double(image.pixelCount());
}

// A white Lambert square facing up (+Y), 200 m wide: from the camera above it fills the view.
std::string writeWhitePlane(const std::string& dir) {
  GltfWriter w;
  int pos = w.addPositions({{-100, 0, 100}, {100, 0, 100}, {100, 0, -100}, {-100, 0, -100}});
  int idx = w.addIndices16({0, 1, 2, 0, 2, 3});
  w.doc["materials"] = json::array({{{"pbrMetallicRoughness",
                                      {{"baseColorFactor", {1.0, 1.0, 1.0, 1.0}},
                                       {"metallicFactor", 0.0},
                                       {"roughnessFactor", 1.0}}}}});
  w.addNode(
      {{"mesh",
        w.addMesh({{"attributes", {{"POSITION", pos}}}, {"indices", idx}, {"material", 0}})}});
  return w.writeGltf(dir, "white_plane");
}

// A glTF without any light is lit by the default daylight, like a glTF viewer shows it: a white
// Lambert plane reflects at least the sun's share E sin(h) / pi, and the clear sky adds a
// positive amount smaller than the sun's (a clear sky's diffuse light is a fraction of the
// direct sun's at 38 degrees of elevation). With an explicit --sky 0,0,0 there is no default:
// the image is black.
TEST_F(GltfRenderTest, UnlitFileIsLitByTheDefaultDaylight) {
  const std::string plane = writeWhitePlane(dir);
  const std::string common = " reference --validate --scene " + plane +
                             " --res 16x16 --spp 4 --lambert --camera 0,5,0:0,0,0:40";
  std::string output;
  ImageRGBA32F lit = run(common, "lit", &output);
  EXPECT_NE(output.find(plane + " has no lights: using a daylight sky and sun"), std::string::npos)
      << output;
  const double sunShare =
      kDaylightSunKilolux * double(towardSunAt(kDefaultSunHours).y) / kPi;  // rho = 1
  const glm::dvec3 mean = meanColor(lit);
  for (int c = 0; c < 3; ++c) {
    EXPECT_GT(mean[c], sunShare) << "channel " << c << ": the sun alone gives " << sunShare;
    EXPECT_LT(mean[c], 2.0 * sunShare) << "channel " << c << ": the sky outshines the sun";
  }
  EXPECT_GT(mean.z - sunShare, mean.x - sunShare) << "a clear sky is blue";

  ImageRGBA32F dark = run(common + " --sky 0,0,0", "dark", &output);
  EXPECT_EQ(output.find("has no lights"), std::string::npos) << output;
  EXPECT_EQ(meanColor(dark), glm::dvec3(0.0));
}

// Four quadrants of a square facing the camera: three carry per-vertex colours (one colour per
// quadrant, so the interpolated colour is exact), the fourth is a primitive without COLOR_0.
// Under a constant white sky with nothing else around, a Lambert surface's radiance is its
// albedo: base colour x vertex colour (glTF 2.0 §3.9.2), and the base colour alone without
// COLOR_0. The real-time G-buffer stores the same base colour.
TEST_F(GltfRenderTest, VertexColorsMultiplyTheBaseColour) {
  const glm::vec3 baseColor(0.8f, 0.6f, 1.0f);
  // Quadrants by image position; colours are exact in 8 bits (k / 255).
  const glm::u8vec4 colors[3] = {{255, 51, 0, 255}, {0, 204, 102, 255}, {153, 153, 255, 255}};
  const glm::vec2 corner[4] = {{-1, 0}, {0, 0}, {-1, -1}, {0, -1}};  // top left, top right, ...
  std::vector<glm::vec3> colored, plain;
  std::vector<uint8_t> rgba;
  std::vector<uint16_t> coloredIndices, plainIndices;
  auto addQuadrant = [](std::vector<glm::vec3>& p, std::vector<uint16_t>& idx, glm::vec2 c) {
    uint16_t base = uint16_t(p.size());
    for (glm::vec2 d : {glm::vec2(0, 0), glm::vec2(1, 0), glm::vec2(1, 1), glm::vec2(0, 1)})
      p.push_back(glm::vec3(c + d, 0.0f));
    for (uint16_t k : {0, 1, 2, 0, 2, 3}) idx.push_back(uint16_t(base + k));
  };
  for (int q = 0; q < 3; ++q) {
    addQuadrant(colored, coloredIndices, corner[q]);
    for (int v = 0; v < 4; ++v) rgba.insert(rgba.end(), &colors[q].x, &colors[q].x + 4);
  }
  addQuadrant(plain, plainIndices, corner[3]);
  GltfWriter w;
  int colorAccessor = w.addAccessor(w.addView(rgba.data(), rgba.size()), 5121, 12, "VEC4");
  w.doc["accessors"][colorAccessor]["normalized"] = true;
  w.doc["materials"] =
      json::array({{{"pbrMetallicRoughness",
                     {{"baseColorFactor", {baseColor.x, baseColor.y, baseColor.z, 1.0}},
                      {"metallicFactor", 0.0}}}}});
  json withColors = {
      {"attributes", {{"POSITION", w.addPositions(colored)}, {"COLOR_0", colorAccessor}}},
      {"indices", w.addIndices16(coloredIndices)},
      {"material", 0}};
  json withoutColors = {{"attributes", {{"POSITION", w.addPositions(plain)}}},
                        {"indices", w.addIndices16(plainIndices)},
                        {"material", 0}};
  w.doc["meshes"].push_back({{"primitives", {withColors, withoutColors}}});
  w.addNode({{"mesh", 0}});
  const std::string path = w.writeGltf(dir, "vertex_colors");

  // 16 x 16 pixels over a 2 x 2 square seen at 40 degrees: each quadrant covers 7 x 7 pixels
  // around (4 or 11, 4 or 11); the 3 x 3 pixels around those centres lie well inside.
  const std::string view = " --scene " + path + " --res 16x16 --camera 0,0,3:0,0,0:40";
  ImageRGBA32F reference =
      run("reference --validate --lambert --spp 2 --sky 1,1,1" + view, "reference", nullptr);
  ImageRGBA32F gbuffer =
      run("render --validate --gi none --frames 1 --view gbuffer.base-color" + view, "gbuffer",
          nullptr);
  const int centre[4][2] = {{4, 4}, {11, 4}, {4, 11}, {11, 11}};
  for (int q = 0; q < 4; ++q) {
    const glm::vec3 expected =
        q < 3 ? baseColor * glm::vec3(colors[q]) / 255.0f : baseColor;  // no COLOR_0: unchanged
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const int x = centre[q][0] + dx, y = centre[q][1] + dy;
        for (int c = 0; c < 3; ++c) {
          // The reference is exact here (cosine-weighted sampling of a Lambert surface under a
          // constant sky has no variance); the G-buffer stores half floats (11-bit mantissa).
          EXPECT_NEAR(reference.at(x, y)[c], expected[c], 1e-4)
              << "reference, quadrant " << q << ", pixel " << x << "," << y << ", channel " << c;
          EXPECT_NEAR(gbuffer.at(x, y)[c], expected[c], 1e-3)
              << "G-buffer, quadrant " << q << ", pixel " << x << "," << y << ", channel " << c;
        }
      }
  }
}

// A valid file whose only triangle is degenerate loads as an empty scene: the path tracer sees
// only the sky, and the real-time frame (every GI pass included) runs on zero triangles without
// a validation error.
TEST_F(GltfRenderTest, FileWithOnlyDegenerateTrianglesRendersTheSky) {
  GltfWriter w;
  int pos = w.addPositions({{0, 0, 0}, {1, 1, 1}, {2, 2, 2}});
  w.addNode({{"mesh", w.addMesh({{"attributes", {{"POSITION", pos}}}})}});
  const std::string path = w.writeGltf(dir, "degenerate");
  const glm::vec3 sky(0.25f, 0.5f, 0.75f);
  std::string output;
  ImageRGBA32F reference = run(
      "reference --validate --spp 1 --res 8x8 --sky 0.25,0.5,0.75 --scene " + path, "sky", &output);
  EXPECT_NE(output.find("skipped: its one triangle has zero area"), std::string::npos) << output;
  for (int y = 0; y < reference.height; ++y)
    for (int x = 0; x < reference.width; ++x)
      ASSERT_EQ(glm::vec3(reference.at(x, y)), sky) << x << "," << y;
  ImageRGBA32F frame =
      run("render --validate --frames 2 --res 16x16 --scene " + path, "frame", nullptr);
  EXPECT_EQ(countNonFinitePixels(frame), 0u);
  EXPECT_GT(meanColor(frame).z, 0.0) << "the default daylight's sky";
}

// The centroid, in pixels, of the pixels whose base colour is red (the box below), and their
// count.
glm::dvec3 redCentroid(const ImageRGBA32F& image) {
  glm::dvec2 sum(0.0);
  double count = 0.0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      glm::vec4 c = image.at(x, y);
      if (c.x > 0.5f && c.y < 0.2f && c.z < 0.2f) {
        sum += glm::dvec2(x, y);
        count += 1.0;
      }
    }
  return count > 0.0 ? glm::dvec3(sum / count, count) : glm::dvec3(0.0);
}

// A red cube 2 m out (+X) on an empty "cart" that slides 4 m along -X over 1 s, over a white
// floor, seen from above. Played to t = 0.5 (`render --animate`, AnimationPlayer: the cart's
// joint track, then the box's track under it) the box's G-buffer base colour stands where the
// pose says (`--pose-time 0.5`, sceneFrozenAt) to within a pixel, 2 m from its rest place.
TEST_F(GltfRenderTest, MeshUnderAnAnimatedParentMovesWhenPlayed) {
  GltfWriter w;
  std::vector<glm::vec3> cube;
  std::vector<uint16_t> cubeIndices;
  const glm::vec3 axes[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  for (int a = 0; a < 3; ++a)
    for (float side : {-1.0f, 1.0f}) {
      glm::vec3 n = side * axes[a], u = axes[(a + 1) % 3], v = side * axes[(a + 2) % 3];
      uint16_t base = uint16_t(cube.size());
      for (glm::vec2 d : {glm::vec2(-1, -1), glm::vec2(1, -1), glm::vec2(1, 1), glm::vec2(-1, 1)})
        cube.push_back(0.5f * (n + d.x * u + d.y * v) + glm::vec3(0, 0.5f, 0));
      for (uint16_t k : {0, 1, 2, 0, 2, 3}) cubeIndices.push_back(uint16_t(base + k));
    }
  int floorPos = w.addPositions({{-5, 0, 5}, {5, 0, 5}, {5, 0, -5}, {-5, 0, -5}});
  int floorIdx = w.addIndices16({0, 1, 2, 0, 2, 3});
  w.doc["materials"] =
      json::array({{{"pbrMetallicRoughness", {{"baseColorFactor", {1.0, 1.0, 1.0, 1.0}}}}},
                   {{"pbrMetallicRoughness", {{"baseColorFactor", {1.0, 0.0, 0.0, 1.0}}}}}});
  w.addNode({{"mesh", w.addMesh({{"attributes", {{"POSITION", floorPos}}},
                                 {"indices", floorIdx},
                                 {"material", 0}})}});
  int box = w.addNode({{"mesh", w.addMesh({{"attributes", {{"POSITION", w.addPositions(cube)}}},
                                           {"indices", w.addIndices16(cubeIndices)},
                                           {"material", 1}})},
                       {"translation", {2, 0, 0}}},
                      false);
  int cart = w.addNode({{"name", "cart"}, {"children", {box}}});
  const float times[] = {0.0f, 1.0f};
  const float moves[] = {0, 0, 0, -4, 0, 0};
  int in = w.addAccessor(w.addView(times, sizeof(times)), test::kFloat, 2, "SCALAR");
  int out = w.addAccessor(w.addView(moves, sizeof(moves)), test::kFloat, 2, "VEC3");
  w.doc["animations"] = json::array(
      {{{"samplers", {{{"input", in}, {"output", out}}}},
        {"channels", {{{"sampler", 0}, {"target", {{"node", cart}, {"path", "translation"}}}}}}}});
  const std::string path = w.writeGltf(dir, "cart");
  const std::string cameraPath = dir + "/camera.json";
  std::ofstream(cameraPath) << R"({"keyframes": [{"time": 0, "position": [0, 9, 1], )"
                               R"("target": [0, 0, 0], "vfov": 50}]})";
  // Frame 8 of 9 at 16 fps is t = 0.5 s; every run draws 9 frames (the same jitter).
  const std::string common = "render --validate --gi none --frames 9 --res 64x48 --camera-path " +
                             cameraPath + " --view gbuffer.base-color --scene " + path;
  const glm::dvec3 rest = redCentroid(run(common, "rest", nullptr));
  const glm::dvec3 frozen = redCentroid(run(common + " --pose-time 0.5", "frozen", nullptr));
  const glm::dvec3 played = redCentroid(run(common + " --animate --fps 16", "played", nullptr));
  std::printf("red box centroid (px): rest (%.2f, %.2f), posed (%.2f, %.2f), played (%.2f, %.2f)\n",
              rest.x, rest.y, frozen.x, frozen.y, played.x, played.y);
  ASSERT_GT(rest.z, 0.0);
  ASSERT_GT(frozen.z, 0.0);
  ASSERT_GT(played.z, 0.0);
  // 2 m at this view is about 10 pixels: the pose moved the box.
  EXPECT_GT(rest.x - frozen.x, 5.0) << "rest " << rest.x << ", posed " << frozen.x;
  EXPECT_LT(glm::length(glm::dvec2(played) - glm::dvec2(frozen)), 1.0)
      << "played (" << played.x << ", " << played.y << "), posed (" << frozen.x << ", " << frozen.y
      << "), rest (" << rest.x << ", " << rest.y << ")";
}

}  // namespace
}  // namespace bounce
