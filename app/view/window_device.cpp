#include "window_device.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <vector>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <bounce/external_device.h>

#include "core/error.h"
#include "vk/check.h"
#include "vk/validation.h"

namespace bounce::view {

namespace {

bool hasDeviceExtension(VkPhysicalDevice pd, const char* name) {
  uint32_t count = 0;
  vkEnumerateDeviceExtensionProperties(pd, nullptr, &count, nullptr);
  std::vector<VkExtensionProperties> exts(count);
  vkEnumerateDeviceExtensionProperties(pd, nullptr, &count, exts.data());
  return std::any_of(exts.begin(), exts.end(), [&](const VkExtensionProperties& e) {
    return std::strcmp(e.extensionName, name) == 0;
  });
}

// A queue family with graphics and compute (Bounce's frame uses one queue) that can present
// to `surface`.
std::optional<uint32_t> presentingQueueFamily(VkPhysicalDevice pd, VkSurfaceKHR surface) {
  uint32_t count = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(pd, &count, nullptr);
  std::vector<VkQueueFamilyProperties> families(count);
  vkGetPhysicalDeviceQueueFamilyProperties(pd, &count, families.data());
  const VkQueueFlags need = VK_QUEUE_COMPUTE_BIT | VK_QUEUE_GRAPHICS_BIT;
  for (uint32_t i = 0; i < count; ++i) {
    VkBool32 present = VK_FALSE;
    vkGetPhysicalDeviceSurfaceSupportKHR(pd, i, surface, &present);
    if ((families[i].queueFlags & need) == need && present) return i;
  }
  return std::nullopt;
}

// Why `pd` cannot run the viewer, or empty. Bounce's own feature checks come later, from the
// adopted Context, with its usual message.
std::string whyUnsuitable(VkPhysicalDevice pd, VkSurfaceKHR surface) {
  VkPhysicalDeviceProperties props;
  vkGetPhysicalDeviceProperties(pd, &props);
  if (props.apiVersion < VK_API_VERSION_1_3) return "needs Vulkan 1.3";
  if (!hasDeviceExtension(pd, VK_KHR_SWAPCHAIN_EXTENSION_NAME)) return "no VK_KHR_swapchain";
  if (!presentingQueueFamily(pd, surface))
    return "no queue with graphics and compute that can present to the window";
  return {};
}

std::string glfwErrorText() {
  const char* description = nullptr;
  glfwGetError(&description);
  return description ? description : "unknown GLFW error";
}

}  // namespace

WindowDevice::WindowDevice(const WindowOptions& options) {
  if (!glfwInit())
    fail("cannot open a window: {} (is DISPLAY set? without a display, run under xvfb-run)",
         glfwErrorText());
  // Later GLFW errors (a window-system call that fails mid-run) are printed as they happen.
  glfwSetErrorCallback([](int code, const char* description) {
    std::fprintf(stderr, "bounce view: GLFW error %d: %s\n", code, description);
  });
  if (!glfwVulkanSupported()) {
    glfwTerminate();
    fail("GLFW finds no Vulkan loader (apt-get install libvulkan1 mesa-vulkan-drivers)");
  }
  glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
  glfwWindowHint(GLFW_RESIZABLE, GLFW_TRUE);
  window_ = glfwCreateWindow(int(options.width), int(options.height), options.title.c_str(),
                             nullptr, nullptr);
  if (!window_) {
    std::string why = glfwErrorText();
    glfwTerminate();
    fail("cannot create a {}x{} window: {}", options.width, options.height, why);
  }
  try {
    createInstance(options.validation);
    VK_CHECK(glfwCreateWindowSurface(instance_, window_, nullptr, &surface_));
    pickPhysicalDevice(options.deviceIndex);
    createDevice();
  } catch (...) {
    release();
    throw;
  }
}

WindowDevice::~WindowDevice() {
  release();
}

void WindowDevice::release() {
  context_.reset();
  if (device_) {
    vkDeviceWaitIdle(device_);
    vkDestroyDevice(device_, nullptr);
    device_ = VK_NULL_HANDLE;
  }
  if (surface_) vkDestroySurfaceKHR(instance_, surface_, nullptr);
  surface_ = VK_NULL_HANDLE;
  vk::destroyDebugMessenger(instance_, messenger_);
  messenger_ = VK_NULL_HANDLE;
  if (instance_) vkDestroyInstance(instance_, nullptr);
  instance_ = VK_NULL_HANDLE;
  if (window_) {
    glfwDestroyWindow(window_);
    glfwTerminate();
    window_ = nullptr;
  }
}

void WindowDevice::createInstance(bool validation) {
  uint32_t glfwCount = 0;
  const char** glfwExtensions = glfwGetRequiredInstanceExtensions(&glfwCount);
  if (!glfwExtensions) fail("GLFW finds no Vulkan surface extension for this window system");
  std::vector<const char*> extensions(glfwExtensions, glfwExtensions + glfwCount);
  std::vector<const char*> layers;

  VkDebugUtilsMessengerCreateInfoEXT messengerInfo =
      vk::validationMessengerInfo(&WindowDevice::onValidationMessage, this);
  VkValidationFeatureEnableEXT syncValidation =
      VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT;
  VkValidationFeaturesEXT features{VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT, &messengerInfo};
  features.enabledValidationFeatureCount = 1;
  features.pEnabledValidationFeatures = &syncValidation;
  if (validation) {
    vk::requireValidationLayer();
    layers.push_back(vk::kValidationLayer);
    extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
  }

  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.pApplicationName = "bounce view";
  app.pEngineName = "bounce";
  app.apiVersion = VK_API_VERSION_1_3;
  VkInstanceCreateInfo ci{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO, validation ? &features : nullptr};
  ci.pApplicationInfo = &app;
  ci.enabledLayerCount = uint32_t(layers.size());
  ci.ppEnabledLayerNames = layers.data();
  ci.enabledExtensionCount = uint32_t(extensions.size());
  ci.ppEnabledExtensionNames = extensions.data();
  VkResult r = vkCreateInstance(&ci, nullptr, &instance_);
  if (r != VK_SUCCESS)
    fail("cannot create a Vulkan 1.3 instance with window-system extensions ({})",
         vk::resultName(r));
  if (validation) messenger_ = vk::createDebugMessenger(instance_, messengerInfo);
}

VKAPI_ATTR VkBool32 VKAPI_CALL WindowDevice::onValidationMessage(
    VkDebugUtilsMessageSeverityFlagBitsEXT severity, VkDebugUtilsMessageTypeFlagsEXT,
    const VkDebugUtilsMessengerCallbackDataEXT* data, void* self) {
  if (vk::printValidationMessage("bounce view", severity, data))
    ++static_cast<WindowDevice*>(self)->validationErrors_;
  return VK_FALSE;
}

void WindowDevice::pickPhysicalDevice(std::optional<uint32_t> index) {
  uint32_t count = 0;
  vkEnumeratePhysicalDevices(instance_, &count, nullptr);
  std::vector<VkPhysicalDevice> devices(count);
  vkEnumeratePhysicalDevices(instance_, &count, devices.data());
  if (devices.empty())
    fail("no Vulkan device found (for the CPU fallback: apt-get install mesa-vulkan-drivers)");
  auto name = [](VkPhysicalDevice pd) {
    VkPhysicalDeviceProperties p;
    vkGetPhysicalDeviceProperties(pd, &p);
    return std::string(p.deviceName);
  };
  if (index) {
    if (*index >= devices.size())
      fail("--device {}: only {} Vulkan device(s) (see `bounce info`)", *index, devices.size());
    std::string why = whyUnsuitable(devices[*index], surface_);
    if (!why.empty())
      fail("--device {} ({}): cannot present: {}", *index, name(devices[*index]), why);
    physicalDevice_ = devices[*index];
  } else {
    int bestRank = -1;
    std::string reasons;
    for (VkPhysicalDevice pd : devices) {
      std::string why = whyUnsuitable(pd, surface_);
      if (!why.empty()) {
        reasons += fmt::format("\n  {}: {}", name(pd), why);
        continue;
      }
      VkPhysicalDeviceProperties p;
      vkGetPhysicalDeviceProperties(pd, &p);
      if (vk::deviceTypeRank(p.deviceType) > bestRank) {
        bestRank = vk::deviceTypeRank(p.deviceType);
        physicalDevice_ = pd;
      }
    }
    if (!physicalDevice_) fail("no Vulkan device can run the viewer:{}", reasons);
  }
  queueFamily_ = *presentingQueueFamily(physicalDevice_, surface_);
}

// The features of vk::Context::createDevice (include/bounce/external_device.h lists them) and
// the swapchain extension; the adopted Context checks them through the create info.
void WindowDevice::createDevice() {
  float priority = 1.0f;
  VkDeviceQueueCreateInfo queueInfo{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
  queueInfo.queueFamilyIndex = queueFamily_;
  queueInfo.queueCount = 1;
  queueInfo.pQueuePriorities = &priority;
  api::RequiredDeviceFeatures features;
  features.vulkan12.hostQueryReset = VK_TRUE;
  const char* extensions[] = {VK_KHR_SWAPCHAIN_EXTENSION_NAME};
  VkDeviceCreateInfo ci{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO, features.chain()};
  ci.queueCreateInfoCount = 1;
  ci.pQueueCreateInfos = &queueInfo;
  ci.enabledExtensionCount = 1;
  ci.ppEnabledExtensionNames = extensions;
  VkResult r = vkCreateDevice(physicalDevice_, &ci, nullptr, &device_);
  if (r != VK_SUCCESS)
    fail("cannot create a Vulkan device with Bounce's features and VK_KHR_swapchain ({})",
         vk::resultName(r));
  vk::AdoptedDevice adopted;
  adopted.instance = instance_;
  adopted.physicalDevice = physicalDevice_;
  adopted.device = device_;
  vkGetDeviceQueue(device_, queueFamily_, 0, &adopted.queue);
  adopted.queueFamily = queueFamily_;
  adopted.createInfo = &ci;
  context_ = std::make_unique<vk::Context>(adopted);
}

}  // namespace bounce::view
