// Bring your own device: the host creates the VkInstance, picks the physical device and creates
// the VkDevice with plain Vulkan, enabling what bounce/external_device.h says Bounce needs, and
// hands them to bounce::Renderer. The example renders the built-in "cornell" box for a few frames
// at a small resolution, reads the image back and checks that it is neither black nor NaN. After
// the renderer is gone, the device must still work (Bounce destroys nothing it did not create);
// the host then destroys it. Exit code 0 on success, 1 with a message otherwise.
#include <cmath>
#include <cstdio>
#include <exception>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <bounce/bounce.h>
#include <vulkan/vulkan.h>

namespace {

void check(VkResult result, const char* what) {
  if (result != VK_SUCCESS)
    throw std::runtime_error(std::string(what) + " failed (VkResult " + std::to_string(result) +
                             ")");
}

// A queue family with graphics and compute, as Bounce needs.
std::optional<uint32_t> graphicsComputeFamily(VkPhysicalDevice device) {
  uint32_t count = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(device, &count, nullptr);
  std::vector<VkQueueFamilyProperties> families(count);
  vkGetPhysicalDeviceQueueFamilyProperties(device, &count, families.data());
  const VkQueueFlags need = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
  for (uint32_t i = 0; i < count; ++i)
    if ((families[i].queueFlags & need) == need) return i;
  return std::nullopt;
}

// Whether the device supports every feature external_device.h lists.
bool supportsBounce(VkPhysicalDevice device) {
  VkPhysicalDeviceProperties properties;
  vkGetPhysicalDeviceProperties(device, &properties);
  if (properties.apiVersion < VK_API_VERSION_1_3 || !graphicsComputeFamily(device)) return false;
  VkPhysicalDeviceVulkan13Features f13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
  VkPhysicalDeviceVulkan12Features f12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES, &f13};
  VkPhysicalDeviceFeatures2 f2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &f12};
  vkGetPhysicalDeviceFeatures2(device, &f2);
  return f2.features.shaderInt64 && f12.bufferDeviceAddress && f12.scalarBlockLayout &&
         f12.timelineSemaphore && f13.synchronization2 && f13.dynamicRendering && f13.maintenance4;
}

// A discrete GPU first, then any other suitable device (lavapipe).
VkPhysicalDevice pickPhysicalDevice(VkInstance instance) {
  uint32_t count = 0;
  vkEnumeratePhysicalDevices(instance, &count, nullptr);
  std::vector<VkPhysicalDevice> devices(count);
  vkEnumeratePhysicalDevices(instance, &count, devices.data());
  VkPhysicalDevice chosen = VK_NULL_HANDLE;
  for (VkPhysicalDevice device : devices) {
    if (!supportsBounce(device)) continue;
    VkPhysicalDeviceProperties properties;
    vkGetPhysicalDeviceProperties(device, &properties);
    if (!chosen || properties.deviceType == VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU) chosen = device;
  }
  if (!chosen) throw std::runtime_error("no Vulkan 1.3 device with the features Bounce needs");
  return chosen;
}

// Renders and checks; the renderer is destroyed when this returns.
void renderCornell(const bounce::ExternalDevice& device) {
  bounce::Scene scene = bounce::Scene::load("cornell");
  bounce::RendererSettings settings = bounce::presetSettings(bounce::Preset::Mobile);
  settings.width = 128;
  settings.height = 96;
  settings.gi = bounce::GiMode::Evolve;
  bounce::Renderer renderer = bounce::Renderer::create(device, scene, settings);
  bounce::FrameStatistics statistics;
  for (int frame = 0; frame < 4; ++frame) statistics = renderer.render(scene.camera());
  bounce::Image image = renderer.readImage();

  if (image.width != settings.width || image.height != settings.height)
    throw std::runtime_error("the image has the wrong size");
  double sum = 0.0;  // of r, g and b
  for (size_t i = 0; i < image.rgba.size(); ++i) {
    if (!std::isfinite(image.rgba[i]))
      throw std::runtime_error("the image has NaN or infinite values");
    if (i % 4 != 3) sum += image.rgba[i];
  }
  double meanRgb = sum / (3.0 * image.width * image.height);
  if (!(meanRgb > 1e-3)) throw std::runtime_error("the image is black");
  std::printf("own_device: cornell %ux%u on %s, %d frames, frame %llu: %.3f ms GPU, mean %.3f\n",
              image.width, image.height, renderer.deviceName().c_str(), 4,
              static_cast<unsigned long long>(statistics.frameIndex), statistics.gpuMilliseconds(),
              meanRgb);
}

}  // namespace

int main() {
  VkInstance instance = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  int exitCode = 0;
  try {
    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.pApplicationName = "bounce own_device example";
    app.apiVersion = VK_API_VERSION_1_3;
    VkInstanceCreateInfo instanceInfo{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    instanceInfo.pApplicationInfo = &app;
    check(vkCreateInstance(&instanceInfo, nullptr, &instance), "vkCreateInstance");

    VkPhysicalDevice physicalDevice = pickPhysicalDevice(instance);
    uint32_t family = *graphicsComputeFamily(physicalDevice);
    float priority = 1.0f;
    VkDeviceQueueCreateInfo queueInfo{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
    queueInfo.queueFamilyIndex = family;
    queueInfo.queueCount = 1;
    queueInfo.pQueuePriorities = &priority;

    // What bounce/external_device.h lists, as a chain.
    bounce::api::RequiredDeviceFeatures features;
    VkDeviceCreateInfo deviceInfo{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO, features.chain()};
    deviceInfo.queueCreateInfoCount = 1;
    deviceInfo.pQueueCreateInfos = &queueInfo;
    check(vkCreateDevice(physicalDevice, &deviceInfo, nullptr, &device), "vkCreateDevice");
    VkQueue queue = VK_NULL_HANDLE;
    vkGetDeviceQueue(device, family, 0, &queue);

    renderCornell({.instance = instance,
                   .physicalDevice = physicalDevice,
                   .device = device,
                   .queue = queue,
                   .queueFamilyIndex = family,
                   .createInfo = &deviceInfo});

    // The device is still the host's and still works.
    VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    VkFence fence = VK_NULL_HANDLE;
    check(vkCreateFence(device, &fenceInfo, nullptr, &fence), "vkCreateFence after the renderer");
    check(vkQueueSubmit(queue, 0, nullptr, fence), "vkQueueSubmit after the renderer");
    check(vkWaitForFences(device, 1, &fence, VK_TRUE, UINT64_MAX), "vkWaitForFences");
    vkDestroyFence(device, fence, nullptr);
    std::printf("own_device: the host's device outlived the renderer\n");
  } catch (const bounce::Error& e) {
    std::fprintf(stderr, "own_device: bounce: %s\n", e.what());
    exitCode = 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "own_device: %s\n", e.what());
    exitCode = 1;
  }
  if (device) vkDestroyDevice(device, nullptr);
  if (instance) vkDestroyInstance(instance, nullptr);
  return exitCode;
}
