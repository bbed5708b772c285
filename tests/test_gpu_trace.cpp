// The GPU traversal (shaders/rt/trace.glsl) against the CPU brute-force reference
// (src/rt/cpu_trace.h), which loops over every triangle of every instance with the same
// watertight triangle test: on 10,000 random rays per scene, the same closest primitive
// (unless two hits tie within 1e-5 relative t), t within 1e-4 relative, identical visibility
// answers, alpha-tested leaves included; with both BLAS layouts (binary and wide), the wide one
// also against its CPU mirror. Validation layers must stay silent.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <thread>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "harness.h"
#include "passes/trace_rays.h"
#include "rt/cpu_trace.h"
#include "rt/gpu_scene.h"
#include "scene/load.h"
#include "scene/scene_options.h"
#include "vk/context.h"

namespace bounce {
namespace {

constexpr int kRayCount = 10000;

// A mix of camera rays (coherent, what a frame traces first), rays from random points in and
// around the scene in random directions (incoherent, like bounces), and finite segments (like
// shadow rays), so that closest-hit and visibility queries both meet hits and misses.
std::vector<gpu::GpuRay> makeRays(const Scene& scene, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  Aabb b = scene.bounds();
  glm::vec3 pad = 0.05f * b.extent();
  glm::vec3 lo = b.min - pad, hi = b.max + pad;
  float diagonal = glm::length(b.extent());
  Camera cam = effectiveCamera(scene);
  glm::vec3 forward = glm::normalize(cam.target - cam.position);
  glm::vec3 right = glm::normalize(glm::cross(forward, cam.up));
  glm::vec3 up = glm::cross(right, forward);
  float tanHalf = std::tan(glm::radians(cam.verticalFovDegrees) * 0.5f);

  auto randomDirection = [&] {
    float z = 2.0f * u(rng) - 1.0f, phi = 6.2831853f * u(rng);
    float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
    return glm::vec3(r * std::cos(phi), r * std::sin(phi), z);
  };
  std::vector<gpu::GpuRay> rays(kRayCount);
  for (int i = 0; i < kRayCount; ++i) {
    gpu::GpuRay& r = rays[i];
    r.tMin = 0.0f;
    r.tMax = 3.0e38f;
    if (i % 5 < 2) {
      r.origin = cam.position;
      r.direction = glm::normalize(forward + (2.0f * u(rng) - 1.0f) * tanHalf * right +
                                   (2.0f * u(rng) - 1.0f) * tanHalf * up);
    } else {
      r.origin = lo + glm::vec3(u(rng), u(rng), u(rng)) * (hi - lo);
      r.direction = randomDirection() * (0.5f + u(rng));  // unnormalised on purpose
      if (i % 5 == 4) r.tMax = u(rng) * diagonal * 0.5f;
    }
  }
  return rays;
}

struct Mismatches {
  int hitMiss = 0, primitive = 0, distance = 0, visibility = 0, facing = 0, hits = 0;
};

// With the wide layout the GPU answers are also checked against the CPU mirror of the wide
// traversal (rt::CpuTracer on the same arrays): the same hit or miss, primitive, t and facing,
// and the same visibility answer on every ray.
void compareWithMirror(const GpuScene& gpuScene, const std::vector<gpu::GpuRay>& rays,
                       const std::vector<gpu::GpuHit>& gpuHits, const rt::AlphaTest& alpha) {
  rt::CpuTracer mirror(gpuScene.bvh());
  int differ = 0, visibility = 0;
  for (size_t i = 0; i < rays.size(); ++i) {
    rt::Ray ray{rays[i].origin, rays[i].direction, rays[i].tMin};
    const rt::TraceHit c = mirror.closestHit(ray, rays[i].tMax, alpha);
    const gpu::GpuHit& g = gpuHits[i];
    const bool same =
        (g.instance != gpu::HIT_NONE) == c.hit &&
        (!c.hit ||
         (g.instance == c.instance && g.geometry == c.geometry && g.primitive == c.primitive &&
          (g.frontFacing != 0) == c.frontFacing && std::abs(g.t - c.t) <= 1e-6f * c.t));
    if (!same && ++differ <= 5)
      ADD_FAILURE() << "ray " << i << ": gpu instance " << g.instance << " primitive "
                    << g.primitive << " t " << g.t << ", cpu mirror " << c.instance << " "
                    << c.primitive << " " << c.t;
    visibility += (g.occluded != 0) != mirror.anyHit(ray, rays[i].tMax, alpha);
  }
  EXPECT_EQ(differ, 0);
  EXPECT_EQ(visibility, 0);
}

void compareScene(const std::string& name, rt::BvhLayout layout = rt::BvhLayout::Binary) {
  SCOPED_TRACE(name);
  Scene scene = loadScene(name);
  vk::Context context(vk::contextOptionsFromEnvironment());
  GpuScene gpuScene(context, scene, GpuSceneOptions{.bvhLayout = layout});
  TraceRaysPass pass(context, gpuScene);
  std::vector<gpu::GpuRay> rays = makeRays(scene, 1234);
  std::vector<gpu::GpuHit> gpuHits = pass.trace(rays, true);

  rt::AlphaTest alpha = [&](uint32_t, uint32_t geometry, uint32_t primitive, float b1, float b2) {
    return gpuScene.alphaAccepts(geometry, primitive, b1, b2);
  };
  // The brute force is slow on big scenes: split the rays over the cores.
  rt::BruteForceTracer bruteForce(scene);
  std::vector<rt::TraceHit> cpuHits(rays.size());
  std::vector<char> cpuOccluded(rays.size());
  unsigned threads = std::max(1u, std::thread::hardware_concurrency());
  std::vector<std::thread> pool;
  for (unsigned t = 0; t < threads; ++t)
    pool.emplace_back([&, t] {
      for (size_t i = t; i < rays.size(); i += threads) {
        rt::Ray ray{rays[i].origin, rays[i].direction, rays[i].tMin};
        cpuHits[i] = bruteForce.closestHit(ray, rays[i].tMax, alpha);
        cpuOccluded[i] = bruteForce.anyHit(ray, rays[i].tMax, alpha);
      }
    });
  for (std::thread& t : pool) t.join();
  if (layout == rt::BvhLayout::Wide) compareWithMirror(gpuScene, rays, gpuHits, alpha);

  Mismatches m;
  for (size_t i = 0; i < rays.size(); ++i) {
    const gpu::GpuHit& g = gpuHits[i];
    const rt::TraceHit& c = cpuHits[i];
    bool gpuHit = g.instance != gpu::HIT_NONE;
    m.visibility += (g.occluded != 0) != (cpuOccluded[i] != 0);
    if (gpuHit != c.hit) {
      ++m.hitMiss;
      continue;
    }
    if (!gpuHit) continue;
    ++m.hits;
    float relative = std::abs(g.t - c.t) / std::max(c.t, 1e-30f);
    bool samePrimitive =
        g.instance == c.instance && g.geometry == c.geometry && g.primitive == c.primitive;
    if (!samePrimitive && relative > 1e-5f) ++m.primitive;
    if (samePrimitive && (g.frontFacing != 0) != c.frontFacing) ++m.facing;
    if (relative > 1e-4f && ++m.distance <= 5)
      ADD_FAILURE() << "ray " << i << ": t gpu " << g.t << " cpu " << c.t << " instance "
                    << c.instance << " primitive " << c.primitive << " |dir| "
                    << glm::length(rays[i].direction);
  }
  EXPECT_EQ(m.hitMiss, 0);
  EXPECT_EQ(m.primitive, 0);
  EXPECT_EQ(m.distance, 0);
  EXPECT_EQ(m.visibility, 0);
  EXPECT_EQ(m.facing, 0);
  // The comparison must cover real hits, not only misses: at least a thousand of them.
  EXPECT_GE(m.hits, 1000);
  EXPECT_EQ(context.validationErrorCount(), 0u);
  std::printf("%s (%s BVH): %d rays, %d hits, all agree\n", name.c_str(), rt::bvhLayoutName(layout),
              kRayCount, m.hits);
}

class GpuTraceBuiltin : public ::testing::TestWithParam<std::string> {};
TEST_P(GpuTraceBuiltin, MatchesBruteForce) {
  compareScene(GetParam());
}
INSTANTIATE_TEST_SUITE_P(Scenes, GpuTraceBuiltin,
                         ::testing::Values("cornell", "sunroom", "foliage", "manylights", "furnace",
                                           "city"));

// The wide compressed BLAS (--bvh wide) on the same rays: against brute force and against
// its CPU mirror. cornell and sunroom: rooms; foliage: instances and alpha-tested leaves.
class GpuTraceWide : public ::testing::TestWithParam<std::string> {};
TEST_P(GpuTraceWide, MatchesBruteForceAndCpuMirror) {
  compareScene(GetParam(), rt::BvhLayout::Wide);
}
INSTANTIATE_TEST_SUITE_P(Scenes, GpuTraceWide, ::testing::Values("cornell", "sunroom", "foliage"));

TEST(GpuTraceShared, GlassVaseFlowersWithAlphaTestedLeaves) {
  compareScene(test::sharedDir() + "/scenes/glass_vase_flowers/glTF/GlassVaseFlowers.gltf");
}

TEST(GpuTraceShared, SheenChair) {
  compareScene(test::sharedDir() + "/scenes/sheen_chair/glTF/SheenChair.gltf");
}

// Traces random rays through `gpuScene` on the GPU (of `scene`, placed as the GPU scene is now)
// and expects the hits of the CPU mirror and of the brute force, with at least a tenth hitting.
void expectTracesAsMirrorAndBruteForce(vk::Context& context, const Scene& scene,
                                       const GpuScene& gpuScene, uint32_t seed) {
  TraceRaysPass pass(context, gpuScene);
  std::vector<gpu::GpuRay> rays = makeRays(scene, seed);
  std::vector<gpu::GpuHit> gpuHits = pass.trace(rays, true);
  rt::AlphaTest alpha = [&](uint32_t, uint32_t geometry, uint32_t primitive, float b1, float b2) {
    return gpuScene.alphaAccepts(geometry, primitive, b1, b2);
  };
  compareWithMirror(gpuScene, rays, gpuHits, alpha);
  rt::BruteForceTracer bruteForce(scene);
  int differ = 0, hits = 0;
  for (size_t i = 0; i < rays.size(); ++i) {
    rt::Ray ray{rays[i].origin, rays[i].direction, rays[i].tMin};
    const rt::TraceHit b = bruteForce.closestHit(ray, rays[i].tMax, alpha);
    const bool gpuHit = gpuHits[i].instance != gpu::HIT_NONE;
    hits += gpuHit;
    differ += gpuHit != b.hit || (b.hit && std::abs(gpuHits[i].t - b.t) > 1e-4f * b.t);
  }
  EXPECT_EQ(differ, 0) << "of " << rays.size() << " rays";
  EXPECT_GT(hits, int(rays.size()) / 10);
}

// Moving instances with the TLAS refitted on the GPU (TlasUpdate::GpuRefit, scene-refit-tlas):
// every foliage instance moved, turned and some hidden, then the refitted boxes equal the CPU
// refit's (rt::refitTlas, the same arithmetic) and the GPU's answers on the moved scene equal
// the CPU traversal's of the refitted arrays and the brute force's.
TEST(GpuTraceMoving, RefittedTlasMatchesTheCpuRefitAndBruteForce) {
  Scene scene = loadScene("foliage");
  vk::Context context(vk::contextOptionsFromEnvironment());
  GpuScene gpuScene(context, scene);
  ASSERT_EQ(gpuScene.tlasUpdate(), TlasUpdate::GpuRefit);
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::vector<glm::mat4> moved;
  for (size_t i = 0; i < scene.instances.size(); ++i) {
    glm::mat4 m = glm::translate(glm::mat4(1.0f), 3.0f * glm::vec3(u(rng), 0.2f * u(rng), u(rng)));
    m = glm::rotate(m, u(rng), glm::vec3(0, 1, 0)) * scene.instances[i].transform;
    if (i % 11 == 5) m = glm::scale(m, glm::vec3(0.0f));  // hidden
    moved.push_back(m);
    scene.instances[i].transform = m;
  }
  gpuScene.setInstanceTransforms(moved);
  context.submitAndWait([&](VkCommandBuffer cmd) { gpuScene.recordInstanceUpload(cmd); });

  gpuScene.refitCpuTlas();
  const std::vector<gpu::GpuBvhNode>& cpu = gpuScene.bvh().tlasNodes;
  std::vector<gpu::GpuBvhNode> gpu(cpu.size());
  vk::downloadBuffer(context, gpuScene.tlasBuffer(), std::as_writable_bytes(std::span(gpu)));
  int boxesDiffer = 0;
  for (size_t n = 0; n < cpu.size(); ++n)
    boxesDiffer += cpu[n].leftMin != gpu[n].leftMin || cpu[n].leftMax != gpu[n].leftMax ||
                   cpu[n].rightMin != gpu[n].rightMin || cpu[n].rightMax != gpu[n].rightMax;
  EXPECT_EQ(boxesDiffer, 0) << "of " << cpu.size() << " TLAS nodes";

  expectTracesAsMirrorAndBruteForce(context, scene, gpuScene, 4321);
  EXPECT_EQ(context.validationErrorCount(), 0u);
}

// Moves every foliage instance but the ground (instance 0) a fraction t of the way from its
// placement to `partner`'s, keeping its own rotation and scale.
std::vector<glm::mat4> towardPartners(const Scene& scene, const std::vector<size_t>& partner,
                                      float t) {
  std::vector<glm::mat4> moved;
  for (size_t i = 0; i < scene.instances.size(); ++i) {
    const glm::mat4& own = scene.instances[i].transform;
    const glm::vec3 target = glm::vec3(scene.instances[partner[i]].transform[3]);
    glm::mat4 m = own;
    m[3] = glm::vec4(glm::mix(glm::vec3(own[3]), target, t), 1.0f);
    moved.push_back(m);
  }
  return moved;
}

// The rebuild policy on the GPU (GpuSceneOptions::tlasRebuildRatio, default): foliage's trees
// and bushes swap places with random partners over four frames; the refitted tree degrades, is
// rebuilt and uploaded, and then the GPU's TLAS equals the CPU copy bit for bit and the GPU's
// hits equal the CPU traversal's and the brute force's. Jitter smaller than a bush rebuilds
// nothing.
TEST(GpuTraceMoving, DegradedTlasIsRebuiltAndTracesAsTheBruteForce) {
  const Scene loaded = loadScene("foliage");
  vk::Context context(vk::contextOptionsFromEnvironment());
  std::mt19937 rng(17);
  {
    GpuScene jittered(context, loaded);
    std::uniform_real_distribution<float> u(-0.2f, 0.2f);
    for (int frame = 0; frame < 4; ++frame) {
      std::vector<glm::mat4> moved;
      for (const Instance& instance : loaded.instances)
        moved.push_back(glm::translate(glm::mat4(1.0f), glm::vec3(u(rng), 0.0f, u(rng))) *
                        instance.transform);
      jittered.setInstanceTransforms(moved);
      context.submitAndWait([&](VkCommandBuffer cmd) { jittered.recordInstanceUpload(cmd); });
      std::printf("jitter frame %d: TLAS cost ratio %.2f\n", frame, jittered.tlasCostRatio());
    }
    EXPECT_EQ(jittered.tlasRebuildCount(), 0u) << "last cost ratio " << jittered.tlasCostRatio();
  }

  Scene scene = loaded;
  GpuScene gpuScene(context, scene);
  std::vector<size_t> partner(scene.instances.size());
  for (size_t i = 0; i < partner.size(); ++i) partner[i] = i;
  std::shuffle(partner.begin() + 1, partner.end(), rng);
  std::vector<glm::mat4> moved;
  for (int frame = 1; frame <= 4; ++frame) {
    moved = towardPartners(loaded, partner, float(frame) / 4.0f);
    gpuScene.setInstanceTransforms(moved);
    context.submitAndWait([&](VkCommandBuffer cmd) { gpuScene.recordInstanceUpload(cmd); });
    std::printf("swap frame %d: TLAS cost ratio %.2f, %u rebuilds\n", frame,
                gpuScene.tlasCostRatio(), gpuScene.tlasRebuildCount());
  }
  EXPECT_GT(gpuScene.tlasRebuildCount(), 0u);
  for (size_t i = 0; i < scene.instances.size(); ++i) scene.instances[i].transform = moved[i];

  const std::vector<gpu::GpuBvhNode>& cpu = gpuScene.bvh().tlasNodes;
  std::vector<gpu::GpuBvhNode> gpu(cpu.size());
  vk::downloadBuffer(context, gpuScene.tlasBuffer(), std::as_writable_bytes(std::span(gpu)));
  EXPECT_EQ(0, std::memcmp(cpu.data(), gpu.data(), cpu.size() * sizeof(gpu::GpuBvhNode)))
      << "the GPU's TLAS differs from the CPU's rebuilt and refitted copy";

  expectTracesAsMirrorAndBruteForce(context, scene, gpuScene, 777);
  EXPECT_EQ(context.validationErrorCount(), 0u);
}

// The alpha test must matter: on the foliage scene some rays pass through the cut-out parts of
// leaf cards that would stop them without the test.
TEST(GpuTraceAlpha, CutoutsLetRaysThrough) {
  Scene scene = loadScene("foliage");
  vk::Context context(vk::contextOptionsFromEnvironment());
  GpuScene gpuScene(context, scene);
  TraceRaysPass pass(context, gpuScene);
  std::vector<gpu::GpuRay> rays = makeRays(scene, 99);
  std::vector<gpu::GpuHit> withTest = pass.trace(rays, true);
  std::vector<gpu::GpuHit> without = pass.trace(rays, false);
  int passedThrough = 0;
  for (size_t i = 0; i < rays.size(); ++i)
    passedThrough += without[i].instance != gpu::HIT_NONE &&
                     (withTest[i].instance == gpu::HIT_NONE || withTest[i].t > without[i].t);
  EXPECT_GT(passedThrough, 50);
  EXPECT_EQ(context.validationErrorCount(), 0u);
}

}  // namespace
}  // namespace bounce
