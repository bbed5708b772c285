// The Khronos validation layer and the debug messenger that reports its messages: shared by the
// headless Context and the viewer's WindowDevice (app/view), which create their own instances.
#pragma once
#include <cstdint>

#include <vulkan/vulkan.h>

namespace bounce::vk {

inline constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

// Whether the loader offers the instance layer `name`.
bool hasInstanceLayer(const char* name);

// Fails, naming the package that installs it, when the validation layer is missing.
void requireValidationLayer();

// A messenger of the validation layer's warnings and errors, of every message type, calling
// `callback` with `userData`.
VkDebugUtilsMessengerCreateInfoEXT validationMessengerInfo(
    PFN_vkDebugUtilsMessengerCallbackEXT callback, void* userData);

VkDebugUtilsMessengerEXT createDebugMessenger(VkInstance instance,
                                              const VkDebugUtilsMessengerCreateInfoEXT& info);
// Destroys `messenger` (VK_NULL_HANDLE: nothing to do).
void destroyDebugMessenger(VkInstance instance, VkDebugUtilsMessengerEXT messenger);

// Prints a validation message to stderr as "PROGRAM: validation error|warning: ..."; returns
// whether it is an error.
bool printValidationMessage(const char* program, VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                            const VkDebugUtilsMessengerCallbackDataEXT* data);

}  // namespace bounce::vk
