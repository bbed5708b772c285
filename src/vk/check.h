// VK_CHECK turns a failed Vulkan call into a bounce::Error naming the call and the result.
#pragma once
#include <vulkan/vulkan.h>

#include "core/error.h"

namespace bounce::vk {
const char* resultName(VkResult result);
// How much a device type is preferred when several could run Bounce: discrete 4, integrated 3,
// virtual 2, CPU 1, other 0 (`bounce info`'s order, the viewer's too).
int deviceTypeRank(VkPhysicalDeviceType type);
}  // namespace bounce::vk

#define VK_CHECK(call)                                            \
  do {                                                            \
    VkResult vk_check_result_ = (call);                           \
    if (vk_check_result_ != VK_SUCCESS)                           \
      ::bounce::fail("Vulkan call {} failed: {}", #call,          \
                     ::bounce::vk::resultName(vk_check_result_)); \
  } while (0)
