// The viewer's window and the Vulkan device that presents to it. The headless Context creates
// its instance without any window-system extension (the GPU machine has no X libraries), so the
// viewer makes its own instance (GLFW's surface extensions, the validation layer on request),
// surface and device (Bounce's required features plus VK_KHR_swapchain) and hands the device to
// Bounce as a host would (vk::Context's adopted-device constructor, bring your own device,
// include/bounce/external_device.h). The validation messages are counted here, since an
// adopted Context has no messenger of its own.
#pragma once
#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include <vulkan/vulkan.h>

#include "vk/context.h"

struct GLFWwindow;

namespace bounce::view {

struct WindowOptions {
  uint32_t width = 640;  // the window's initial client area in screen coordinates
  uint32_t height = 360;
  std::string title = "bounce view";
  std::optional<uint32_t> deviceIndex;  // --device N; else the best device that can present
  bool validation = false;              // Khronos validation (with synchronization validation)
};

class WindowDevice {
 public:
  // Throws bounce::Error when GLFW cannot open a window (no display), when no device can present
  // to it, or when the chosen one lacks Bounce's requirements.
  explicit WindowDevice(const WindowOptions& options);
  ~WindowDevice();
  WindowDevice(const WindowDevice&) = delete;
  WindowDevice& operator=(const WindowDevice&) = delete;

  GLFWwindow* window() const { return window_; }
  VkSurfaceKHR surface() const { return surface_; }
  vk::Context& context() { return *context_; }
  VkInstance instance() const { return instance_; }
  VkPhysicalDevice physicalDevice() const { return physicalDevice_; }
  VkDevice device() const { return device_; }
  uint32_t validationErrorCount() const { return validationErrors_; }

 private:
  void release();  // everything, in reverse order of creation
  void createInstance(bool validation);
  void pickPhysicalDevice(std::optional<uint32_t> index);
  void createDevice();
  static VKAPI_ATTR VkBool32 VKAPI_CALL onValidationMessage(
      VkDebugUtilsMessageSeverityFlagBitsEXT severity, VkDebugUtilsMessageTypeFlagsEXT types,
      const VkDebugUtilsMessengerCallbackDataEXT* data, void* self);

  GLFWwindow* window_ = nullptr;
  VkInstance instance_ = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
  VkSurfaceKHR surface_ = VK_NULL_HANDLE;
  VkPhysicalDevice physicalDevice_ = VK_NULL_HANDLE;
  uint32_t queueFamily_ = 0;
  VkDevice device_ = VK_NULL_HANDLE;
  std::unique_ptr<vk::Context> context_;
  uint32_t validationErrors_ = 0;
};

}  // namespace bounce::view
