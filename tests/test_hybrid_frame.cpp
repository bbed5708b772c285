// The hybrid frame without GI (src/render/hybrid_frame.h) on lavapipe at small resolutions:
//   - the GBuffer (raster vbuffer + compute gbuffer) sees what primary rays see: same triangle,
//     view depth and geometric normal on at least 99.5% of pixels of every built-in scene;
//   - 20 frames of every built-in scene leave the validation layers (synchronization included)
//     silent, allocate nothing after the first frames and composite only finite radiance;
//   - a white Lambert floor in the sun has radiance E cos(theta) / pi in the composite.
#include <cmath>
#include <cstdio>
#include <cstring>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <glm/gtc/packing.hpp>
#include "core/error.h"
#include "frame/presets.h"
#include "harness.h"

#include "frame/hybrid_frame.h"
#include "passes/primary_view.h"
#include "passes/trace_rays.h"
#include "rt/gpu_scene.h"
#include "scene/load.h"
#include "scene/scene_options.h"
#include "shared/camera.h"
#include "shared/restir_gi_io.h"
#include "vk/context.h"

namespace bounce {
namespace {

using test::decodeOctahedral;

template <typename T>
std::vector<T> texels(const graph::DebugView& view) {
  std::vector<T> out(view.bytes.size() / sizeof(T));
  std::memcpy(out.data(), view.bytes.data(), out.size() * sizeof(T));
  return out;
}

glm::vec3 rowTransform(const glm::vec4 (&rows)[3], const glm::vec3& p) {
  return {glm::dot(glm::vec3(rows[0]), p) + rows[0].w, glm::dot(glm::vec3(rows[1]), p) + rows[1].w,
          glm::dot(glm::vec3(rows[2]), p) + rows[2].w};
}

// The world-space normal of the hit triangle, facing the ray's origin.
glm::vec3 geometricNormal(const rt::SceneBvh& bvh, const gpu::GpuHit& hit, const glm::vec3& dir) {
  const gpu::GpuGeometry& g = bvh.geometries[hit.geometry];
  const gpu::GpuInstance& instance = bvh.instances[hit.instance];
  glm::vec3 p[3];
  for (int k = 0; k < 3; ++k)
    p[k] = rowTransform(
        instance.objectToWorld,
        bvh.positions[g.vertexOffset + bvh.indices[g.firstIndex + 3 * hit.primitive + k]]);
  glm::vec3 n = glm::normalize(glm::cross(p[1] - p[0], p[2] - p[0]));
  return glm::dot(n, dir) > 0.0f ? -n : n;
}

struct GBufferAgreement {
  uint32_t pixels = 0;
  uint32_t matching = 0;      // hit/miss, view depth and geometric normal agree
  uint32_t sameTriangle = 0;  // ... and the ids too
};

GBufferAgreement compareWithRayCast(const std::string& sceneName, uint32_t width, uint32_t height,
                                    VBufferMode vbuffer = VBufferMode::Raster) {
  vk::Context context(vk::contextOptionsFromEnvironment({}));
  Scene scene = loadScene(sceneName);
  GpuScene gpuScene(context, scene);
  HybridSettings settings;
  settings.width = width;
  settings.height = height;
  settings.vbuffer = vbuffer;
  HybridFrame frame(context, gpuScene, scene, settings);
  frame.requestDebugView("vbuffer.ids");
  frame.requestDebugView("gbuffer.depth");
  frame.requestDebugView("gbuffer.normals");
  Camera camera = effectiveCamera(scene);
  frame.render(camera);
  std::vector<glm::uvec4> ids = texels<glm::uvec4>(frame.graph().readDebugView("vbuffer.ids"));
  std::vector<float> depth = texels<float>(frame.graph().readDebugView("gbuffer.depth"));
  std::vector<glm::u16vec4> normals =
      texels<glm::u16vec4>(frame.graph().readDebugView("gbuffer.normals"));

  gpu::GpuCamera cam = makeGpuCamera(camera, width, height, gpuScene.bounds());
  std::vector<gpu::GpuRay> rays;
  for (uint32_t y = 0; y < height; ++y)
    for (uint32_t x = 0; x < width; ++x) {
      glm::vec3 dir =
          gpu::cameraRayDirection(cam, glm::vec2(x + 0.5f, y + 0.5f), glm::vec2(width, height));
      rays.push_back({cam.position, 0.0f, dir, 3.0e38f});
    }
  std::vector<gpu::GpuHit> hits = TraceRaysPass(context, gpuScene).trace(rays, true);

  GBufferAgreement result;
  for (size_t i = 0; i < rays.size(); ++i) {
    ++result.pixels;
    const gpu::GpuHit& hit = hits[i];
    bool rayHit = hit.instance != gpu::HIT_NONE;
    bool rasterHit = ids[i].x != gpu::VBUFFER_NO_HIT;
    if (rayHit != rasterHit) continue;
    if (!rayHit) {
      ++result.matching;
      ++result.sameTriangle;
      continue;
    }
    float rayDepth = hit.t * glm::dot(rays[i].direction, cam.forward);
    if (std::abs(depth[i] - rayDepth) > 1e-3f * rayDepth) continue;
    glm::vec3 n =
        decodeOctahedral({glm::unpackHalf1x16(normals[i].z), glm::unpackHalf1x16(normals[i].w)});
    if (glm::dot(n, geometricNormal(gpuScene.bvh(), hit, rays[i].direction)) < 0.999f) continue;
    ++result.matching;
    // A pixel centre on the edge shared by two triangles of one surface may go to either: the
    // raster's tie-break rule differs from the watertight ray test's. Same depth and normal
    // make that a match above; here only identical ids count.
    if (ids[i].x == hit.instance && ids[i].y == hit.geometry && ids[i].z == hit.primitive)
      ++result.sameTriangle;
  }
  EXPECT_EQ(context.validationErrorCount(), 0u);
  return result;
}

TEST(HybridFrame, GBufferMatchesRayCastPrimaryHitsInEveryBuiltinScene) {
  for (const std::string& name : builtinSceneNames()) {
    SCOPED_TRACE(name);
    GBufferAgreement a = compareWithRayCast(name, 96, 54);
    double fraction = double(a.matching) / double(a.pixels);
    EXPECT_GE(fraction, 0.995) << a.matching << " of " << a.pixels << " pixels agree";
    double sameTriangle = double(a.sameTriangle) / double(a.pixels);
    EXPECT_GE(sameTriangle, 0.99) << a.sameTriangle << " of " << a.pixels
                                  << " pixels name the same triangle";
    std::printf("%-12s %u of %u pixels agree (%.2f%%), %.2f%% on the same triangle\n", name.c_str(),
                a.matching, a.pixels, 100.0 * fraction, 100.0 * sameTriangle);
  }
}

// The ray-cast vbuffer runs the same traversal as the reference rays through the same pixel
// centres, so it must name the same triangle everywhere (bar the odd pixel where the two shader
// builds round a ray direction differently).
TEST(HybridFrame, RayCastVBufferNamesTheRayCastTriangles) {
  for (const char* name : {"sunroom", "foliage", "city"}) {
    SCOPED_TRACE(name);
    GBufferAgreement a = compareWithRayCast(name, 96, 54, VBufferMode::Trace);
    EXPECT_GE(double(a.sameTriangle) / double(a.pixels), 0.999)
        << a.sameTriangle << " of " << a.pixels << " pixels name the same triangle";
  }
}

// One check of the settings' ranges for the library and the command line: the presets and the
// unbiased configuration pass; each out-of-range field is refused by name, never clamped.
TEST(FrameSettings, ValidateRefusesOutOfRangeFieldsByName) {
  for (Preset preset : {Preset::Mobile, Preset::Desktop}) {
    HybridSettings s = presetSettings(preset);
    s.gi = GiMode::Evolve;
    EXPECT_NO_THROW(validate(s));
    s.restirGi = RestirGiSettings::unbiased();
    EXPECT_NO_THROW(validate(s));
  }
  auto refused = [](const char* expected, auto change) {
    HybridSettings s = presetSettings(Preset::Desktop);
    s.gi = GiMode::Evolve;
    change(s);
    try {
      validate(s);
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
      return;
    }
    ADD_FAILURE() << "accepted: " << expected;
  };
  refused("resolution 0x1080", [](HybridSettings& s) { s.width = 0; });
  refused("shadow divisor 0", [](HybridSettings& s) { s.shadows.divisor = 0; });
  refused("reflection motion parallax tolerance 2",
          [](HybridSettings& s) { s.reflections.motionParallaxTolerance = 2.0f; });
  refused("reflection denoise motion parallax tolerance -1",
          [](HybridSettings& s) { s.reflectionDenoise.motionParallaxTolerance = -1.0f; });
  refused("exposure 100 stops", [](HybridSettings& s) { s.exposureStops = 100.0f; });
  refused("auto exposure percentiles 0.9 .. 0.5", [](HybridSettings& s) {
    s.exposure.lowPercentile = 0.9f;
    s.exposure.highPercentile = 0.5f;
  });
  refused("auto exposure key 0", [](HybridSettings& s) { s.exposure.key = 0.0f; });
  refused("auto exposure luminance range 2^-20",
          [](HybridSettings& s) { s.exposure.minLog2Luminance = -20.0f; });
  refused("auto exposure darkening time -1",
          [](HybridSettings& s) { s.exposure.darkeningSeconds = -1.0f; });
  refused("resolution divisor 17", [](HybridSettings& s) { s.restirGi.divisor = 17; });
  refused("6 temporal history samples",
          [](HybridSettings& s) { s.restirGi.temporalHistorySamples = 6; });
  refused("firefly ratio 0.5", [](HybridSettings& s) { s.restirGi.fireflyRatio = 0.5f; });
  refused("3 rays per cell", [](HybridSettings& s) { s.cache.raysPerCell = 3; });
}

// A resize between frames: every size that follows the resolution (shadow and GI images) is
// made anew, the frame renders at the new size without validation errors or NaN, and the GI
// still lights the room.
TEST(HybridFrame, ResizeBetweenFramesRendersAtTheNewSize) {
  vk::Context context(
      vk::contextOptionsFromEnvironment({.validation = true, .synchronizationValidation = true}));
  ASSERT_TRUE(context.validationEnabled()) << "the Khronos validation layer is missing";
  Scene scene = loadScene("cornell");
  GpuScene gpuScene(context, scene);
  HybridSettings settings = presetSettings(Preset::Desktop);
  settings.gi = GiMode::Evolve;
  settings.width = 40;
  settings.height = 24;
  HybridFrame frame(context, gpuScene, scene, settings);
  frame.requestDebugView("gi.diffuse");
  frame.requestDebugView("composite");
  Camera camera = effectiveCamera(scene);
  for (int i = 0; i < 3; ++i) frame.render(camera);
  for (auto [width, height] : {std::pair{56u, 36u}, std::pair{24u, 16u}}) {
    frame.resize(width, height);
    for (int i = 0; i < 3; ++i) frame.render(camera);
    for (const char* view : {"gi.diffuse", "composite"}) {
      SCOPED_TRACE(view);
      ImageRGBA32F image = frame.debugViewImage(view);
      ASSERT_EQ(image.width, int(width));
      ASSERT_EQ(image.height, int(height));
      double sum = 0.0;
      for (float v : image.pixels) {
        ASSERT_TRUE(std::isfinite(v));
        sum += v;
      }
      EXPECT_GT(sum, 0.0) << "black after resizing to " << width << "x" << height;
    }
  }
  EXPECT_THROW(frame.resize(0, 16), Error);
  EXPECT_EQ(context.validationErrorCount(), 0u);
}

// A 40 m white floor (y = 0) under a sun at 50 degrees from the zenith, no sky, no other light.
Scene sunlitFloor(float irradiance, float zenithDegrees) {
  Scene scene;
  scene.name = "sunlit-floor";
  Geometry g;
  const float h = 20.0f;
  g.positions = {{-h, 0, -h}, {-h, 0, h}, {h, 0, h}, {h, 0, -h}};
  g.normals.assign(4, {0, 1, 0});
  g.uvs = {{0, 0}, {0, 1}, {1, 1}, {1, 0}};
  g.indices = {0, 1, 2, 0, 2, 3};
  scene.meshes.push_back({"floor", {g}});
  scene.instances.push_back({0, glm::mat4(1.0f), "floor"});
  Material white;
  white.baseColor = glm::vec4(1.0f);
  white.metallic = 0.0f;
  white.roughness = 1.0f;
  scene.materials.push_back(white);
  float zenith = glm::radians(zenithDegrees);
  scene.sun.direction = -glm::vec3(std::sin(zenith), std::cos(zenith), 0.0f);
  scene.sun.irradiance = irradiance;
  scene.sky.radiance = glm::vec3(0.0f);
  scene.camera = Camera{{0.0f, 3.0f, 3.0f}, {0.0f, 0.0f, 0.0f}, {0, 1, 0}, 40.0f};
  validateScene(scene, "sunlit floor");
  return scene;
}

TEST(HybridFrame, SunlitLambertFloorHasRadianceECosThetaOverPi) {
  const float irradiance = 3.0f, zenithDegrees = 50.0f;
  vk::Context context(vk::contextOptionsFromEnvironment({}));
  Scene scene = sunlitFloor(irradiance, zenithDegrees);
  GpuScene gpuScene(context, scene);
  HybridSettings settings;
  settings.width = 32;
  settings.height = 24;
  settings.lambert = true;
  HybridFrame frame(context, gpuScene, scene, settings);
  frame.requestDebugView("composite");
  for (int i = 0; i < 4; ++i) frame.render(*scene.camera);
  ImageRGBA32F hdr = frame.debugViewImage("composite");
  const float expected = irradiance * std::cos(glm::radians(zenithDegrees)) / float(M_PI);
  for (int y = 0; y < hdr.height; ++y)
    for (int x = 0; x < hdr.width; ++x)
      for (int c = 0; c < 3; ++c)
        ASSERT_NEAR(hdr.at(x, y)[c], expected, 0.01f * expected) << "pixel " << x << "," << y;
}

// Rays counted on the GPU (HybridFrame::countRays, what `bounce bench` reports per pass)
// against what each pass must trace on a view that is all sunlit floor: the ray-cast vbuffer
// one ray per pixel, shadows-trace one per shadow pixel (every one sees the sun in front of the
// floor), the passes that trace nothing none; counting off gives no count.
TEST(HybridFrame, CountedRaysMatchWhatEachPassTraces) {
  vk::Context context(vk::contextOptionsFromEnvironment({}));
  Scene scene = sunlitFloor(3.0f, 50.0f);
  GpuScene gpuScene(context, scene);
  HybridSettings settings = presetSettings(Preset::Desktop);
  settings.gi = GiMode::Evolve;
  settings.vbuffer = VBufferMode::Trace;
  settings.width = 32;
  settings.height = 24;
  HybridFrame frame(context, gpuScene, scene, settings);
  frame.countRays(true);
  std::vector<vk::PassTiming> timings;
  for (int i = 0; i < 3; ++i) timings = frame.render(*scene.camera);
  auto raysOf = [&](const std::string& pass) -> std::optional<uint64_t> {
    for (const vk::PassTiming& t : timings)
      if (t.name == pass) return t.rays;
    ADD_FAILURE() << "no pass " << pass;
    return std::nullopt;
  };
  const VkExtent2D shadow = settings.shadows.resolution(settings.resolution());
  EXPECT_EQ(raysOf("vbuffer"), std::optional<uint64_t>(32 * 24));
  EXPECT_EQ(raysOf("shadows-trace"), std::optional<uint64_t>(shadow.width * shadow.height));
  for (const char* none : {"gbuffer", "composite", "tonemap"})
    EXPECT_EQ(raysOf(none), std::optional<uint64_t>(0)) << none;
  uint64_t giRays = 0;
  for (const vk::PassTiming& t : timings) {
    ASSERT_TRUE(t.rays.has_value()) << t.name;
    if (t.name.rfind("gi-", 0) == 0 || t.name.rfind("cache-", 0) == 0) giRays += *t.rays;
  }
  EXPECT_GT(giRays, 0u) << "the GI traced no counted ray";

  frame.countRays(false);
  timings = frame.render(*scene.camera);
  for (const vk::PassTiming& t : timings) EXPECT_FALSE(t.rays.has_value()) << t.name;
}

// The two passes that walk a ray list (shared/restir_gi_io.h, "Ray lists") trace for exactly
// the pixels that need rays, none twice and none lost: on the Cornell box (the light's NEE rays
// from the walls, occluder edges around the two blocks), gi-trace-diffuse-nee-rays counts one
// ray per GI pixel whose gi.nee-ray is set, and gi-trace-resolve-visibility some rays and at most
// one per resolve sample (4) for each pixel gi.resolve-occlusion marks beside an occluder (a
// sample not on the pixel's surface or behind it takes no ray).
TEST(HybridFrame, RayListPassesTraceForEveryListedPixelOnce) {
  vk::Context context(vk::contextOptionsFromEnvironment({}));
  Scene scene = loadScene("cornell");
  GpuScene gpuScene(context, scene);
  HybridSettings settings = presetSettings(Preset::Desktop);
  settings.gi = GiMode::Evolve;
  settings.width = 48;
  settings.height = 36;
  HybridFrame frame(context, gpuScene, scene, settings);
  frame.countRays(true);
  frame.requestDebugView("gi.nee-ray");
  frame.requestDebugView("gi.resolve-occlusion");
  std::vector<vk::PassTiming> timings;
  for (int i = 0; i < 3; ++i) timings = frame.render(*scene.camera);
  auto raysOf = [&](const std::string& pass) -> uint64_t {
    for (const vk::PassTiming& t : timings)
      if (t.name == pass && t.rays) return *t.rays;
    ADD_FAILURE() << "no ray count for " << pass;
    return 0;
  };
  const ImageRGBA32F neeRays = frame.debugViewImage("gi.nee-ray");
  uint64_t neePixels = 0;
  for (size_t i = 0; i < neeRays.pixelCount(); ++i)
    neePixels += neeRays.pixels[4 * i] != 0.0f || neeRays.pixels[4 * i + 1] != 0.0f ||
                 neeRays.pixels[4 * i + 2] != 0.0f;
  const ImageRGBA32F occlusion = frame.debugViewImage("gi.resolve-occlusion");
  uint64_t besideOccluder = 0;
  for (size_t i = 0; i < occlusion.pixelCount(); ++i)
    besideOccluder += (uint32_t(occlusion.pixels[4 * i]) & gpu::RESOLVE_BESIDE_OCCLUDER) != 0;
  std::printf("NEE: %llu GI pixels with a ray; beside an occluder: %llu pixels, %llu rays\n",
              (unsigned long long)neePixels, (unsigned long long)besideOccluder,
              (unsigned long long)raysOf("gi-trace-resolve-visibility"));
  ASSERT_GT(neePixels, 0u);
  EXPECT_EQ(raysOf("gi-trace-diffuse-nee-rays"), neePixels);
  ASSERT_GT(besideOccluder, 0u);
  EXPECT_GT(raysOf("gi-trace-resolve-visibility"), 0u);
  EXPECT_LE(raysOf("gi-trace-resolve-visibility"), 4 * besideOccluder);
}

TEST(HybridFrame, ViewProjectionMapsPixelRaysBackToTheirPixels) {
  Camera camera{{1.0f, 2.0f, 3.0f}, {0.0f, 0.5f, -1.0f}, {0, 1, 0}, 50.0f};
  Aabb bounds;
  bounds.extend(glm::vec3(-5.0f));
  bounds.extend(glm::vec3(5.0f));
  gpu::GpuCamera cam = makeGpuCamera(camera, 64, 32, bounds);
  glm::mat4 m = viewProjection(cam, 0.01f);
  for (glm::vec2 pixel :
       {glm::vec2(0.5f, 0.5f), glm::vec2(63.5f, 10.5f), glm::vec2(20.25f, 31.5f)}) {
    glm::vec3 dir = gpu::cameraRayDirection(cam, pixel, glm::vec2(64, 32));
    float t = 7.0f;
    glm::vec4 clip = m * glm::vec4(cam.position + t * dir, 1.0f);
    glm::vec2 ndc = glm::vec2(clip) / clip.w;
    glm::vec2 back = (ndc * 0.5f + 0.5f) * glm::vec2(64, 32);
    EXPECT_NEAR(back.x, pixel.x, 1e-3f);
    EXPECT_NEAR(back.y, pixel.y, 1e-3f);
    EXPECT_NEAR(clip.w, t * glm::dot(dir, cam.forward), 1e-4f);  // view depth
    EXPECT_NEAR(clip.z / clip.w, 0.01f / clip.w, 1e-7f);         // reversed Z
  }
}

}  // namespace
}  // namespace bounce
