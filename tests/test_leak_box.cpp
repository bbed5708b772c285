// Light leaks through thin walls (issue 23: "light inside a closed box stays below 1 % of the
// outside's", each GI mode). A closed box with 2 cm walls stands on a ground plane under a
// bright sun and sky; nothing inside emits, so the reference inside is black. The camera looks
// around the inside; its composite's mean luminance must stay below 1 % of the mean of a view
// of the lit box from outside, for evolve, gi10, lux and cache. Every GI mode gathers light
// through world-space structures (the clipmap cache's cells, GI-1.0's probes) or reuses
// samples across surfaces, and a wall thinner than a cell is where those leak.
// Measured (lavapipe, 2026-11-26): inside 0 for all four (outside 9.12-9.20). The
// test can fail: with the roof removed the inside measured 38 % (evolve) and 37 % (gi10).
#include <cstdio>
#include <ostream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "harness.h"

#include "frame/hybrid_frame.h"
#include "frame/presets.h"
#include "rt/gpu_scene.h"
#include "scene/procedural/mesh_builder.h"
#include "scene/scene.h"
#include "vk/context.h"

namespace bounce {
namespace {

using test::meanLuminance;

constexpr float kWall = 0.02f;  // wall thickness, metres

Camera insideCamera() {
  Camera c;
  c.position = {0.8f, 1.3f, 0.9f};
  c.target = {-1.0f, 0.9f, -1.2f};
  c.verticalFovDegrees = 80.0f;
  return c;
}

Camera outsideCamera() {
  Camera c;
  c.position = {6.0f, 3.0f, 7.0f};
  c.target = {0.0f, 1.0f, 0.0f};
  c.verticalFovDegrees = 50.0f;
  return c;
}

// A 3 x 2.5 x 3 m box with 2 cm walls (outer faces outward, inner faces inward: a closed room)
// on a 40 m ground plane, Lambert albedo 0.5 everywhere, under a sun of 100 W/m^2 and a sky
// of radiance 3.
Scene leakBoxScene() {
  Scene scene;
  scene.name = "leak-box";
  const uint32_t material = procedural::addMaterial(
      scene, procedural::lambertMaterial("leak_box_white", glm::vec3(0.5f)));
  Geometry g;
  g.material = material;
  Aabb outer{{-1.5f, 0.0f, -1.5f}, {1.5f, 2.5f, 1.5f}};
  Aabb inner{outer.min + kWall, outer.max - kWall};
  procedural::addBox(g, outer, procedural::Facing::Outward);
  procedural::addBox(g, inner, procedural::Facing::Inward);
  procedural::addQuadFacing(g, {0.0f, 1.0f, 0.0f}, {-20.0f, 0.0f, -20.0f}, {20.0f, 0.0f, -20.0f},
                            {20.0f, 0.0f, 20.0f}, {-20.0f, 0.0f, 20.0f});
  Mesh mesh;
  mesh.name = "leak_box";
  mesh.geometries.push_back(std::move(g));
  procedural::addMeshInstance(scene, std::move(mesh));
  scene.sun.direction = glm::normalize(glm::vec3(0.4f, -1.0f, 0.3f));
  scene.sun.irradiance = 100.0f;
  scene.sky.radiance = glm::vec3(3.0f);
  scene.camera = insideCamera();
  validateScene(scene, "leak box");
  return scene;
}

HybridSettings leakSettings(GiMode mode) {
  HybridSettings s = presetSettings(Preset::Desktop);
  s.width = 32;
  s.height = 24;
  s.lambert = true;
  s.gi = mode;
  return s;
}

// Mean composite luminance of frames 9-16 of a static view.
double meanComposite(vk::Context& context, GpuScene& gpuScene, const Scene& scene,
                     const HybridSettings& settings, const Camera& camera) {
  HybridFrame frame(context, gpuScene, scene, settings);
  frame.requestDebugView("composite");
  double sum = 0.0;
  for (int i = 0; i < 16; ++i) {
    frame.render(camera);
    if (i >= 8) sum += meanLuminance(frame.debugViewImage("composite")) / 8.0;
  }
  return sum;
}

struct LeakCase {
  const char* name;
  GiMode mode;
};

// gtest prints a parameter with this (otherwise as its bytes).
void PrintTo(const LeakCase& c, std::ostream* os) {
  *os << c.name;
}

class LeakBox : public ::testing::TestWithParam<LeakCase> {};

TEST_P(LeakBox, InsideStaysBelowOnePercentOfOutside) {
  Scene scene = leakBoxScene();
  vk::Context context(vk::contextOptionsFromEnvironment());
  GpuScene gpuScene(context, scene);
  HybridSettings settings = leakSettings(GetParam().mode);
  double inside = meanComposite(context, gpuScene, scene, settings, insideCamera());
  double outside = meanComposite(context, gpuScene, scene, settings, outsideCamera());
  std::printf("leak box, %s, 32x24, frames 9-16: inside %.5f, outside %.4f: %.3f %%\n",
              GetParam().name, inside, outside, 100.0 * inside / outside);
  EXPECT_GT(outside, 0.0);
  EXPECT_LT(inside, 0.01 * outside);
  EXPECT_EQ(context.validationErrorCount(), 0u);
}

INSTANTIATE_TEST_SUITE_P(GiModes, LeakBox,
                         ::testing::Values(LeakCase{"evolve", GiMode::Evolve},
                                           LeakCase{"gi10", GiMode::Gi10},
                                           LeakCase{"lux", GiMode::Lux},
                                           LeakCase{"cache", GiMode::Cache}),
                         [](const auto& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace bounce
