#include "vk/validation.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <vector>

#include "vk/check.h"

namespace bounce::vk {

bool hasInstanceLayer(const char* name) {
  uint32_t count = 0;
  vkEnumerateInstanceLayerProperties(&count, nullptr);
  std::vector<VkLayerProperties> layers(count);
  vkEnumerateInstanceLayerProperties(&count, layers.data());
  return std::any_of(layers.begin(), layers.end(), [&](const VkLayerProperties& l) {
    return std::strcmp(l.layerName, name) == 0;
  });
}

void requireValidationLayer() {
  if (!hasInstanceLayer(kValidationLayer))
    fail("validation requested but {} is not installed (apt-get install vulkan-validationlayers)",
         kValidationLayer);
}

VkDebugUtilsMessengerCreateInfoEXT validationMessengerInfo(
    PFN_vkDebugUtilsMessengerCallbackEXT callback, void* userData) {
  VkDebugUtilsMessengerCreateInfoEXT info{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
  info.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                         VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  info.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                     VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                     VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
  info.pfnUserCallback = callback;
  info.pUserData = userData;
  return info;
}

VkDebugUtilsMessengerEXT createDebugMessenger(VkInstance instance,
                                              const VkDebugUtilsMessengerCreateInfoEXT& info) {
  auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
      vkGetInstanceProcAddr(instance, "vkCreateDebugUtilsMessengerEXT"));
  VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
  VK_CHECK(create(instance, &info, nullptr, &messenger));
  return messenger;
}

void destroyDebugMessenger(VkInstance instance, VkDebugUtilsMessengerEXT messenger) {
  if (!messenger) return;
  auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
      vkGetInstanceProcAddr(instance, "vkDestroyDebugUtilsMessengerEXT"));
  if (destroy) destroy(instance, messenger, nullptr);
}

bool printValidationMessage(const char* program, VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                            const VkDebugUtilsMessengerCallbackDataEXT* data) {
  const bool error = severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  std::fprintf(stderr, "%s: validation %s: %s\n", program, error ? "error" : "warning",
               data->pMessage ? data->pMessage : "");
  return error;
}

}  // namespace bounce::vk
