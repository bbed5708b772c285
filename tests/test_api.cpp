// The public API (include/bounce/) as a host sees it: this test includes <bounce/bounce.h> and
// links bounce::bounce only. Bad input gets bounce::Error with a useful message; a scene built in
// code renders; the presets differ as bounce/settings.h documents; bring-your-own-device rejects
// a device without the features Bounce needs and leaves the host's objects alone; bring your own
// G-buffer (Renderer::renderGi) needs the host's device and names the host image at fault. CTest
// runs it with BOUNCE_VALIDATE=1: the Khronos validation layer reports to stderr, which must stay
// free of validation errors.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <bounce/bounce.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace {

using testing::HasSubstr;

// The message of the bounce::Error that `f` throws (fails the test if it throws none).
template <typename F>
std::string errorOf(F&& f) {
  try {
    f();
  } catch (const bounce::Error& e) {
    return e.what();
  }
  ADD_FAILURE() << "no bounce::Error thrown";
  return {};
}

// A 2 m x 2 m white floor at y = 0, lit straight from above by a sun of 100 W/m^2, under a black
// sky, and a camera looking down at it from 45 degrees.
bounce::Scene litQuadScene() {
  bounce::Scene scene;
  bounce::MaterialId white =
      scene.addMaterial({.baseColor = {0.8f, 0.8f, 0.8f}, .roughness = 1.0f, .doubleSided = true});
  std::vector<bounce::Vec3> positions = {{-1, 0, -1}, {-1, 0, 1}, {1, 0, 1}, {1, 0, -1}};
  std::vector<bounce::Vec3> normals(4, bounce::Vec3{0, 1, 0});
  std::vector<uint32_t> indices = {0, 1, 2, 0, 2, 3};
  bounce::MeshId quad = scene.addMesh(positions, normals, indices, white);
  scene.addInstance(quad);
  scene.setSun({.direction = {0, -1, 0}, .irradiance = 100.0f});
  return scene;
}

bounce::Camera quadCamera() {
  return {.position = {0.0f, 1.5f, 1.5f}, .target = {0, 0, 0}, .verticalFovDegrees = 50.0f};
}

bounce::RendererSettings smallSettings(bounce::Preset preset, bounce::GiMode gi) {
  bounce::RendererSettings settings = bounce::presetSettings(preset);
  settings.width = 64;
  settings.height = 48;
  settings.gi = gi;
  return settings;
}

bool hasPass(const bounce::FrameStatistics& statistics, const std::string& name) {
  return statistics.milliseconds(name).has_value();
}

class Api : public testing::Test {
 protected:
  void SetUp() override { testing::internal::CaptureStderr(); }
  void TearDown() override {
    std::string stderrText = testing::internal::GetCapturedStderr();
    EXPECT_THAT(stderrText, testing::Not(HasSubstr("validation error"))) << stderrText;
  }
};

// A glTF without any light gets the default daylight sun and sky when loaded through the
// library, as on the command line (docs/scenes.md); setSky / setSun replace it.
TEST_F(Api, UnlitGltfGetsTheDefaultDaylight) {
  const std::filesystem::path path =
      std::filesystem::temp_directory_path() / "bounce-test-api-unlit-triangle.gltf";
  std::ofstream(path) << R"({"asset": {"version": "2.0"}, "scenes": [{"nodes": [0]}],
    "nodes": [{"mesh": 0}], "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"}],
    "bufferViews": [{"buffer": 0, "byteLength": 36}],
    "buffers": [{"byteLength": 36,
      "uri": "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}]})";
  bounce::Scene scene = bounce::Scene::load(path.string());
  std::filesystem::remove(path);
  EXPECT_EQ(scene.triangleCount(), 1u);
  EXPECT_GT(scene.sun().irradiance, 0.0f);
  EXPECT_LT(scene.sun().direction.y, 0.0f);
  EXPECT_EQ(scene.sky().model, bounce::Sky::Model::Daylight);
  scene.setSky({});
  EXPECT_EQ(scene.sky().model, bounce::Sky::Model::Constant);
}

TEST_F(Api, BadScenePathNamesThePath) {
  const std::string path = "/nonexistent/bounce-test/missing.gltf";
  EXPECT_THAT(errorOf([&] { bounce::Scene::load(path); }), HasSubstr(path));
  std::string unknown = errorOf([] { bounce::Scene::load("no-such-scene"); });
  EXPECT_THAT(unknown, HasSubstr("no-such-scene"));
  EXPECT_THAT(unknown, HasSubstr("cornell"));  // lists the built-in names
}

TEST_F(Api, BadSceneInputIsRejected) {
  bounce::Scene scene;
  bounce::MaterialId m = scene.addMaterial({});
  std::vector<bounce::Vec3> positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  std::vector<uint32_t> outOfRange = {0, 1, 3};
  EXPECT_THAT(errorOf([&] { scene.addMesh(positions, {}, outOfRange, m); }),
              HasSubstr("index 3 out of range"));
  EXPECT_THAT(errorOf([&] { scene.addMesh(positions, {}, {}, bounce::MaterialId{7}); }),
              HasSubstr("material 7 does not exist"));
  EXPECT_THAT(errorOf([&] { scene.addMaterial({.roughness = 2.0f}); }), HasSubstr("roughness"));
  EXPECT_THAT(errorOf([&] { bounce::Renderer::create(scene); }), HasSubstr("no instances"));
  EXPECT_THAT(
      errorOf([&] { bounce::Renderer::create(litQuadScene(), {.width = 0, .height = 10}); }),
      HasSubstr("resolution 0x10"));
}

TEST_F(Api, PresetsDifferAsDocumented) {
  bounce::RendererSettings mobile = bounce::presetSettings(bounce::Preset::Mobile);
  bounce::RendererSettings desktop = bounce::presetSettings(bounce::Preset::Desktop);
  EXPECT_EQ(mobile.preset, bounce::Preset::Mobile);
  EXPECT_EQ(mobile.width, 1170u);
  EXPECT_EQ(mobile.height, 540u);
  EXPECT_EQ(desktop.preset, bounce::Preset::Desktop);
  EXPECT_EQ(desktop.width, 1920u);
  EXPECT_EQ(desktop.height, 1080u);
  bounce::RendererSettings defaults;
  EXPECT_EQ(defaults.preset, mobile.preset);
  EXPECT_EQ(defaults.width, mobile.width);
  EXPECT_EQ(defaults.height, mobile.height);
  EXPECT_EQ(defaults.gi, bounce::GiMode::Evolve);
  EXPECT_TRUE(defaults.autoExposure);
  EXPECT_EQ(defaults.exposureStops, 0.0f);

  // Beyond the resolution: only desktop runs the GI's final spatial denoise.
  bounce::Scene scene = litQuadScene();
  bounce::Renderer mobileRenderer = bounce::Renderer::create(
      scene, smallSettings(bounce::Preset::Mobile, bounce::GiMode::Evolve));
  bounce::Renderer desktopRenderer = bounce::Renderer::create(
      scene, smallSettings(bounce::Preset::Desktop, bounce::GiMode::Evolve));
  bounce::FrameStatistics m = mobileRenderer.render(quadCamera());
  bounce::FrameStatistics d = desktopRenderer.render(quadCamera());
  ASSERT_FALSE(m.passes.empty()) << "the device has no timestamps";
  EXPECT_TRUE(hasPass(m, "gi-restir-temporal"));
  EXPECT_TRUE(hasPass(d, "gi-restir-temporal"));
  EXPECT_FALSE(hasPass(m, "gi-spatial-denoise"));
  EXPECT_TRUE(hasPass(d, "gi-spatial-denoise"));
}

TEST_F(Api, CodeBuiltLitQuadRenders) {
  bounce::Renderer renderer = bounce::Renderer::create(
      litQuadScene(), smallSettings(bounce::Preset::Mobile, bounce::GiMode::None));
  renderer.requestImage("composite");
  bounce::FrameStatistics first = renderer.render(quadCamera());
  bounce::FrameStatistics second = renderer.render(quadCamera());
  EXPECT_EQ(first.frameIndex, 0u);
  EXPECT_EQ(second.frameIndex, 1u);
  EXPECT_TRUE(hasPass(second, "gbuffer"));
  EXPECT_TRUE(hasPass(second, "tonemap"));
  EXPECT_FALSE(hasPass(second, "gi-restir-temporal"));  // GiMode::None

  bounce::Image display = renderer.readImage();
  ASSERT_EQ(display.width, 64u);
  ASSERT_EQ(display.height, 48u);
  ASSERT_EQ(display.rgba.size(), 64u * 48u * 4u);
  for (float v : display.rgba) ASSERT_TRUE(std::isfinite(v));
  // The image centre sees the floor; a white Lambert floor facing the sun has radiance
  // 0.8 E / pi in the composite (some specular on top). Automatic exposure meters the evenly lit
  // floor as middle grey: 0.18 after exposure, acesFilmic(0.18) = 0.267 on the display (the
  // specular part varies by a few percent across the floor).
  const float* centre = display.pixel(32, 24);
  EXPECT_NEAR(centre[0], 0.267f, 0.03f);
  EXPECT_NEAR(centre[0], centre[2], 1e-3f);  // white light on a white floor
  const float* radiance = renderer.readImage("composite").pixel(32, 24);
  EXPECT_NEAR(radiance[1], 0.8f * 100.0f / 3.14159265f, 0.25f * 0.8f * 100.0f / 3.14159265f);
}

// The scene's own animation through the API: the skinned tube bends between two times, so the
// G-buffer's velocity shows motion while the camera stands still; without a new time, none.
TEST_F(Api, AnimationTimeMovesSkinsAndStops) {
  bounce::Scene scene = bounce::Scene::load("skinned");
  bounce::Renderer renderer =
      bounce::Renderer::create(scene, smallSettings(bounce::Preset::Mobile, bounce::GiMode::None));
  renderer.requestImage("gbuffer.velocity");
  auto fastestPixel = [&] {
    bounce::Image velocity = renderer.readImage("gbuffer.velocity");
    float fastest = 0.0f;
    for (uint32_t y = 0; y < velocity.height; ++y)
      for (uint32_t x = 0; x < velocity.width; ++x)
        fastest = std::max(fastest, std::hypot(velocity.pixel(x, y)[0], velocity.pixel(x, y)[1]));
    return fastest;
  };
  renderer.setAnimationTime(0.5);
  renderer.render(scene.camera());
  renderer.setAnimationTime(0.7);
  renderer.render(scene.camera());
  EXPECT_GT(fastestPixel(), 0.3f);
  renderer.render(scene.camera());
  EXPECT_LT(fastestPixel(), 1e-3f);
  EXPECT_THAT(errorOf([&] { renderer.setAnimationTime(-1.0); }), HasSubstr("setAnimationTime"));
}

// Fixed exposure multiplies radiance by 2^exposureStops before the ACES curve (Narkowicz 2015);
// the display keeps fp16 precision. Out-of-range stops are refused by name.
TEST_F(Api, FixedExposureIsTwoToTheStops) {
  bounce::RendererSettings settings = smallSettings(bounce::Preset::Mobile, bounce::GiMode::None);
  settings.autoExposure = false;
  settings.exposureStops = -6.0f;
  bounce::Renderer renderer = bounce::Renderer::create(litQuadScene(), settings);
  renderer.requestImage("composite");
  renderer.render(quadCamera());
  const float radiance = renderer.readImage("composite").pixel(32, 24)[1];
  const double x = radiance * std::exp2(-6.0);
  const double aces = (x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14);
  EXPECT_NEAR(renderer.readImage().pixel(32, 24)[1], aces, 1e-3);

  settings.exposureStops = 100.0f;
  EXPECT_THAT(errorOf([&] { bounce::Renderer::create(litQuadScene(), settings); }),
              HasSubstr("exposureStops 100"));
}

TEST_F(Api, UnknownImageNameGivesClearError) {
  bounce::Renderer renderer = bounce::Renderer::create(
      litQuadScene(), smallSettings(bounce::Preset::Mobile, bounce::GiMode::None));
  EXPECT_THAT(errorOf([&] { renderer.readImage(); }), HasSubstr("no frame rendered yet"));
  renderer.requestImage("no-such-pass");
  std::string message = errorOf([&] { renderer.render(quadCamera()); });
  EXPECT_THAT(message, HasSubstr("no-such-pass"));
  EXPECT_THAT(message, HasSubstr("no pass or resource has that name"));
  EXPECT_THAT(message, HasSubstr("tonemap"));  // lists the valid names
  // The request is dropped and the renderer keeps working.
  renderer.render(quadCamera());
  EXPECT_EQ(renderer.readImage().width, 64u);
  EXPECT_THAT(errorOf([&] { renderer.readImage("no-such-pass"); }), HasSubstr("no-such-pass"));
  EXPECT_THAT(errorOf([&] { renderer.readImage("gbuffer.normals"); }), HasSubstr("requestImage"));
}

// A host's Vulkan instance on the first physical device, and a graphics + compute queue family
// there, as an engine would make them before handing its device to Bounce.
struct HostInstance {
  VkInstance instance = VK_NULL_HANDLE;
  VkPhysicalDevice physicalDevice = VK_NULL_HANDLE;
  uint32_t family = 0;       // a graphics + compute queue family
  uint32_t familyCount = 0;  // queue families of the device
};

void createHostInstance(HostInstance& host) {
  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.apiVersion = VK_API_VERSION_1_3;
  VkInstanceCreateInfo instanceInfo{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  instanceInfo.pApplicationInfo = &app;
  ASSERT_EQ(vkCreateInstance(&instanceInfo, nullptr, &host.instance), VK_SUCCESS);
  uint32_t count = 1;
  vkEnumeratePhysicalDevices(host.instance, &count, &host.physicalDevice);
  ASSERT_NE(host.physicalDevice, VK_NULL_HANDLE);
  vkGetPhysicalDeviceQueueFamilyProperties(host.physicalDevice, &host.familyCount, nullptr);
  std::vector<VkQueueFamilyProperties> families(host.familyCount);
  vkGetPhysicalDeviceQueueFamilyProperties(host.physicalDevice, &host.familyCount, families.data());
  const VkQueueFlags need = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
  while (host.family < host.familyCount && (families[host.family].queueFlags & need) != need)
    ++host.family;
  ASSERT_LT(host.family, host.familyCount);
}

// A host device created without Bounce's features: a clear error, and the host's device and
// instance stay alive (the host destroys them afterwards).
TEST_F(Api, ExternalDeviceWithoutFeaturesIsRejected) {
  HostInstance host;
  ASSERT_NO_FATAL_FAILURE(createHostInstance(host));
  VkInstance instance = host.instance;
  VkPhysicalDevice physicalDevice = host.physicalDevice;
  const uint32_t family = host.family, familyCount = host.familyCount;

  float priority = 1.0f;
  VkDeviceQueueCreateInfo queueInfo{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
  queueInfo.queueFamilyIndex = family;
  queueInfo.queueCount = 1;
  queueInfo.pQueuePriorities = &priority;
  VkDeviceCreateInfo deviceInfo{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};  // no features enabled
  deviceInfo.queueCreateInfoCount = 1;
  deviceInfo.pQueueCreateInfos = &queueInfo;
  VkDevice device = VK_NULL_HANDLE;
  ASSERT_EQ(vkCreateDevice(physicalDevice, &deviceInfo, nullptr, &device), VK_SUCCESS);
  VkQueue queue = VK_NULL_HANDLE;
  vkGetDeviceQueue(device, family, 0, &queue);

  bounce::ExternalDevice external{.instance = instance,
                                  .physicalDevice = physicalDevice,
                                  .device = device,
                                  .queue = queue,
                                  .queueFamilyIndex = family,
                                  .createInfo = &deviceInfo};
  std::string message = errorOf([&] { bounce::Renderer::create(external, litQuadScene()); });
  EXPECT_THAT(message, HasSubstr("not enabled at vkCreateDevice"));
  EXPECT_THAT(message, HasSubstr("bufferDeviceAddress"));
  EXPECT_THAT(message, HasSubstr("shaderInt64"));

  external.queueFamilyIndex = familyCount;  // no such family
  EXPECT_THAT(errorOf([&] { bounce::Renderer::create(external, litQuadScene()); }),
              HasSubstr("does not exist"));

  EXPECT_EQ(vkDeviceWaitIdle(device), VK_SUCCESS);  // still the host's, still alive
  vkDestroyDevice(device, nullptr);
  vkDestroyInstance(instance, nullptr);
}

// Bring your own G-buffer: only on the host's device, only with a GI mode, and a host image of
// the wrong format or extent is an error naming it. (The images' handles here are stand-ins that
// Bounce never passes to Vulkan: the contract is checked before anything is recorded. The full
// path runs in examples/own_gbuffer and tests/test_gbuffer_import.cpp.)
TEST_F(Api, RenderGiChecksTheDeviceAndTheHostImages) {
  bounce::Scene scene = litQuadScene();
  bounce::RendererSettings settings = smallSettings(bounce::Preset::Mobile, bounce::GiMode::Evolve);
  {
    bounce::Renderer own = bounce::Renderer::create(scene, settings);
    EXPECT_THAT(errorOf([&] { own.renderGi(quadCamera(), {}); }), HasSubstr("ExternalDevice"));
  }

  HostInstance host;
  ASSERT_NO_FATAL_FAILURE(createHostInstance(host));
  VkInstance instance = host.instance;
  VkPhysicalDevice physicalDevice = host.physicalDevice;
  const uint32_t family = host.family;
  float priority = 1.0f;
  VkDeviceQueueCreateInfo queueInfo{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
  queueInfo.queueFamilyIndex = family;
  queueInfo.queueCount = 1;
  queueInfo.pQueuePriorities = &priority;
  VkPhysicalDeviceVulkan13Features f13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
  f13.synchronization2 = f13.dynamicRendering = f13.maintenance4 = VK_TRUE;
  VkPhysicalDeviceVulkan12Features f12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES, &f13};
  f12.bufferDeviceAddress = f12.scalarBlockLayout = f12.timelineSemaphore = VK_TRUE;
  VkPhysicalDeviceFeatures2 f2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &f12};
  f2.features.shaderInt64 = VK_TRUE;
  VkDeviceCreateInfo deviceInfo{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO, &f2};
  deviceInfo.queueCreateInfoCount = 1;
  deviceInfo.pQueueCreateInfos = &queueInfo;
  VkDevice device = VK_NULL_HANDLE;
  ASSERT_EQ(vkCreateDevice(physicalDevice, &deviceInfo, nullptr, &device), VK_SUCCESS);
  VkQueue queue = VK_NULL_HANDLE;
  vkGetDeviceQueue(device, family, 0, &queue);
  bounce::ExternalDevice external{.instance = instance,
                                  .physicalDevice = physicalDevice,
                                  .device = device,
                                  .queue = queue,
                                  .queueFamilyIndex = family,
                                  .createInfo = &deviceInfo};
  {
    bounce::RendererSettings noGi = settings;
    noGi.gi = bounce::GiMode::None;
    bounce::Renderer renderer = bounce::Renderer::create(external, scene, noGi);
    EXPECT_THAT(errorOf([&] { renderer.renderGi(quadCamera(), {}); }), HasSubstr("GI mode"));
  }
  {
    bounce::Renderer renderer = bounce::Renderer::create(external, scene, settings);
    auto standIn = [](VkFormat format, uint32_t width, uint32_t height) {
      return bounce::HostImage{reinterpret_cast<VkImage>(uintptr_t(0x1000)),
                               reinterpret_cast<VkImageView>(uintptr_t(0x2000)), format, width,
                               height};
    };
    bounce::HostGBuffer gbuffer{
        standIn(VK_FORMAT_R32_SFLOAT, 64, 48), standIn(VK_FORMAT_R16G16B16A16_SFLOAT, 64, 48),
        standIn(VK_FORMAT_R8G8B8A8_SRGB, 64, 48), standIn(VK_FORMAT_R16G16_SFLOAT, 64, 48)};
    std::string message = errorOf([&] { renderer.renderGi(quadCamera(), gbuffer); });
    EXPECT_THAT(message, HasSubstr("albedo image has format VK_FORMAT_R8G8B8A8_SRGB"));
    EXPECT_THAT(message, HasSubstr("VK_FORMAT_R8G8B8A8_UNORM"));
    gbuffer.albedo.format = VK_FORMAT_R8G8B8A8_UNORM;
    gbuffer.motion.width = 32;
    EXPECT_THAT(errorOf([&] { renderer.renderGi(quadCamera(), gbuffer); }),
                HasSubstr("motion image is 32x48; it must be the render resolution 64x48"));
    gbuffer.motion.width = 64;
    gbuffer.depth.view = VK_NULL_HANDLE;
    EXPECT_THAT(errorOf([&] { renderer.renderGi(quadCamera(), gbuffer); }),
                HasSubstr("depth image has no VkImage or no VkImageView"));
    // Still a working renderer.
    EXPECT_EQ(renderer.render(quadCamera()).frameIndex, 0u);
  }
  vkDestroyDevice(device, nullptr);
  vkDestroyInstance(instance, nullptr);
}

}  // namespace

namespace {

// A flat plane (depth 3, facing the camera) of known mean 0.5 with exponential noise, 16x16.
bounce::DenoiserFrame noisyPlane(uint32_t seed) {
  constexpr uint32_t n = 16;
  bounce::DenoiserFrame f;
  f.noisy = {n, n, std::vector<float>(n * n * 4, 1.0f)};
  f.normal = {n, n, std::vector<float>(n * n * 4, 0.0f)};
  f.depth.assign(n * n, 3.0f);
  f.motion.assign(2 * n * n, 0.0f);
  uint32_t state = seed;
  for (uint32_t i = 0; i < n * n; ++i) {
    state = state * 1664525u + 1013904223u;  // an LCG: the test needs no quality, only noise
    float u = (float(state >> 8) + 0.5f) / 16777216.0f;
    float v = -0.5f * std::log(u);  // mean 0.5
    f.noisy.rgba[4 * i] = f.noisy.rgba[4 * i + 1] = f.noisy.rgba[4 * i + 2] = v;
    f.normal.rgba[4 * i + 2] = 1.0f;
  }
  return f;
}

double squaredError(const bounce::Image& image) {
  double sum = 0.0;
  for (size_t i = 0; i < image.rgba.size(); i += 4) sum += std::pow(image.rgba[i] - 0.5, 2.0);
  return sum / double(image.rgba.size() / 4);
}

}  // namespace

// Each denoiser alone through bounce/denoiser.h: 16 frames of a noisy plane come out with a lower
// squared error against its mean at least 4x below the input's (issue 21); a wrong image size is
// named.
TEST_F(Api, DenoisersWorkAlone) {
  for (const char* name : {"svgf", "reblur", "hybrid"}) {
    bounce::Denoiser denoiser =
        bounce::Denoiser::create(bounce::denoiserKindFromName(name), 16, 16);
    bounce::Image out;
    bounce::DenoiserFrame f;
    for (uint32_t frame = 0; frame < 16; ++frame) {
      f = noisyPlane(frame + 1);
      out = denoiser.denoise(f);
    }
    ASSERT_EQ(out.width, 16u);
    EXPECT_LT(squaredError(out), squaredError(f.noisy) / 4.0) << name;
    f.depth.pop_back();
    EXPECT_THAT(errorOf([&] { denoiser.denoise(f); }), HasSubstr("depth")) << name;
  }
  EXPECT_THAT(errorOf([] { bounce::denoiserKindFromName("nlm"); }), HasSubstr("nlm"));
}
