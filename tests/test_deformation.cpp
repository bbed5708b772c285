// Deforming meshes on the GPU (rt/gpu_deformer.h), on lavapipe, against the CPU pose
// (scene/deformation.h) of the built-in `skinned` scene (a skinned tube, a morphing blob):
//   - after scene-deform and scene-refit-blas, rays traced through the GPU's refitted BLAS (both
//     node layouts) hit what the brute force finds in the CPU-posed scene, pose after pose;
//   - the G-buffer's motion vectors on the skinned tube are the screen motion of the surface
//     point between the two poses, and return to zero when the pose stops changing;
//   - sceneFrozenAt (`--pose-time`) places instances and poses meshes as the animation does at
//     that time, and leaves a still scene;
//   - a skinned glTF file, loaded and posed on the GPU, traces as the brute force of its CPU pose,
//     its tip turned by the animated joint.
#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/packing.hpp>

#include "frame/hybrid_frame.h"
#include "frame_texels.h"
#include "gltf_writer.h"
#include "harness.h"
#include "passes/primary_view.h"
#include "passes/trace_rays.h"
#include "rt/cpu_trace.h"
#include "rt/gpu_scene.h"
#include "scene/deformation.h"
#include "scene/load.h"
#include "shared/camera.h"
#include "vk/context.h"

namespace bounce {
namespace {

using test::texels;

uint32_t instanceNamed(const Scene& scene, const std::string& name) {
  for (uint32_t i = 0; i < scene.instances.size(); ++i)
    if (scene.instances[i].name == name) return i;
  ADD_FAILURE() << "no instance " << name;
  return 0;
}

Aabb meshBounds(const Scene& scene, uint32_t instance) {
  Aabb box;
  for (const Geometry& g : scene.meshes[scene.instances[instance].mesh].geometries)
    for (const glm::vec3& p : g.positions) box.extend(p);
  return box;
}

// Rays from a sphere around the scene, each aimed at a random point of one of `targets`' boxes
// (most hit them, some graze past), so the deforming meshes get most of the hits.
std::vector<gpu::GpuRay> raysAt(const std::vector<Aabb>& targets, uint32_t count, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<gpu::GpuRay> rays;
  for (uint32_t i = 0; i < count; ++i) {
    const Aabb& box = targets[i % targets.size()];
    glm::vec3 target = box.min + glm::vec3(u(rng), u(rng), u(rng)) * (box.max - box.min) * 1.2f -
                       0.1f * (box.max - box.min);
    float phi = 6.2831853f * u(rng), z = 2.0f * u(rng) - 1.0f;
    glm::vec3 around(std::sqrt(1.0f - z * z) * std::cos(phi), std::abs(z),
                     std::sqrt(1.0f - z * z) * std::sin(phi));
    glm::vec3 origin = box.center() + 4.0f * around;
    rays.push_back({origin, 0.0f, target - origin, 1e30f});
  }
  return rays;
}

struct TraceComparison {
  int differ = 0;
  int deformingHits = 0;
};

TraceComparison compareWithBruteForce(const Scene& posed, std::span<const gpu::GpuRay> rays,
                                      std::span<const gpu::GpuHit> gpuHits,
                                      const std::vector<uint32_t>& deforming) {
  rt::BruteForceTracer bruteForce(posed);
  TraceComparison c;
  for (size_t i = 0; i < rays.size(); ++i) {
    rt::Ray ray{rays[i].origin, rays[i].direction, rays[i].tMin};
    const rt::TraceHit b = bruteForce.closestHit(ray, rays[i].tMax);
    const bool gpuHit = gpuHits[i].instance != gpu::HIT_NONE;
    bool same = gpuHit == b.hit && (!b.hit || (std::abs(gpuHits[i].t - b.t) <= 1e-4f * b.t &&
                                               gpuHits[i].instance == b.instance));
    c.differ += !same;
    for (uint32_t d : deforming) c.deformingHits += gpuHit && gpuHits[i].instance == d;
  }
  return c;
}

class DeformedTraversal : public ::testing::TestWithParam<rt::BvhLayout> {};

// Three poses in turn (each refit starts from the last one's boxes): the GPU hits equal the brute
// force's over the scene posed on the CPU, and most rays hit the tube or the blob.
TEST_P(DeformedTraversal, HitsWhatTheBruteForceHitsInTheCpuPose) {
  const Scene scene = loadScene("skinned");
  vk::Context context(vk::contextOptionsFromEnvironment());
  GpuScene gpuScene(context, scene, {.bvhLayout = GetParam()});
  ASSERT_TRUE(gpuScene.deforms());
  TraceRaysPass pass(context, gpuScene);
  const std::vector<uint32_t> deforming = {instanceNamed(scene, "tube"),
                                           instanceNamed(scene, "blob")};
  DeformationPose pose;
  for (float t : {0.7f, 1.9f, 3.1f}) {
    evaluatePose(scene, scene.animation, t, pose);
    gpuScene.setDeformation(pose);
    context.submitAndWait([&](VkCommandBuffer cmd) { gpuScene.recordInstanceUpload(cmd); });
    const Scene posed = posedScene(scene, pose);
    std::vector<Aabb> targets;
    for (uint32_t d : deforming) targets.push_back(meshBounds(posed, d));
    std::vector<gpu::GpuRay> rays = raysAt(targets, 3000, uint32_t(1000 * t));
    std::vector<gpu::GpuHit> hits = pass.trace(rays, true);
    TraceComparison c = compareWithBruteForce(posed, rays, hits, deforming);
    std::printf("t = %.1f s: %d of %zu rays differ, %d hit a deforming mesh\n", t, c.differ,
                rays.size(), c.deformingHits);
    EXPECT_EQ(c.differ, 0) << "t = " << t;
    // Not vacuous: the bent tube fills little of its box, so about a third of the rays hit it or
    // the blob.
    EXPECT_GT(c.deformingHits, int(rays.size()) / 5) << "t = " << t;
  }
  EXPECT_EQ(context.validationErrorCount(), 0u);
}

INSTANTIATE_TEST_SUITE_P(Layouts, DeformedTraversal,
                         ::testing::Values(rt::BvhLayout::Binary, rt::BvhLayout::Wide),
                         [](const ::testing::TestParamInfo<rt::BvhLayout>& info) {
                           return std::string(rt::bvhLayoutName(info.param));
                         });

// sunroom's panel and cube move (instance tracks), skinned's tube and blob deform: frozen at t,
// each equals the animation's evaluation there, and nothing is left to play but the camera.
TEST(FrozenScene, IsTheAnimationAtThatTimeAndStill) {
  for (const char* name : {"sunroom", "skinned"}) {
    const Scene scene = loadScene(name);
    const float t = 1.3f;
    const Scene frozen = sceneFrozenAt(scene, t);
    validateScene(frozen, name);
    DeformationPose pose;
    evaluatePose(scene, scene.animation, t, pose);
    std::vector<glm::mat4> transforms;
    for (const Instance& i : scene.instances) transforms.push_back(i.transform);
    evaluateTransforms(scene.animation, t, pose.skeletonWorld, transforms);
    const Scene posed = posedScene(scene, pose);
    int moved = 0;
    for (size_t i = 0; i < scene.instances.size(); ++i) {
      EXPECT_EQ(frozen.instances[i].transform, transforms[i]) << name << " instance " << i;
      moved += transforms[i] != scene.instances[i].transform;
      for (size_t g = 0; g < scene.meshes[scene.instances[i].mesh].geometries.size(); ++g) {
        const Geometry& f = frozen.meshes[frozen.instances[i].mesh].geometries[g];
        const Geometry& p = posed.meshes[posed.instances[i].mesh].geometries[g];
        const Geometry& r = scene.meshes[scene.instances[i].mesh].geometries[g];
        EXPECT_EQ(f.positions, p.positions) << name << " instance " << i;
        moved += f.positions != r.positions;
      }
    }
    EXPECT_GE(moved, 2) << name << ": the animation moved nothing at t";
    EXPECT_FALSE(frozen.deforms()) << name;
    EXPECT_TRUE(frozen.animation.transforms.empty() && frozen.animation.joints.empty() &&
                frozen.animation.morphWeights.empty())
        << name;
  }
}

// A double-sided strip 0.2 m wide and 2 m tall up +Y, skinned to joint 0 at the origin (below
// y = 0.5), joint 1 at y = 1 (above y = 1.5) and both between; an animation turns joint 1 from 0
// to 90 degrees about +Z over 1 s. Unsigned short joints, float weights, inverse bind matrices.
std::string writeSkinnedStrip(const std::string& dir) {
  test::GltfWriter w;
  std::vector<glm::vec3> positions;
  std::vector<uint16_t> joints;
  std::vector<glm::vec4> weights;
  for (int row = 0; row <= 4; ++row)
    for (float x : {-0.1f, 0.1f}) {
      float y = 0.5f * float(row);
      positions.emplace_back(x, y, 0.0f);
      float w1 = glm::clamp((y - 0.5f) / 1.0f, 0.0f, 1.0f);
      joints.insert(joints.end(), {0, 1, 0, 0});
      weights.emplace_back(1.0f - w1, w1, 0.0f, 0.0f);
    }
  std::vector<uint16_t> indices;
  for (uint16_t row = 0; row < 4; ++row) {
    uint16_t a = uint16_t(2 * row);
    indices.insert(indices.end(),
                   {a, uint16_t(a + 1), uint16_t(a + 3), a, uint16_t(a + 3), uint16_t(a + 2)});
  }
  const int jointsAccessor = w.addAccessor(w.addView(joints.data(), joints.size() * 2),
                                           test::kUnsignedShort, positions.size(), "VEC4");
  const int weightsAccessor = w.addAccessor(w.addView(weights.data(), weights.size() * 16),
                                            test::kFloat, weights.size(), "VEC4");
  const glm::mat4 inverseBind[2] = {glm::mat4(1.0f),
                                    glm::translate(glm::mat4(1.0f), {0.0f, -1.0f, 0.0f})};
  const int bindAccessor =
      w.addAccessor(w.addView(inverseBind, sizeof(inverseBind)), test::kFloat, 2, "MAT4");
  w.doc["materials"] = {{{"doubleSided", true}}};
  const int mesh = w.addMesh({{"attributes",
                               {{"POSITION", w.addPositions(positions)},
                                {"JOINTS_0", jointsAccessor},
                                {"WEIGHTS_0", weightsAccessor}}},
                              {"indices", w.addIndices16(indices)},
                              {"material", 0}});
  const int tip = w.addNode({{"name", "tip"}, {"translation", {0.0, 1.0, 0.0}}}, false);
  const int root = w.addNode({{"name", "root"}, {"children", {tip}}});
  w.addNode({{"name", "strip"}, {"mesh", mesh}, {"skin", 0}});
  w.doc["skins"] = {{{"joints", {root, tip}}, {"inverseBindMatrices", bindAccessor}}};
  // Held at 90 degrees until 2 s, where the loop wraps (so t = 1 is not the wrap point).
  const std::vector<float> times = {0.0f, 1.0f, 2.0f};
  const float h = std::sqrt(0.5f);
  const std::vector<glm::vec4> turns = {{0, 0, 0, 1}, {0, 0, h, h}, {0, 0, h, h}};  // x, y, z, w
  const int input = w.addAccessor(w.addView(times.data(), 12), test::kFloat, 3, "SCALAR");
  const int output = w.addAccessor(w.addView(turns.data(), 48), test::kFloat, 3, "VEC4");
  w.doc["accessors"][size_t(input)]["min"] = {0.0};
  w.doc["accessors"][size_t(input)]["max"] = {2.0};
  w.doc["animations"] = {
      {{"samplers", {{{"input", input}, {"output", output}}}},
       {"channels", {{{"sampler", 0}, {"target", {{"node", tip}, {"path", "rotation"}}}}}}}};
  return w.writeGltf(dir, "skinned_strip");
}

// The loader's skin (joints, weights, inverse bind matrices, the joint's animation) reaches the
// GPU as the CPU poses it: rays aimed at the strip hit what the brute force finds in the CPU
// pose at 0, 0.5 and 1 s, and at 1 s the strip's tip lies along -X (turned 90 degrees).
TEST(DeformedGltf, SkinnedFileTracesAsItsCpuPose) {
  const Scene scene = loadScene(writeSkinnedStrip(test::tempDir("deformed_gltf")));
  ASSERT_EQ(scene.skins.size(), 1u);
  vk::Context context(vk::contextOptionsFromEnvironment());
  GpuScene gpuScene(context, scene);
  TraceRaysPass pass(context, gpuScene);
  DeformationPose pose;
  for (float t : {0.0f, 0.5f, 1.0f}) {
    evaluatePose(scene, scene.animation, t, pose);
    gpuScene.setDeformation(pose);
    context.submitAndWait([&](VkCommandBuffer cmd) { gpuScene.recordInstanceUpload(cmd); });
    const Scene posed = posedScene(scene, pose);
    const Aabb box = meshBounds(posed, 0);
    std::vector<gpu::GpuRay> rays = raysAt({box}, 2000, uint32_t(7 + 100 * t));
    std::vector<gpu::GpuHit> hits = pass.trace(rays, true);
    TraceComparison c = compareWithBruteForce(posed, rays, hits, {0u});
    EXPECT_EQ(c.differ, 0) << "t = " << t;
    EXPECT_GT(c.deformingHits, 200) << "t = " << t;
    if (t == 1.0f) {
      EXPECT_NEAR(box.min.x, -1.0f, 1e-4f);  // the tip, x = -(y - 1) for y = 2
      EXPECT_NEAR(box.max.y, 1.1f, 1e-4f);   // the turned part's top edge: y = 1 + 0.1
    }
  }
  EXPECT_EQ(context.validationErrorCount(), 0u);
}

// The rasterised vbuffer culls instances by their boxes on the CPU, which for a deforming mesh
// are those of the rest pose. The strip's tip turned into a view that its rest box misses must
// still be drawn: the raster and the traced vbuffer both see it at the image centre.
TEST(DeformedGltf, RasterVBufferDrawsAPoseOutsideTheRestBox) {
  const Scene scene = loadScene(writeSkinnedStrip(test::tempDir("deformed_gltf_raster")));
  vk::Context context(vk::contextOptionsFromEnvironment());
  DeformationPose pose;
  evaluatePose(scene, scene.animation, 1.0f, pose);
  const Camera camera{.position = {-0.75f, 1.0f, 1.6f},
                      .target = {-0.75f, 1.0f, 0.0f},
                      .verticalFovDegrees = 30.0f};
  for (VBufferMode mode : {VBufferMode::Raster, VBufferMode::Trace}) {
    GpuScene gpuScene(context, scene);
    HybridSettings settings;
    settings.width = 64;
    settings.height = 48;
    settings.vbuffer = mode;
    HybridFrame frame(context, gpuScene, scene, settings);
    frame.requestDebugView("vbuffer.ids");
    frame.setDeformation(pose);
    frame.render(camera);
    std::vector<glm::uvec4> ids = texels<glm::uvec4>(frame, "vbuffer.ids");
    EXPECT_EQ(ids[24 * 64 + 32].x, 0u) << (mode == VBufferMode::Raster ? "raster" : "trace");
  }
  EXPECT_EQ(context.validationErrorCount(), 0u);
}

// ---- motion vectors -----------------------------------------------------------------------------

glm::vec2 projectToPixel(const gpu::GpuCamera& cam, glm::uvec2 res, const glm::vec3& p) {
  glm::vec4 clip = viewProjection(cam, 0.01f) * glm::vec4(p, 1.0f);
  return (glm::vec2(clip) / clip.w * 0.5f + 0.5f) * glm::vec2(res);
}

// Barycentric weights (of v1, v2) of the point where the ray from `origin` along `dir` crosses
// the plane of triangle v0 v1 v2.
glm::vec2 rayBarycentrics(const glm::vec3& origin, const glm::vec3& dir, const glm::vec3& v0,
                          const glm::vec3& v1, const glm::vec3& v2) {
  glm::vec3 e1 = v1 - v0, e2 = v2 - v0, p = glm::cross(dir, e2);
  float inv = 1.0f / glm::dot(e1, p);
  glm::vec3 s = origin - v0, q = glm::cross(s, e1);
  return {glm::dot(s, p) * inv, glm::dot(dir, q) * inv};
}

struct PosedTriangle {
  glm::vec3 v[3];
};

PosedTriangle triangleOf(const Scene& posed, uint32_t instance, uint32_t localGeometry,
                         uint32_t primitive) {
  const Geometry& g = posed.meshes[posed.instances[instance].mesh].geometries[localGeometry];
  PosedTriangle t;
  for (int k = 0; k < 3; ++k) t.v[k] = g.positions[g.indices[3 * primitive + uint32_t(k)]];
  return t;
}

// The tube bends between two frames while the camera stands still: each tube pixel's velocity
// is its surface point's motion on screen (found on the CPU: the pixel ray's barycentrics on the
// triangle of this pose, carried to the last pose's triangle). The next frame without a new
// pose has none.
TEST(DeformedMotion, VelocityIsTheSkinnedSurfacesScreenMotion) {
  vk::Context context(vk::contextOptionsFromEnvironment({}));
  const Scene scene = loadScene("skinned");
  GpuScene gpuScene(context, scene);
  HybridSettings settings;
  settings.width = 96;
  settings.height = 64;
  HybridFrame frame(context, gpuScene, scene, settings);
  frame.requestDebugView("vbuffer.ids");
  frame.requestDebugView("gbuffer.velocity");
  const uint32_t tube = instanceNamed(scene, "tube");
  DeformationPose before, after;
  evaluatePose(scene, scene.animation, 0.4f, before);
  evaluatePose(scene, scene.animation, 0.6f, after);
  frame.setDeformation(before);
  frame.render(*scene.camera);
  frame.setDeformation(after);
  frame.render(*scene.camera);

  const Scene posedBefore = posedScene(scene, before), posedAfter = posedScene(scene, after);
  const uint32_t geometryBase = gpuScene.bvh().geometryBase[scene.instances[tube].mesh];
  std::vector<glm::uvec4> ids = texels<glm::uvec4>(frame, "vbuffer.ids");
  std::vector<glm::u16vec2> velocity = texels<glm::u16vec2>(frame, "gbuffer.velocity");
  const glm::uvec2 res(settings.width, settings.height);
  const gpu::GpuCamera cam = makeGpuCamera(*scene.camera, res.x, res.y, gpuScene.bounds());
  uint32_t tubePixels = 0;
  float maxError = 0.0f, meanSpeed = 0.0f;
  for (uint32_t y = 0; y < res.y; ++y)
    for (uint32_t x = 0; x < res.x; ++x) {
      size_t i = size_t(y) * res.x + x;
      if (ids[i].x != tube) continue;
      glm::vec2 centre(x + 0.5f, y + 0.5f);
      glm::vec3 dir = gpu::cameraRayDirection(cam, centre, glm::vec2(res));
      uint32_t localGeometry = ids[i].y - geometryBase;
      PosedTriangle now = triangleOf(posedAfter, tube, localGeometry, ids[i].z);
      PosedTriangle then = triangleOf(posedBefore, tube, localGeometry, ids[i].z);
      glm::vec2 b = rayBarycentrics(cam.position, dir, now.v[0], now.v[1], now.v[2]);
      glm::vec3 was = then.v[0] * (1.0f - b.x - b.y) + then.v[1] * b.x + then.v[2] * b.y;
      glm::vec2 expected = centre - projectToPixel(cam, res, was);
      glm::vec2 v(glm::unpackHalf1x16(velocity[i].x), glm::unpackHalf1x16(velocity[i].y));
      maxError = std::max(maxError, glm::length(v - expected));
      meanSpeed += glm::length(expected);
      ++tubePixels;
    }
  ASSERT_GT(tubePixels, 100u);
  meanSpeed /= float(tubePixels);
  std::printf("skinned tube: %u pixels, mean motion %.2f px, max velocity error %.4f px\n",
              tubePixels, meanSpeed, maxError);
  EXPECT_GT(meanSpeed, 0.5f);
  EXPECT_LT(maxError, 0.02f);  // RG16F and float rounding (MovingObjectVelocity's bound)

  frame.render(*scene.camera);  // the same pose again
  float maxSpeed = 0.0f;
  for (glm::u16vec2 v : texels<glm::u16vec2>(frame, "gbuffer.velocity"))
    maxSpeed = std::max(maxSpeed, std::hypot(glm::unpackHalf1x16(v.x), glm::unpackHalf1x16(v.y)));
  EXPECT_LT(maxSpeed, 1e-3f) << "a mesh that stopped deforming keeps its motion vectors";
  EXPECT_EQ(context.validationErrorCount(), 0u);
}

}  // namespace
}  // namespace bounce
