#include "vk/ray_tracing.h"

#include <cstring>

#include "vk/check.h"

namespace bounce::vk {

namespace {

void requireHardwareRayTracing(const Context& context) {
  if (!context.hardwareRayTracing()) fail("{}", hardwareRayTracingUnsupported(context));
}

template <typename F>
F deviceFunction(const Context& context, const char* name) {
  auto f = reinterpret_cast<F>(vkGetDeviceProcAddr(context.device(), name));
  if (!f)
    fail("{}: the driver of {} does not export {}", "hardware ray tracing", context.info().name,
         name);
  return f;
}

// The spec requires an acceleration structure's offset in its buffer to be a multiple of 256.
constexpr VkDeviceSize kAccelerationStructureAlignment = 256;

}  // namespace

std::string hardwareRayTracingUnsupported(const Context& context) {
  return fmt::format("hardware ray tracing (VK_KHR_ray_tracing_pipeline) is not supported on {}",
                     context.info().name);
}

RayTracingApi::RayTracingApi(const Context& context) {
  requireHardwareRayTracing(context);
  getBuildSizes = deviceFunction<PFN_vkGetAccelerationStructureBuildSizesKHR>(
      context, "vkGetAccelerationStructureBuildSizesKHR");
  createAccelerationStructure = deviceFunction<PFN_vkCreateAccelerationStructureKHR>(
      context, "vkCreateAccelerationStructureKHR");
  destroyAccelerationStructure = deviceFunction<PFN_vkDestroyAccelerationStructureKHR>(
      context, "vkDestroyAccelerationStructureKHR");
  getAccelerationStructureAddress = deviceFunction<PFN_vkGetAccelerationStructureDeviceAddressKHR>(
      context, "vkGetAccelerationStructureDeviceAddressKHR");
  cmdBuildAccelerationStructures = deviceFunction<PFN_vkCmdBuildAccelerationStructuresKHR>(
      context, "vkCmdBuildAccelerationStructuresKHR");
  createRayTracingPipelines =
      deviceFunction<PFN_vkCreateRayTracingPipelinesKHR>(context, "vkCreateRayTracingPipelinesKHR");
  getShaderGroupHandles = deviceFunction<PFN_vkGetRayTracingShaderGroupHandlesKHR>(
      context, "vkGetRayTracingShaderGroupHandlesKHR");
  cmdTraceRays = deviceFunction<PFN_vkCmdTraceRaysKHR>(context, "vkCmdTraceRaysKHR");
}

RayTracingProperties rayTracingProperties(const Context& context) {
  requireHardwareRayTracing(context);
  VkPhysicalDeviceAccelerationStructurePropertiesKHR as{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ACCELERATION_STRUCTURE_PROPERTIES_KHR};
  VkPhysicalDeviceRayTracingPipelinePropertiesKHR rt{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_RAY_TRACING_PIPELINE_PROPERTIES_KHR, &as};
  VkPhysicalDeviceProperties2 p2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &rt};
  vkGetPhysicalDeviceProperties2(context.physicalDevice(), &p2);
  RayTracingProperties p;
  p.shaderGroupHandleSize = rt.shaderGroupHandleSize;
  p.shaderGroupHandleAlignment = rt.shaderGroupHandleAlignment;
  p.shaderGroupBaseAlignment = rt.shaderGroupBaseAlignment;
  p.maxRayRecursionDepth = rt.maxRayRecursionDepth;
  p.maxRayDispatchInvocationCount = rt.maxRayDispatchInvocationCount;
  p.minScratchOffsetAlignment = as.minAccelerationStructureScratchOffsetAlignment;
  p.maxPrimitiveCount = as.maxPrimitiveCount;
  p.maxGeometryCount = as.maxGeometryCount;
  p.maxInstanceCount = as.maxInstanceCount;
  return p;
}

AlignedBuffer::AlignedBuffer(Context& context, VkDeviceSize size, VkDeviceSize alignment,
                             VkBufferUsageFlags usage, MemoryUse use, const std::string& name)
    : buffer_(context, size + (alignment > 1 ? alignment : 0), usage, use, name) {
  offset_ = alignUp(buffer_.address(), alignment) - buffer_.address();
}

AccelerationStructureSet::AccelerationStructureSet(Context& context,
                                                   VkAccelerationStructureTypeKHR type,
                                                   const std::vector<VkDeviceSize>& sizes,
                                                   const std::string& name)
    : context_(context), api_(context) {
  std::vector<VkDeviceSize> offsets;
  VkDeviceSize total = 0;
  for (VkDeviceSize s : sizes) {
    offsets.push_back(total);
    total = alignUp(total + s, kAccelerationStructureAlignment);
  }
  storage_ =
      Buffer(context, std::max<VkDeviceSize>(total, kAccelerationStructureAlignment),
             VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_STORAGE_BIT_KHR, MemoryUse::DeviceOnly, name);
  for (size_t i = 0; i < sizes.size(); ++i) {
    VkAccelerationStructureCreateInfoKHR ci{
        VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_CREATE_INFO_KHR};
    ci.buffer = storage_.handle();
    ci.offset = offsets[i];
    ci.size = sizes[i];
    ci.type = type;
    VkAccelerationStructureKHR handle = VK_NULL_HANDLE;
    VK_CHECK(api_.createAccelerationStructure(context.device(), &ci, nullptr, &handle));
    handles_.push_back(handle);
    VkAccelerationStructureDeviceAddressInfoKHR ai{
        VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_DEVICE_ADDRESS_INFO_KHR};
    ai.accelerationStructure = handle;
    addresses_.push_back(api_.getAccelerationStructureAddress(context.device(), &ai));
  }
}

AccelerationStructureSet::~AccelerationStructureSet() {
  for (VkAccelerationStructureKHR h : handles_)
    api_.destroyAccelerationStructure(context_.device(), h, nullptr);
}

RayTracingPipeline::RayTracingPipeline(Context& context, const std::string& raygen,
                                       const std::vector<std::string>& misses,
                                       const std::vector<HitGroup>& hitGroups,
                                       const std::vector<const DescriptorSetLayout*>& setLayouts,
                                       uint32_t pushConstantBytes)
    : context_(context), api_(context) {
  // Stages, then groups in SBT order: raygen, misses, hit groups.
  std::vector<VkShaderModule> modules;
  std::vector<VkPipelineShaderStageCreateInfo> stages;
  auto addStage = [&](const std::string& shader, VkShaderStageFlagBits stage) {
    modules.push_back(createShaderModule(context, shader));
    VkPipelineShaderStageCreateInfo s{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
    s.stage = stage;
    s.module = modules.back();
    s.pName = "main";
    stages.push_back(s);
    return uint32_t(stages.size() - 1);
  };
  std::vector<VkRayTracingShaderGroupCreateInfoKHR> groups;
  auto general = [&](uint32_t stage) {
    VkRayTracingShaderGroupCreateInfoKHR g{
        VK_STRUCTURE_TYPE_RAY_TRACING_SHADER_GROUP_CREATE_INFO_KHR};
    g.type = VK_RAY_TRACING_SHADER_GROUP_TYPE_GENERAL_KHR;
    g.generalShader = stage;
    g.closestHitShader = VK_SHADER_UNUSED_KHR;
    g.anyHitShader = VK_SHADER_UNUSED_KHR;
    g.intersectionShader = VK_SHADER_UNUSED_KHR;
    groups.push_back(g);
  };
  general(addStage(raygen, VK_SHADER_STAGE_RAYGEN_BIT_KHR));
  for (const std::string& miss : misses) general(addStage(miss, VK_SHADER_STAGE_MISS_BIT_KHR));
  for (const HitGroup& hit : hitGroups) {
    VkRayTracingShaderGroupCreateInfoKHR g{
        VK_STRUCTURE_TYPE_RAY_TRACING_SHADER_GROUP_CREATE_INFO_KHR};
    g.type = VK_RAY_TRACING_SHADER_GROUP_TYPE_TRIANGLES_HIT_GROUP_KHR;
    g.generalShader = VK_SHADER_UNUSED_KHR;
    g.closestHitShader = hit.closestHit.empty()
                             ? VK_SHADER_UNUSED_KHR
                             : addStage(hit.closestHit, VK_SHADER_STAGE_CLOSEST_HIT_BIT_KHR);
    g.anyHitShader = hit.anyHit.empty() ? VK_SHADER_UNUSED_KHR
                                        : addStage(hit.anyHit, VK_SHADER_STAGE_ANY_HIT_BIT_KHR);
    g.intersectionShader = VK_SHADER_UNUSED_KHR;
    groups.push_back(g);
  }

  layout_ = createPipelineLayout(context, setLayouts, pushConstantBytes, kStages);

  VkRayTracingPipelineCreateInfoKHR ci{VK_STRUCTURE_TYPE_RAY_TRACING_PIPELINE_CREATE_INFO_KHR};
  ci.stageCount = uint32_t(stages.size());
  ci.pStages = stages.data();
  ci.groupCount = uint32_t(groups.size());
  ci.pGroups = groups.data();
  ci.maxPipelineRayRecursionDepth = 1;  // raygen traces; hit and miss shaders do not
  ci.layout = layout_;
  VkResult r = api_.createRayTracingPipelines(context.device(), VK_NULL_HANDLE, VK_NULL_HANDLE, 1,
                                              &ci, nullptr, &pipeline_);
  for (VkShaderModule m : modules) vkDestroyShaderModule(context.device(), m, nullptr);
  if (r != VK_SUCCESS) fail("creating ray-tracing pipeline '{}' failed: {}", raygen, resultName(r));
  context.setObjectName(uint64_t(pipeline_), VK_OBJECT_TYPE_PIPELINE, raygen);

  // The SBT: each region starts at a multiple of shaderGroupBaseAlignment; records are handles
  // (no shader record data) padded to shaderGroupHandleAlignment; the raygen region's size
  // must equal its stride.
  const RayTracingProperties p = rayTracingProperties(context);
  const VkDeviceSize handleSize = p.shaderGroupHandleSize;
  const VkDeviceSize recordStride = alignUp(handleSize, p.shaderGroupHandleAlignment);
  const VkDeviceSize base = p.shaderGroupBaseAlignment;
  const VkDeviceSize raygenStride = alignUp(recordStride, base);
  const VkDeviceSize raygenBytes = raygenStride;
  const VkDeviceSize missBytes = alignUp(misses.size() * recordStride, base);
  const VkDeviceSize hitBytes = alignUp(hitGroups.size() * recordStride, base);
  sbt_ = AlignedBuffer(context, raygenBytes + missBytes + hitBytes, base,
                       VK_BUFFER_USAGE_SHADER_BINDING_TABLE_BIT_KHR, MemoryUse::Upload,
                       raygen + ".sbt");
  std::vector<uint8_t> handles(groups.size() * handleSize);
  VK_CHECK(api_.getShaderGroupHandles(context.device(), pipeline_, 0, uint32_t(groups.size()),
                                      handles.size(), handles.data()));
  auto* sbt = static_cast<uint8_t*>(sbt_.mapped());
  std::memset(sbt, 0, raygenBytes + missBytes + hitBytes);
  auto copyHandle = [&](size_t group, VkDeviceSize at) {
    std::memcpy(sbt + at, handles.data() + group * handleSize, handleSize);
  };
  copyHandle(0, 0);
  for (size_t i = 0; i < misses.size(); ++i) copyHandle(1 + i, raygenBytes + i * recordStride);
  for (size_t i = 0; i < hitGroups.size(); ++i)
    copyHandle(1 + misses.size() + i, raygenBytes + missBytes + i * recordStride);
  raygenRegion_ = {sbt_.address(), raygenStride, raygenBytes};
  missRegion_ = {sbt_.address() + raygenBytes, recordStride, missBytes};
  hitRegion_ = {sbt_.address() + raygenBytes + missBytes, recordStride, hitBytes};
  if (misses.empty()) missRegion_ = {};
  if (hitGroups.empty()) hitRegion_ = {};
}

RayTracingPipeline::~RayTracingPipeline() {
  vkDestroyPipeline(context_.device(), pipeline_, nullptr);
  vkDestroyPipelineLayout(context_.device(), layout_, nullptr);
}

void RayTracingPipeline::bind(VkCommandBuffer cmd, const std::vector<VkDescriptorSet>& sets) const {
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_RAY_TRACING_KHR, pipeline_);
  if (!sets.empty())
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_RAY_TRACING_KHR, layout_, 0,
                            uint32_t(sets.size()), sets.data(), 0, nullptr);
}

void RayTracingPipeline::traceRays(VkCommandBuffer cmd, uint32_t width, uint32_t height) const {
  api_.cmdTraceRays(cmd, &raygenRegion_, &missRegion_, &hitRegion_, &callableRegion_, width, height,
                    1);
}

}  // namespace bounce::vk
