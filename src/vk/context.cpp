#include "vk/context.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <unordered_map>

#include <bounce/external_device.h>

#include "vk/check.h"
#include "vk/validation.h"

namespace bounce::vk {

namespace {

std::unordered_map<VkDeviceMemory, VkDeviceSize>& allocationSizes() {
  static std::unordered_map<VkDeviceMemory, VkDeviceSize> sizes;
  return sizes;
}

bool hasInstanceExtension(const char* name) {
  uint32_t count = 0;
  vkEnumerateInstanceExtensionProperties(nullptr, &count, nullptr);
  std::vector<VkExtensionProperties> exts(count);
  vkEnumerateInstanceExtensionProperties(nullptr, &count, exts.data());
  return std::any_of(exts.begin(), exts.end(), [&](const VkExtensionProperties& e) {
    return std::strcmp(e.extensionName, name) == 0;
  });
}

std::vector<std::string> deviceExtensions(VkPhysicalDevice pd) {
  uint32_t count = 0;
  vkEnumerateDeviceExtensionProperties(pd, nullptr, &count, nullptr);
  std::vector<VkExtensionProperties> exts(count);
  vkEnumerateDeviceExtensionProperties(pd, nullptr, &count, exts.data());
  std::vector<std::string> names;
  for (const auto& e : exts) names.emplace_back(e.extensionName);
  return names;
}

const char* deviceTypeName(VkPhysicalDeviceType type) {
  switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU:
      return "discrete";
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU:
      return "integrated";
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU:
      return "virtual";
    case VK_PHYSICAL_DEVICE_TYPE_CPU:
      return "cpu";
    default:
      return "other";
  }
}

bool hasDeviceExtension(VkPhysicalDevice pd, const char* name) {
  const std::vector<std::string> all = deviceExtensions(pd);
  return std::find(all.begin(), all.end(), name) != all.end();
}

// A queue family that can do both compute and graphics (the frame uses one queue).
std::optional<uint32_t> findQueueFamily(VkPhysicalDevice pd, bool* timestamps) {
  uint32_t count = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(pd, &count, nullptr);
  std::vector<VkQueueFamilyProperties> families(count);
  vkGetPhysicalDeviceQueueFamilyProperties(pd, &count, families.data());
  for (uint32_t i = 0; i < count; ++i) {
    VkQueueFlags need = VK_QUEUE_COMPUTE_BIT | VK_QUEUE_GRAPHICS_BIT;
    if ((families[i].queueFlags & need) == need) {
      if (timestamps) *timestamps = families[i].timestampValidBits > 0;
      return i;
    }
  }
  return std::nullopt;
}

// The features Bounce requires (createDevice() enables them; include/bounce/external_device.h
// lists them for hosts) that `f10`, `f12` and `f13` lack, in a fixed order.
std::vector<const char*> missingFeatures(const VkPhysicalDeviceFeatures& f10,
                                         const VkPhysicalDeviceVulkan12Features& f12,
                                         const VkPhysicalDeviceVulkan13Features& f13) {
  std::vector<const char*> missing;
  if (!f12.bufferDeviceAddress) missing.push_back("bufferDeviceAddress");
  if (!f12.scalarBlockLayout) missing.push_back("scalarBlockLayout");
  if (!f12.timelineSemaphore) missing.push_back("timelineSemaphore");
  if (!f13.synchronization2) missing.push_back("synchronization2");
  if (!f13.dynamicRendering) missing.push_back("dynamicRendering");
  if (!f13.maintenance4) missing.push_back("maintenance4");
  if (!f10.shaderInt64) missing.push_back("shaderInt64");
  return missing;
}

// Everything Bounce requires of a device (DESIGN.md §1: Vulkan 1.3 core plus what lavapipe
// 22.3 offers). Returns the reason a device is unusable, or an empty string.
std::string checkRequirements(VkPhysicalDevice pd, const VkPhysicalDeviceProperties& props) {
  if (props.apiVersion < VK_API_VERSION_1_3) return "needs Vulkan 1.3";
  VkPhysicalDeviceVulkan13Features f13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
  VkPhysicalDeviceVulkan12Features f12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES, &f13};
  VkPhysicalDeviceFeatures2 f2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &f12};
  vkGetPhysicalDeviceFeatures2(pd, &f2);
  std::vector<const char*> missing = missingFeatures(f2.features, f12, f13);
  if (!missing.empty()) return fmt::format("no {}", missing.front());
  if (!findQueueFamily(pd, nullptr)) return "no queue with compute and graphics";
  return {};
}

// What a host's VkDeviceCreateInfo enables, gathered from pEnabledFeatures and the pNext chain:
// VkPhysicalDeviceFeatures2, the Vulkan 1.2 and 1.3 feature structs, and the per-feature structs
// of the extensions promoted into them.
struct EnabledFeatures {
  VkPhysicalDeviceFeatures f10{};
  VkPhysicalDeviceVulkan12Features f12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
  VkPhysicalDeviceVulkan13Features f13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
};

EnabledFeatures enabledFeatures(const VkDeviceCreateInfo& ci) {
  EnabledFeatures e;
  auto enable = [](VkBool32& to, VkBool32 from) { to = to || from; };
  if (ci.pEnabledFeatures) enable(e.f10.shaderInt64, ci.pEnabledFeatures->shaderInt64);
  for (auto* s = static_cast<const VkBaseInStructure*>(ci.pNext); s; s = s->pNext) {
    switch (s->sType) {
      case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2: {
        auto* f = reinterpret_cast<const VkPhysicalDeviceFeatures2*>(s);
        enable(e.f10.shaderInt64, f->features.shaderInt64);
        break;
      }
      case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES: {
        auto* f = reinterpret_cast<const VkPhysicalDeviceVulkan12Features*>(s);
        enable(e.f12.bufferDeviceAddress, f->bufferDeviceAddress);
        enable(e.f12.scalarBlockLayout, f->scalarBlockLayout);
        enable(e.f12.timelineSemaphore, f->timelineSemaphore);
        break;
      }
      case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES: {
        auto* f = reinterpret_cast<const VkPhysicalDeviceVulkan13Features*>(s);
        enable(e.f13.synchronization2, f->synchronization2);
        enable(e.f13.dynamicRendering, f->dynamicRendering);
        enable(e.f13.maintenance4, f->maintenance4);
        break;
      }
      case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_BUFFER_DEVICE_ADDRESS_FEATURES:
        enable(e.f12.bufferDeviceAddress,
               reinterpret_cast<const VkPhysicalDeviceBufferDeviceAddressFeatures*>(s)
                   ->bufferDeviceAddress);
        break;
      case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SCALAR_BLOCK_LAYOUT_FEATURES:
        enable(e.f12.scalarBlockLayout,
               reinterpret_cast<const VkPhysicalDeviceScalarBlockLayoutFeatures*>(s)
                   ->scalarBlockLayout);
        break;
      case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_TIMELINE_SEMAPHORE_FEATURES:
        enable(e.f12.timelineSemaphore,
               reinterpret_cast<const VkPhysicalDeviceTimelineSemaphoreFeatures*>(s)
                   ->timelineSemaphore);
        break;
      case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SYNCHRONIZATION_2_FEATURES:
        enable(
            e.f13.synchronization2,
            reinterpret_cast<const VkPhysicalDeviceSynchronization2Features*>(s)->synchronization2);
        break;
      case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DYNAMIC_RENDERING_FEATURES:
        enable(
            e.f13.dynamicRendering,
            reinterpret_cast<const VkPhysicalDeviceDynamicRenderingFeatures*>(s)->dynamicRendering);
        break;
      case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MAINTENANCE_4_FEATURES:
        enable(e.f13.maintenance4,
               reinterpret_cast<const VkPhysicalDeviceMaintenance4Features*>(s)->maintenance4);
        break;
      default:
        break;
    }
  }
  return e;
}

DeviceInfo describeDevice(VkPhysicalDevice pd, uint32_t index) {
  VkPhysicalDeviceSubgroupProperties subgroup{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_PROPERTIES};
  VkPhysicalDeviceDriverProperties driver{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES,
                                          &subgroup};
  VkPhysicalDeviceProperties2 props2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &driver};
  vkGetPhysicalDeviceProperties2(pd, &props2);
  const VkPhysicalDeviceProperties& p = props2.properties;

  DeviceInfo info;
  info.index = index;
  info.name = p.deviceName;
  info.type = deviceTypeName(p.deviceType);
  info.driver = std::string(driver.driverName) + " " + driver.driverInfo;
  info.apiVersion = p.apiVersion;
  info.subgroupSize = subgroup.subgroupSize;
  info.maxStorageBufferRange = p.limits.maxStorageBufferRange;
  info.maxPushConstantsSize = p.limits.maxPushConstantsSize;
  info.maxComputeWorkGroupInvocations = p.limits.maxComputeWorkGroupInvocations;
  info.timestampPeriodNs = p.limits.timestampPeriod;
  findQueueFamily(pd, &info.timestampsOnComputeQueue);

  VkPhysicalDeviceVulkan12Features f12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
  VkPhysicalDeviceFeatures2 f2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &f12};
  vkGetPhysicalDeviceFeatures2(pd, &f2);
  info.shaderFloat16 = f12.shaderFloat16;

  bool accelerationStructure = false, deferredHostOperations = false;
  for (const std::string& ext : deviceExtensions(pd)) {
    if (ext == VK_KHR_RAY_TRACING_PIPELINE_EXTENSION_NAME) info.rayTracingPipeline = true;
    if (ext == VK_KHR_ACCELERATION_STRUCTURE_EXTENSION_NAME) accelerationStructure = true;
    if (ext == VK_KHR_DEFERRED_HOST_OPERATIONS_EXTENSION_NAME) deferredHostOperations = true;
    if (ext == "VK_KHR_ray_query") info.rayQuery = true;
    if (ext == "VK_KHR_cooperative_matrix" || ext == "VK_NV_cooperative_matrix")
      info.cooperativeMatrix = true;
  }
  if (info.rayTracingPipeline && accelerationStructure && deferredHostOperations) {
    VkPhysicalDeviceAccelerationStructureFeaturesKHR as{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ACCELERATION_STRUCTURE_FEATURES_KHR};
    VkPhysicalDeviceRayTracingPipelineFeaturesKHR rtp{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_RAY_TRACING_PIPELINE_FEATURES_KHR, &as};
    VkPhysicalDeviceFeatures2 rt2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &rtp};
    vkGetPhysicalDeviceFeatures2(pd, &rt2);
    info.hardwareRayTracingUsable = rtp.rayTracingPipeline && as.accelerationStructure;
  }
  VkPhysicalDeviceMemoryProperties mem;
  vkGetPhysicalDeviceMemoryProperties(pd, &mem);
  for (uint32_t h = 0; h < mem.memoryHeapCount; ++h)
    if (mem.memoryHeaps[h].flags & VK_MEMORY_HEAP_DEVICE_LOCAL_BIT)
      info.deviceLocalBytes = std::max<uint64_t>(info.deviceLocalBytes, mem.memoryHeaps[h].size);

  info.unsuitableBecause = checkRequirements(pd, p);
  info.suitable = info.unsuitableBecause.empty();
  info.rank = info.suitable ? deviceTypeRank(p.deviceType) : -1;
  return info;
}

std::vector<VkPhysicalDevice> physicalDevices(VkInstance instance) {
  uint32_t count = 0;
  vkEnumeratePhysicalDevices(instance, &count, nullptr);
  std::vector<VkPhysicalDevice> devices(count);
  vkEnumeratePhysicalDevices(instance, &count, devices.data());
  return devices;
}

VkInstance createBareInstance(const std::vector<const char*>& layers,
                              const std::vector<const char*>& extensions, const void* next) {
  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.pApplicationName = "bounce";
  app.pEngineName = "bounce";
  app.apiVersion = VK_API_VERSION_1_3;
  VkInstanceCreateInfo ci{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO, next};
  ci.pApplicationInfo = &app;
  ci.enabledLayerCount = uint32_t(layers.size());
  ci.ppEnabledLayerNames = layers.data();
  ci.enabledExtensionCount = uint32_t(extensions.size());
  ci.ppEnabledExtensionNames = extensions.data();
  VkInstance instance = VK_NULL_HANDLE;
  VkResult r = vkCreateInstance(&ci, nullptr, &instance);
  if (r != VK_SUCCESS)
    fail(
        "cannot create a Vulkan 1.3 instance ({}): is a Vulkan driver installed? "
        "(lavapipe: apt-get install mesa-vulkan-drivers)",
        resultName(r));
  return instance;
}

}  // namespace

ContextOptions contextOptionsFromEnvironment(ContextOptions options) {
  if (const char* v = std::getenv("BOUNCE_VALIDATE"); v && std::strcmp(v, "0") != 0)
    options.validation = true;
  if (!options.deviceIndex) {
    if (const char* d = std::getenv("BOUNCE_DEVICE")) {
      char* end = nullptr;
      long n = std::strtol(d, &end, 10);
      if (end == d || *end != '\0' || n < 0) fail("BOUNCE_DEVICE='{}': expected a device index", d);
      options.deviceIndex = uint32_t(n);
    }
  }
  if (options.memoryLimitBytes == 0) {
    if (const char* m = std::getenv("BOUNCE_DEVICE_MEMORY_LIMIT")) {
      char* end = nullptr;
      long long mib = std::strtoll(m, &end, 10);
      if (end == m || *end != '\0' || mib <= 0)
        fail("BOUNCE_DEVICE_MEMORY_LIMIT='{}': expected a positive number of MiB", m);
      options.memoryLimitBytes = uint64_t(mib) << 20;
    }
  }
  return options;
}

std::vector<DeviceInfo> Context::listDevices() {
  VkInstance instance = createBareInstance({}, {}, nullptr);
  std::vector<DeviceInfo> infos;
  uint32_t index = 0;
  for (VkPhysicalDevice pd : physicalDevices(instance))
    infos.push_back(describeDevice(pd, index++));
  vkDestroyInstance(instance, nullptr);
  return infos;
}

Context::Context(const ContextOptions& options) : memoryLimitBytes_(options.memoryLimitBytes) {
  createInstance(options);
  pickPhysicalDevice(options);
  createDevice();
}

Context::Context(const AdoptedDevice& host) : adopted_(true) {
  if (!host.instance || !host.physicalDevice || !host.device || !host.queue)
    fail("external device: the instance, physical device, device and queue must all be given");
  std::vector<VkPhysicalDevice> devices = physicalDevices(host.instance);
  auto found = std::find(devices.begin(), devices.end(), host.physicalDevice);
  if (found == devices.end())
    fail("external device: the physical device is not one of the instance's {} device(s)",
         devices.size());
  info_ = describeDevice(host.physicalDevice, uint32_t(found - devices.begin()));

  std::vector<std::string> problems;
  if (!info_.suitable) problems.push_back(info_.unsuitableBecause);
  uint32_t familyCount = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(host.physicalDevice, &familyCount, nullptr);
  std::vector<VkQueueFamilyProperties> families(familyCount);
  vkGetPhysicalDeviceQueueFamilyProperties(host.physicalDevice, &familyCount, families.data());
  const VkQueueFlags need = VK_QUEUE_COMPUTE_BIT | VK_QUEUE_GRAPHICS_BIT;
  if (host.queueFamily >= familyCount) {
    problems.push_back(fmt::format("queue family {} does not exist (the device has {})",
                                   host.queueFamily, familyCount));
  } else {
    if ((families[host.queueFamily].queueFlags & need) != need)
      problems.push_back(
          fmt::format("queue family {} lacks graphics or compute", host.queueFamily));
    info_.timestampsOnComputeQueue = families[host.queueFamily].timestampValidBits > 0;
  }
  info_.shaderFloat16 = false;  // enabled or not, Bounce's shaders do not rely on it
  if (const VkDeviceCreateInfo* ci = host.createInfo) {
    EnabledFeatures enabled = enabledFeatures(*ci);
    std::vector<const char*> missing = missingFeatures(enabled.f10, enabled.f12, enabled.f13);
    if (!missing.empty()) {
      std::string names;
      for (const char* name : missing)
        names += fmt::format("{}{}", names.empty() ? "" : ", ", name);
      problems.push_back("not enabled at vkCreateDevice: " + names);
    }
    bool requested = false;
    for (uint32_t i = 0; i < ci->queueCreateInfoCount; ++i)
      requested = requested || ci->pQueueCreateInfos[i].queueFamilyIndex == host.queueFamily;
    if (!requested)
      problems.push_back(
          fmt::format("no queue of family {} was requested at vkCreateDevice", host.queueFamily));
  }
  if (!problems.empty()) {
    std::string reasons;
    for (const std::string& p : problems)
      reasons += fmt::format("{}{}", reasons.empty() ? "" : "; ", p);
    fail(
        "external device '{}' cannot run Bounce: {} (include/bounce/external_device.h lists "
        "what Bounce needs)",
        info_.name, reasons);
  }

  instance_ = host.instance;
  physicalDevice_ = host.physicalDevice;
  device_ = host.device;
  queue_ = host.queue;
  queueFamily_ = host.queueFamily;
  VkPhysicalDeviceProperties props;
  vkGetPhysicalDeviceProperties(physicalDevice_, &props);
  limits_ = props.limits;
  vkGetPhysicalDeviceMemoryProperties(physicalDevice_, &memoryProperties_);
  createCommandPoolAndFence();
}

Context::~Context() {
  if (device_) {
    waitIdle();
    vkDestroyFence(device_, fence_, nullptr);
    vkDestroyCommandPool(device_, commandPool_, nullptr);
    if (!adopted_) vkDestroyDevice(device_, nullptr);
  }
  destroyDebugMessenger(instance_, messenger_);
  if (instance_ && !adopted_) vkDestroyInstance(instance_, nullptr);
}

void Context::waitIdle() const {
  if (adopted_)
    vkQueueWaitIdle(queue_);
  else
    vkDeviceWaitIdle(device_);
}

void Context::createInstance(const ContextOptions& options) {
  std::vector<const char*> layers;
  std::vector<const char*> extensions;
  debugUtils_ = hasInstanceExtension(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
  if (debugUtils_) extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
  if (options.validation) {
    requireValidationLayer();
    if (!debugUtils_) fail("validation requested but VK_EXT_debug_utils is missing");
    layers.push_back(kValidationLayer);
    validationEnabled_ = true;
  }

  VkDebugUtilsMessengerCreateInfoEXT messengerInfo =
      validationMessengerInfo(&Context::onValidationMessage, this);

  VkValidationFeatureEnableEXT syncValidation =
      VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT;
  VkValidationFeaturesEXT features{VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT};
  features.enabledValidationFeatureCount = 1;
  features.pEnabledValidationFeatures = &syncValidation;

  const void* next = nullptr;
  if (validationEnabled_) {
    next = &messengerInfo;
    if (options.synchronizationValidation) {
      features.pNext = &messengerInfo;
      next = &features;
    }
  }
  instance_ = createBareInstance(layers, extensions, next);
  if (debugUtils_) {
    beginLabel_ = reinterpret_cast<PFN_vkCmdBeginDebugUtilsLabelEXT>(
        vkGetInstanceProcAddr(instance_, "vkCmdBeginDebugUtilsLabelEXT"));
    endLabel_ = reinterpret_cast<PFN_vkCmdEndDebugUtilsLabelEXT>(
        vkGetInstanceProcAddr(instance_, "vkCmdEndDebugUtilsLabelEXT"));
  }
  if (validationEnabled_) messenger_ = createDebugMessenger(instance_, messengerInfo);
}

VKAPI_ATTR VkBool32 VKAPI_CALL Context::onValidationMessage(
    VkDebugUtilsMessageSeverityFlagBitsEXT severity, VkDebugUtilsMessageTypeFlagsEXT,
    const VkDebugUtilsMessengerCallbackDataEXT* data, void* self) {
  if (printValidationMessage("bounce", severity, data))
    ++static_cast<Context*>(self)->validationErrors_;
  return VK_FALSE;
}

void Context::pickPhysicalDevice(const ContextOptions& options) {
  std::vector<VkPhysicalDevice> devices = physicalDevices(instance_);
  if (devices.empty())
    fail("no Vulkan device found (for the CPU fallback: apt-get install mesa-vulkan-drivers)");
  std::vector<DeviceInfo> infos;
  for (uint32_t i = 0; i < devices.size(); ++i) infos.push_back(describeDevice(devices[i], i));

  uint32_t chosen = 0;
  if (options.deviceIndex) {
    chosen = *options.deviceIndex;
    if (chosen >= devices.size())
      fail("--device {}: only {} Vulkan device(s) (see `bounce info`)", chosen, devices.size());
    if (!infos[chosen].suitable)
      fail("--device {} ({}): unsupported: {}", chosen, infos[chosen].name,
           infos[chosen].unsuitableBecause);
  } else {
    auto best =
        std::max_element(infos.begin(), infos.end(),
                         [](const DeviceInfo& a, const DeviceInfo& b) { return a.rank < b.rank; });
    if (!best->suitable) {
      std::string reasons;
      for (const DeviceInfo& d : infos)
        reasons += fmt::format("\n  {}: {}", d.name, d.unsuitableBecause);
      fail("no Vulkan device meets Bounce's requirements:{}", reasons);
    }
    chosen = best->index;
  }
  physicalDevice_ = devices[chosen];
  info_ = infos[chosen];
  VkPhysicalDeviceProperties props;
  vkGetPhysicalDeviceProperties(physicalDevice_, &props);
  limits_ = props.limits;
  vkGetPhysicalDeviceMemoryProperties(physicalDevice_, &memoryProperties_);
}

void Context::createDevice() {
  queueFamily_ = *findQueueFamily(physicalDevice_, nullptr);
  float priority = 1.0f;
  VkDeviceQueueCreateInfo queueInfo{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
  queueInfo.queueFamilyIndex = queueFamily_;
  queueInfo.queueCount = 1;
  queueInfo.pQueuePriorities = &priority;

  // What an adopted device must have, plus two that Bounce uses when it creates the device.
  api::RequiredDeviceFeatures features;
  features.vulkan12.hostQueryReset = VK_TRUE;
  features.vulkan12.shaderFloat16 = info_.shaderFloat16;

  VkDeviceCreateInfo ci{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO, features.chain()};
  ci.queueCreateInfoCount = 1;
  ci.pQueueCreateInfos = &queueInfo;
  std::vector<const char*> extensions;

  // The hardware tracer's extensions, only where the device has them all (DeviceInfo::
  // hardwareRayTracingUsable): a device without them is created exactly as before.
  const char* rayTracingExtensions[] = {VK_KHR_RAY_TRACING_PIPELINE_EXTENSION_NAME,
                                        VK_KHR_ACCELERATION_STRUCTURE_EXTENSION_NAME,
                                        VK_KHR_DEFERRED_HOST_OPERATIONS_EXTENSION_NAME};
  VkPhysicalDeviceAccelerationStructureFeaturesKHR accelerationStructure{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ACCELERATION_STRUCTURE_FEATURES_KHR};
  VkPhysicalDeviceRayTracingPipelineFeaturesKHR rayTracingPipeline{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_RAY_TRACING_PIPELINE_FEATURES_KHR, &accelerationStructure};
  if (info_.hardwareRayTracingUsable) {
    accelerationStructure.accelerationStructure = VK_TRUE;
    rayTracingPipeline.rayTracingPipeline = VK_TRUE;
    // Ahead of the required chain: features.vulkan13's pNext is the chain's end.
    features.vulkan13.pNext = &rayTracingPipeline;
    extensions.insert(extensions.end(), std::begin(rayTracingExtensions),
                      std::end(rayTracingExtensions));
  }
  // The driver's own statistics of each compute pipeline (registers, spills), asked for with
  // BOUNCE_PIPELINE_STATS=1 (docs/startup.md); else the device is created without them.
  VkPhysicalDevicePipelineExecutablePropertiesFeaturesKHR executableInfo{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PIPELINE_EXECUTABLE_PROPERTIES_FEATURES_KHR};
  const char* statisticsWanted = std::getenv("BOUNCE_PIPELINE_STATS");
  if (statisticsWanted && std::strcmp(statisticsWanted, "0") != 0 &&
      hasDeviceExtension(physicalDevice_, VK_KHR_PIPELINE_EXECUTABLE_PROPERTIES_EXTENSION_NAME)) {
    executableInfo.pipelineExecutableInfo = VK_TRUE;
    executableInfo.pNext = features.vulkan13.pNext;
    features.vulkan13.pNext = &executableInfo;
    extensions.push_back(VK_KHR_PIPELINE_EXECUTABLE_PROPERTIES_EXTENSION_NAME);
    pipelineStatistics_ = true;
  }
  ci.enabledExtensionCount = uint32_t(extensions.size());
  ci.ppEnabledExtensionNames = extensions.data();
  VK_CHECK(vkCreateDevice(physicalDevice_, &ci, nullptr, &device_));
  hardwareRayTracing_ = info_.hardwareRayTracingUsable;
  vkGetDeviceQueue(device_, queueFamily_, 0, &queue_);
  createCommandPoolAndFence();
}

void Context::createCommandPoolAndFence() {
  VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  poolInfo.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
  poolInfo.queueFamilyIndex = queueFamily_;
  VK_CHECK(vkCreateCommandPool(device_, &poolInfo, nullptr, &commandPool_));
  VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  VK_CHECK(vkCreateFence(device_, &fenceInfo, nullptr, &fence_));
}

VkDeviceMemory Context::allocate(const VkMemoryRequirements& req, MemoryUse use,
                                 bool deviceAddress) {
  // Preferred property sets, best first; the first type that the resource accepts wins.
  std::vector<VkMemoryPropertyFlags> preferences;
  const VkMemoryPropertyFlags hostCoherent =
      VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
  switch (use) {
    case MemoryUse::DeviceOnly:
      preferences = {VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, 0};
      break;
    case MemoryUse::Upload:
      preferences = {hostCoherent | VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, hostCoherent};
      break;
    case MemoryUse::Readback:
      preferences = {hostCoherent | VK_MEMORY_PROPERTY_HOST_CACHED_BIT, hostCoherent};
      break;
  }
  uint32_t typeIndex = UINT32_MAX;
  for (VkMemoryPropertyFlags want : preferences) {
    for (uint32_t i = 0; i < memoryProperties_.memoryTypeCount && typeIndex == UINT32_MAX; ++i)
      if ((req.memoryTypeBits & (1u << i)) &&
          (memoryProperties_.memoryTypes[i].propertyFlags & want) == want)
        typeIndex = i;
    if (typeIndex != UINT32_MAX) break;
  }
  if (typeIndex == UINT32_MAX) fail("no Vulkan memory type fits a {}-byte allocation", req.size);

  VkMemoryAllocateFlagsInfo flags{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_FLAGS_INFO};
  flags.flags = VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT;
  VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, deviceAddress ? &flags : nullptr};
  ai.allocationSize = req.size;
  ai.memoryTypeIndex = typeIndex;
  if (memoryLimitBytes_ != 0 && liveBytes_ + req.size > memoryLimitBytes_)
    failOutOfMemory(req.size, typeIndex,
                    fmt::format("the --device-memory-limit of {:.1f} MiB",
                                double(memoryLimitBytes_) / (1 << 20)));
  VkDeviceMemory memory = VK_NULL_HANDLE;
  VkResult r = vkAllocateMemory(device_, &ai, nullptr, &memory);
  if (r != VK_SUCCESS) failOutOfMemory(req.size, typeIndex, resultName(r));
  ++allocationCount_;
  ++liveAllocations_;
  liveBytes_ += req.size;
  allocationSizes()[memory] = req.size;
  return memory;
}

// What a user needs to act on: how much was asked for, how much Bounce already holds, how big the
// heap is, and what to change.
void Context::failOutOfMemory(VkDeviceSize size, uint32_t typeIndex,
                              const std::string& cause) const {
  const uint32_t heap = memoryProperties_.memoryTypes[typeIndex].heapIndex;
  const double mib = double(1 << 20);
  fail(
      "out of GPU memory on {}: an allocation of {:.1f} MiB failed ({}). Bounce already held "
      "{:.1f} MiB in {} allocations, so it needed at least {:.1f} MiB; memory heap {} of the "
      "device has {:.1f} MiB. Use a smaller --res, the mobile preset or a smaller scene",
      info_.name, double(size) / mib, cause, double(liveBytes_) / mib, liveAllocations_,
      double(liveBytes_ + size) / mib, heap,
      double(memoryProperties_.memoryHeaps[heap].size) / mib);
}

void Context::free(VkDeviceMemory memory) {
  if (!memory) return;
  auto it = allocationSizes().find(memory);
  if (it != allocationSizes().end()) {
    liveBytes_ -= it->second;
    --liveAllocations_;
    allocationSizes().erase(it);
  }
  vkFreeMemory(device_, memory, nullptr);
}

void Context::submitAndWait(const std::function<void(VkCommandBuffer)>& record) {
  VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  ai.commandPool = commandPool_;
  ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  ai.commandBufferCount = 1;
  VkCommandBuffer cmd;
  VK_CHECK(vkAllocateCommandBuffers(device_, &ai, &cmd));
  VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  VK_CHECK(vkBeginCommandBuffer(cmd, &bi));
  record(cmd);
  VK_CHECK(vkEndCommandBuffer(cmd));
  VkCommandBufferSubmitInfo cbInfo{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
  cbInfo.commandBuffer = cmd;
  VkSubmitInfo2 submit{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
  submit.commandBufferInfoCount = 1;
  submit.pCommandBufferInfos = &cbInfo;
  VK_CHECK(vkResetFences(device_, 1, &fence_));
  VK_CHECK(vkQueueSubmit2(queue_, 1, &submit, fence_));
  VkResult waited = vkWaitForFences(device_, 1, &fence_, VK_TRUE, UINT64_MAX);
  vkFreeCommandBuffers(device_, commandPool_, 1, &cmd);
  VK_CHECK(waited);
}

void Context::setObjectName(uint64_t handle, VkObjectType type, const std::string& name) {
  if (!debugUtils_ || !validationEnabled_) return;
  auto setName = reinterpret_cast<PFN_vkSetDebugUtilsObjectNameEXT>(
      vkGetInstanceProcAddr(instance_, "vkSetDebugUtilsObjectNameEXT"));
  if (!setName) return;
  VkDebugUtilsObjectNameInfoEXT info{VK_STRUCTURE_TYPE_DEBUG_UTILS_OBJECT_NAME_INFO_EXT};
  info.objectType = type;
  info.objectHandle = handle;
  info.pObjectName = name.c_str();
  setName(device_, &info);
}

void Context::beginDebugLabel(VkCommandBuffer cmd, const std::string& name) const {
  if (!beginLabel_ || !endLabel_) return;
  VkDebugUtilsLabelEXT label{VK_STRUCTURE_TYPE_DEBUG_UTILS_LABEL_EXT};
  label.pLabelName = name.c_str();
  beginLabel_(cmd, &label);
}

void Context::endDebugLabel(VkCommandBuffer cmd) const {
  if (beginLabel_ && endLabel_) endLabel_(cmd);
}

const char* resultName(VkResult r) {
  switch (r) {
    case VK_SUCCESS:
      return "VK_SUCCESS";
    case VK_NOT_READY:
      return "VK_NOT_READY";
    case VK_TIMEOUT:
      return "VK_TIMEOUT";
    case VK_ERROR_OUT_OF_HOST_MEMORY:
      return "VK_ERROR_OUT_OF_HOST_MEMORY";
    case VK_ERROR_OUT_OF_DEVICE_MEMORY:
      return "VK_ERROR_OUT_OF_DEVICE_MEMORY";
    case VK_ERROR_INITIALIZATION_FAILED:
      return "VK_ERROR_INITIALIZATION_FAILED";
    case VK_ERROR_DEVICE_LOST:
      return "VK_ERROR_DEVICE_LOST";
    case VK_ERROR_LAYER_NOT_PRESENT:
      return "VK_ERROR_LAYER_NOT_PRESENT";
    case VK_ERROR_EXTENSION_NOT_PRESENT:
      return "VK_ERROR_EXTENSION_NOT_PRESENT";
    case VK_ERROR_FEATURE_NOT_PRESENT:
      return "VK_ERROR_FEATURE_NOT_PRESENT";
    case VK_ERROR_INCOMPATIBLE_DRIVER:
      return "VK_ERROR_INCOMPATIBLE_DRIVER";
    default:
      return "VkResult error";
  }
}

int deviceTypeRank(VkPhysicalDeviceType type) {
  switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU:
      return 4;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU:
      return 3;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU:
      return 2;
    case VK_PHYSICAL_DEVICE_TYPE_CPU:
      return 1;
    default:
      return 0;
  }
}

}  // namespace bounce::vk
