// The Vulkan side of the hardware tracer (VK_KHR_ray_tracing_pipeline with
// VK_KHR_acceleration_structure): the extension's entry points, the device's ray-tracing
// limits, acceleration-structure storage and a ray-tracing pipeline with its shader binding
// table. Usable only on a Context with hardwareRayTracing() (Context enables the extensions
// where the device has them); the constructors throw bounce::Error elsewhere.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "vk/context.h"
#include "vk/pipeline.h"
#include "vk/resources.h"

namespace bounce::vk {

// "hardware ray tracing (VK_KHR_ray_tracing_pipeline) is not supported on <device>": the error
// every hardware-tracing entry point gives on a Context without hardwareRayTracing().
std::string hardwareRayTracingUnsupported(const Context& context);

// Extension functions are not exported by the loader: fetched with vkGetDeviceProcAddr.
struct RayTracingApi {
  explicit RayTracingApi(const Context& context);
  PFN_vkGetAccelerationStructureBuildSizesKHR getBuildSizes = nullptr;
  PFN_vkCreateAccelerationStructureKHR createAccelerationStructure = nullptr;
  PFN_vkDestroyAccelerationStructureKHR destroyAccelerationStructure = nullptr;
  PFN_vkGetAccelerationStructureDeviceAddressKHR getAccelerationStructureAddress = nullptr;
  PFN_vkCmdBuildAccelerationStructuresKHR cmdBuildAccelerationStructures = nullptr;
  PFN_vkCreateRayTracingPipelinesKHR createRayTracingPipelines = nullptr;
  PFN_vkGetRayTracingShaderGroupHandlesKHR getShaderGroupHandles = nullptr;
  PFN_vkCmdTraceRaysKHR cmdTraceRays = nullptr;
};

// The limits the tracer's layouts depend on (VkPhysicalDeviceRayTracingPipelinePropertiesKHR,
// VkPhysicalDeviceAccelerationStructurePropertiesKHR).
struct RayTracingProperties {
  uint32_t shaderGroupHandleSize = 0;
  uint32_t shaderGroupHandleAlignment = 0;
  uint32_t shaderGroupBaseAlignment = 0;
  uint32_t maxRayRecursionDepth = 0;
  uint32_t maxRayDispatchInvocationCount = 0;
  uint32_t minScratchOffsetAlignment = 0;  // minAccelerationStructureScratchOffsetAlignment
  uint64_t maxPrimitiveCount = 0;
  uint64_t maxGeometryCount = 0;
  uint64_t maxInstanceCount = 0;
};
RayTracingProperties rayTracingProperties(const Context& context);

// `value` rounded up to a multiple of `alignment` (a power of two, or 0/1 for none).
constexpr uint64_t alignUp(uint64_t value, uint64_t alignment) {
  return alignment > 1 ? (value + alignment - 1) & ~(alignment - 1) : value;
}

// A buffer whose device address is rounded up to `alignment` (dedicated allocations are
// aligned to the buffer's memory requirements only, which need not cover the scratch offset
// or shader-binding-table alignment): `address()` is the aligned start, `size` bytes usable.
class AlignedBuffer {
 public:
  AlignedBuffer() = default;
  AlignedBuffer(Context& context, VkDeviceSize size, VkDeviceSize alignment,
                VkBufferUsageFlags usage, MemoryUse use, const std::string& name);
  VkDeviceAddress address() const { return buffer_.address() + offset_; }
  VkDeviceSize offset() const { return offset_; }
  // Host pointer to the aligned start (Upload buffers).
  void* mapped() const { return static_cast<std::byte*>(buffer_.mapped()) + offset_; }
  const Buffer& buffer() const { return buffer_; }

 private:
  Buffer buffer_;
  VkDeviceSize offset_ = 0;
};

// Acceleration structures placed in one buffer at 256-byte offsets (the spec's required
// alignment of an acceleration structure's offset).
class AccelerationStructureSet {
 public:
  AccelerationStructureSet(Context& context, VkAccelerationStructureTypeKHR type,
                           const std::vector<VkDeviceSize>& sizes, const std::string& name);
  ~AccelerationStructureSet();
  AccelerationStructureSet(const AccelerationStructureSet&) = delete;
  AccelerationStructureSet& operator=(const AccelerationStructureSet&) = delete;

  size_t size() const { return handles_.size(); }
  VkAccelerationStructureKHR handle(size_t i) const { return handles_[i]; }
  VkDeviceAddress address(size_t i) const { return addresses_[i]; }
  VkDeviceSize bytes() const { return storage_.size(); }

 private:
  Context& context_;
  RayTracingApi api_;
  Buffer storage_;
  std::vector<VkAccelerationStructureKHR> handles_;
  std::vector<VkDeviceAddress> addresses_;
};

// A ray-tracing pipeline of one ray-generation shader, miss shaders and triangle hit groups,
// with its shader binding table (SBT) in one host-visible buffer. Shaders are embedded SPIR-V
// named with their extension, e.g. "rt/hw_closest_hit.rchit". Push constants are visible to
// every ray-tracing stage.
class RayTracingPipeline {
 public:
  struct HitGroup {
    std::string closestHit;  // empty: none
    std::string anyHit;      // empty: none
  };
  RayTracingPipeline(Context& context, const std::string& raygen,
                     const std::vector<std::string>& misses, const std::vector<HitGroup>& hitGroups,
                     const std::vector<const DescriptorSetLayout*>& setLayouts,
                     uint32_t pushConstantBytes);
  ~RayTracingPipeline();
  RayTracingPipeline(const RayTracingPipeline&) = delete;
  RayTracingPipeline& operator=(const RayTracingPipeline&) = delete;

  static constexpr VkShaderStageFlags kStages =
      VK_SHADER_STAGE_RAYGEN_BIT_KHR | VK_SHADER_STAGE_MISS_BIT_KHR |
      VK_SHADER_STAGE_CLOSEST_HIT_BIT_KHR | VK_SHADER_STAGE_ANY_HIT_BIT_KHR;

  void bind(VkCommandBuffer cmd, const std::vector<VkDescriptorSet>& sets) const;
  template <typename T>
  void push(VkCommandBuffer cmd, const T& constants) const {
    vkCmdPushConstants(cmd, layout_, kStages, 0, sizeof(T), &constants);
  }
  // One ray-generation invocation per (x, y) of width x height.
  void traceRays(VkCommandBuffer cmd, uint32_t width, uint32_t height) const;
  VkDeviceSize sbtBytes() const { return sbt_.buffer().size(); }

 private:
  Context& context_;
  RayTracingApi api_;
  VkPipelineLayout layout_ = VK_NULL_HANDLE;
  VkPipeline pipeline_ = VK_NULL_HANDLE;
  AlignedBuffer sbt_;
  VkStridedDeviceAddressRegionKHR raygenRegion_{}, missRegion_{}, hitRegion_{}, callableRegion_{};
};

}  // namespace bounce::vk
