// Bring your own device: the host's Vulkan objects, for Renderer::create(const ExternalDevice&,
// ...). Bounce records and submits its own command buffers on the host's queue and creates its
// own resources on the host's device; it never destroys what it did not create (the instance,
// device and queue stay the host's; its destructor waits for its work on the queue only).
//
// What the device must have (Vulkan 1.3 core; lavapipe 22.3 has all of it):
//   - VkPhysicalDeviceProperties::apiVersion >= 1.3, and the instance created with
//     VkApplicationInfo::apiVersion >= VK_API_VERSION_1_3;
//   - these features enabled at vkCreateDevice (in VkPhysicalDeviceFeatures2 and the
//     VkPhysicalDeviceVulkan12Features / VkPhysicalDeviceVulkan13Features structs, or the
//     equivalent per-feature structs):
//       shaderInt64,
//       bufferDeviceAddress, scalarBlockLayout, timelineSemaphore   (Vulkan 1.2),
//       synchronization2, dynamicRendering, maintenance4             (Vulkan 1.3);
//   - a queue whose family supports both VK_QUEUE_GRAPHICS_BIT and VK_QUEUE_COMPUTE_BIT;
//     timestamps on it (timestampValidBits > 0 and timestampComputeAndGraphics) give
//     FrameStatistics its pass times.
// No device or instance extension is needed. Renderer::create throws bounce::Error naming the
// device and what is missing. RequiredDeviceFeatures (below) is that list as a pNext chain.
//
// Threads: Vulkan requires access to a queue to be externally synchronised. Bounce uses the
// queue inside Renderer::create, render(), readImage() and the Renderer's destructor; the host
// must not submit to the same queue from another thread meanwhile.
#pragma once
#include <cstdint>

#include <vulkan/vulkan.h>

#include "bounce/config.h"

namespace bounce::api {

struct ExternalDevice {
  VkInstance instance = VK_NULL_HANDLE;
  VkPhysicalDevice physicalDevice = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;  // created from physicalDevice
  VkQueue queue = VK_NULL_HANDLE;    // a queue of queueFamilyIndex on device
  uint32_t queueFamilyIndex = 0;
  // Optional: the VkDeviceCreateInfo the device was created with, read only inside
  // Renderer::create (it may point to the host's stack). Vulkan cannot tell which features a
  // device was created with; given this, Bounce checks that the ones above are enabled and the
  // queue family was requested, rather than only that the physical device supports them.
  const VkDeviceCreateInfo* createInfo = nullptr;
};

// The features listed above, switched on in a chain ready for VkDeviceCreateInfo::pNext:
//   bounce::api::RequiredDeviceFeatures features;
//   features.vulkan12.descriptorIndexing = VK_TRUE;  // the host's own, if it wants more
//   VkDeviceCreateInfo info{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO, features.chain()};
// The structs point at each other, so the object can be neither copied nor moved; keep it alive
// until vkCreateDevice returns.
struct RequiredDeviceFeatures {
  VkPhysicalDeviceVulkan13Features vulkan13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
  VkPhysicalDeviceVulkan12Features vulkan12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES,
                                            &vulkan13};
  VkPhysicalDeviceFeatures2 features2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &vulkan12};

  RequiredDeviceFeatures() {
    features2.features.shaderInt64 = VK_TRUE;
    vulkan12.bufferDeviceAddress = VK_TRUE;
    vulkan12.scalarBlockLayout = VK_TRUE;
    vulkan12.timelineSemaphore = VK_TRUE;
    vulkan13.synchronization2 = VK_TRUE;
    vulkan13.dynamicRendering = VK_TRUE;
    vulkan13.maintenance4 = VK_TRUE;  // workgroup sizes from specialisation constants
  }
  RequiredDeviceFeatures(const RequiredDeviceFeatures&) = delete;
  RequiredDeviceFeatures& operator=(const RequiredDeviceFeatures&) = delete;

  const VkPhysicalDeviceFeatures2* chain() const { return &features2; }
};

}  // namespace bounce::api
