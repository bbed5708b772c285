// The Vulkan device Bounce runs on: instance (optionally with validation), physical-device
// choice (a discrete GPU first, lavapipe as the fallback), one queue that does compute and
// graphics, memory allocation, one-shot command submission. Fully headless: no surface, no
// window-system extension. Or the host's device, adopted (bring your own device,
// include/bounce/external_device.h): checked against the same requirements, never destroyed.
#pragma once
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

namespace bounce::vk {

// What `bounce info` prints, and what device choice looks at.
struct DeviceInfo {
  uint32_t index = 0;
  std::string name;
  std::string type;  // "discrete", "integrated", "cpu", ...
  std::string driver;
  uint32_t apiVersion = 0;
  bool suitable = false;
  std::string unsuitableBecause;  // empty when suitable
  uint32_t subgroupSize = 0;
  uint64_t maxStorageBufferRange = 0;
  uint32_t maxPushConstantsSize = 0;
  uint32_t maxComputeWorkGroupInvocations = 0;
  uint64_t deviceLocalBytes = 0;
  float timestampPeriodNs = 0.0f;
  bool timestampsOnComputeQueue = false;
  bool shaderFloat16 = false;
  bool rayTracingPipeline = false;  // optional back end, not required
  // VK_KHR_ray_tracing_pipeline with VK_KHR_acceleration_structure and
  // VK_KHR_deferred_host_operations and their features: what Context enables for the hardware
  // tracer (src/rt/hardware_tracer.h) when it creates the device.
  bool hardwareRayTracingUsable = false;
  bool rayQuery = false;           // optional back end, not required
  bool cooperativeMatrix = false;  // optional, not required
  int rank = 0;                    // higher is preferred
};

struct ContextOptions {
  std::optional<uint32_t> deviceIndex;  // --device N; else BOUNCE_DEVICE; else the best ranked
  bool validation = false;              // Khronos validation layer; errors are counted
  bool synchronizationValidation = false;
  // --device-memory-limit: allocations that would take Bounce's live device memory beyond this
  // many bytes fail as if the device had run out, so that a preset can be checked against a
  // smaller GPU's memory (and the out-of-memory path tested on any device). 0: no limit.
  uint64_t memoryLimitBytes = 0;
};

// The host's Vulkan objects for Context(const AdoptedDevice&). `createInfo`, when given, is what
// `device` was created with: it lets the checks see which features are enabled (Vulkan has no
// query for that), and is read only inside the constructor.
struct AdoptedDevice {
  VkInstance instance = VK_NULL_HANDLE;
  VkPhysicalDevice physicalDevice = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  VkQueue queue = VK_NULL_HANDLE;
  uint32_t queueFamily = 0;
  const VkDeviceCreateInfo* createInfo = nullptr;
};

enum class MemoryUse {
  DeviceOnly,  // fastest for the GPU; filled by copies or shaders
  Upload,      // host writes, GPU reads (mapped)
  Readback,    // GPU writes, host reads (mapped, cached where possible)
};

class Context {
 public:
  explicit Context(const ContextOptions& options = {});
  // Runs on the host's device. Throws bounce::Error naming the device and every requirement it
  // misses (the features createDevice() enables, a queue with graphics and compute). Creates
  // only its own command pool and fence; the destructor waits for the queue, not the device,
  // and destroys nothing it adopted. No validation layer or debug labels of its own.
  explicit Context(const AdoptedDevice& device);
  ~Context();
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  // Enumerates devices on a temporary instance without creating a device.
  static std::vector<DeviceInfo> listDevices();

  VkInstance instance() const { return instance_; }
  VkPhysicalDevice physicalDevice() const { return physicalDevice_; }
  VkDevice device() const { return device_; }
  bool adopted() const { return adopted_; }
  VkQueue queue() const { return queue_; }
  uint32_t queueFamily() const { return queueFamily_; }
  const DeviceInfo& info() const { return info_; }
  const VkPhysicalDeviceLimits& limits() const { return limits_; }
  // True when this device was created with the ray-tracing pipeline, acceleration structures
  // and deferred host operations enabled (DeviceInfo::hardwareRayTracingUsable; never for an
  // adopted device, whose enabled extensions Bounce cannot know).
  bool hardwareRayTracing() const { return hardwareRayTracing_; }
  // Pipelines are created with the driver's statistics captured and print them
  // (BOUNCE_PIPELINE_STATS=1 on a device with VK_KHR_pipeline_executable_properties).
  bool pipelineStatistics() const { return pipelineStatistics_; }

  // Allocates dedicated memory for a resource; counted so tests can check that frames do
  // not allocate (DESIGN.md §1).
  VkDeviceMemory allocate(const VkMemoryRequirements& requirements, MemoryUse use,
                          bool deviceAddress);
  void free(VkDeviceMemory memory);
  uint64_t allocationCount() const { return allocationCount_; }
  uint64_t liveAllocationBytes() const { return liveBytes_; }
  uint64_t liveAllocationCount() const { return liveAllocations_; }

  // Waits until Bounce's work on the GPU is done: the whole device when Bounce created it, its
  // queue when adopted (waiting for the host's device would need the host's other queues).
  void waitIdle() const;

  // Records commands with `record`, submits them and waits. For set-up and tests; frames use
  // their own command buffers.
  void submitAndWait(const std::function<void(VkCommandBuffer)>& record);

  // Validation messages of error severity seen so far (0 when validation is off).
  uint32_t validationErrorCount() const { return validationErrors_; }
  bool validationEnabled() const { return validationEnabled_; }

  void setObjectName(uint64_t handle, VkObjectType type, const std::string& name);
  // Debug-utils labels around a command range (shown by validation messages and GPU
  // debuggers); no-ops when VK_EXT_debug_utils is missing.
  void beginDebugLabel(VkCommandBuffer cmd, const std::string& name) const;
  void endDebugLabel(VkCommandBuffer cmd) const;

 private:
  void createInstance(const ContextOptions& options);
  void pickPhysicalDevice(const ContextOptions& options);
  void createDevice();
  void createCommandPoolAndFence();
  [[noreturn]] void failOutOfMemory(VkDeviceSize size, uint32_t typeIndex,
                                    const std::string& cause) const;
  static VKAPI_ATTR VkBool32 VKAPI_CALL onValidationMessage(
      VkDebugUtilsMessageSeverityFlagBitsEXT severity, VkDebugUtilsMessageTypeFlagsEXT types,
      const VkDebugUtilsMessengerCallbackDataEXT* data, void* self);

  VkInstance instance_ = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
  VkPhysicalDevice physicalDevice_ = VK_NULL_HANDLE;
  VkDevice device_ = VK_NULL_HANDLE;
  VkQueue queue_ = VK_NULL_HANDLE;
  uint32_t queueFamily_ = 0;
  VkCommandPool commandPool_ = VK_NULL_HANDLE;
  VkFence fence_ = VK_NULL_HANDLE;
  VkPhysicalDeviceMemoryProperties memoryProperties_{};
  VkPhysicalDeviceLimits limits_{};
  DeviceInfo info_;
  bool adopted_ = false;  // instance_, device_ and queue_ belong to the host
  bool validationEnabled_ = false;
  bool hardwareRayTracing_ = false;
  bool pipelineStatistics_ = false;
  bool debugUtils_ = false;
  PFN_vkCmdBeginDebugUtilsLabelEXT beginLabel_ = nullptr;
  PFN_vkCmdEndDebugUtilsLabelEXT endLabel_ = nullptr;
  uint32_t validationErrors_ = 0;
  uint64_t allocationCount_ = 0;
  uint64_t liveBytes_ = 0;
  uint64_t liveAllocations_ = 0;
  uint64_t memoryLimitBytes_ = 0;  // ContextOptions::memoryLimitBytes
};

// Reads BOUNCE_VALIDATE / BOUNCE_DEVICE / BOUNCE_DEVICE_MEMORY_LIMIT (MiB) from the environment
// into options (tests and CLI).
ContextOptions contextOptionsFromEnvironment(ContextOptions options = {});

}  // namespace bounce::vk
