#include "rt/hardware_tracer.h"

#include <algorithm>
#include <chrono>
#include <cstring>

#include "core/error.h"
#include "shared/hardware_trace.h"
#include "vk/check.h"
#include "vk/gpu_timer.h"
#include "vk/memory_barrier.h"

namespace bounce {

namespace {

using Clock = std::chrono::steady_clock;

// Scratch memory for the BLAS builds of one command: builds are batched so that their scratch
// regions together stay under this (or the largest single build's need), with a barrier between
// batches that reuse the memory. A scene of 10^6 triangles needs some tens of MiB.
constexpr VkDeviceSize kScratchBudget = VkDeviceSize(256) << 20;

// Build inputs (vertex, index and instance data) need this usage besides device addresses.
constexpr VkBufferUsageFlags kBuildInput =
    VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_BUILD_INPUT_READ_ONLY_BIT_KHR;

// The barrier every build needs before it: earlier transfer writes (the inputs' uploads) and
// earlier builds (scratch reuse, a BLAS that the TLAS references) complete and visible.
void barrierBeforeBuild(VkCommandBuffer cmd) {
  vk::memoryBarrier(
      cmd,
      VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT |
          VK_PIPELINE_STAGE_2_ACCELERATION_STRUCTURE_BUILD_BIT_KHR,
      VK_ACCESS_2_TRANSFER_WRITE_BIT | VK_ACCESS_2_ACCELERATION_STRUCTURE_WRITE_BIT_KHR,
      VK_PIPELINE_STAGE_2_ACCELERATION_STRUCTURE_BUILD_BIT_KHR,
      VK_ACCESS_2_ACCELERATION_STRUCTURE_READ_BIT_KHR |
          VK_ACCESS_2_ACCELERATION_STRUCTURE_WRITE_BIT_KHR | VK_ACCESS_2_SHADER_READ_BIT);
}

VkTransformMatrixKHR transformOf(const gpu::GpuInstance& instance) {
  // VkTransformMatrixKHR is a row-major 3x4 matrix: the three rows of GpuInstance's
  // objectToWorld (xyz the linear part, w the translation).
  VkTransformMatrixKHR m{};
  for (int row = 0; row < 3; ++row)
    for (int col = 0; col < 4; ++col) m.matrix[row][col] = instance.objectToWorld[row][col];
  return m;
}

double secondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

}  // namespace

std::string HardwareTracer::unsupportedMessage(const vk::Context& context) {
  return vk::hardwareRayTracingUnsupported(context);
}

HardwareTracer::HardwareTracer(vk::Context& context, const GpuScene& scene)
    : context_(context),
      scene_(scene),
      api_(context),  // throws unsupportedMessage() without hardware ray tracing
      properties_(vk::rayTracingProperties(context)) {
  const auto start = Clock::now();
  buildBlas(scene);
  buildTlas(scene);
  writeDescriptors();
  stats_.buildSeconds = secondsSince(start);
}

HardwareTracer::~HardwareTracer() {
  if (pool_) vkDestroyDescriptorPool(context_.device(), pool_, nullptr);
}

void HardwareTracer::buildBlas(const GpuScene& scene) {
  const rt::SceneBvh& bvh = scene.bvh();
  const std::vector<gpu::GpuMaterial>& materials = scene.textures().materials;
  // The scene's own streams, copied into buffers the builds may read (GpuScene's lack the
  // build-input usage). Indices are relative to each geometry's vertexOffset, which the
  // geometry's vertexData address absorbs.
  auto upload = [&](const auto& items, const char* name) {
    stats_.inputBytes += items.size() * sizeof(items[0]);
    return vk::uploadVector(context_, std::span(items), kBuildInput, name);
  };
  positions_ = upload(bvh.positions, "hw-tracer.positions");
  indices_ = upload(bvh.indices, "hw-tracer.indices");

  const size_t meshCount = bvh.geometryBase.size();
  struct MeshBuild {
    size_t mesh;
    std::vector<VkAccelerationStructureGeometryKHR> geometries;
    std::vector<VkAccelerationStructureBuildRangeInfoKHR> ranges;
    VkAccelerationStructureBuildGeometryInfoKHR info{};
    VkDeviceSize scratch = 0;
  };
  std::vector<MeshBuild> builds;
  meshBlas_.assign(meshCount, -1);
  std::vector<VkDeviceSize> sizes;
  for (size_t m = 0; m < meshCount; ++m) {
    const uint32_t first = bvh.geometryBase[m];
    const uint32_t end =
        m + 1 < meshCount ? bvh.geometryBase[m + 1] : uint32_t(bvh.geometries.size());
    MeshBuild b;
    b.mesh = m;
    uint64_t triangles = 0;
    for (uint32_t g = first; g < end; ++g) {
      const gpu::GpuGeometry& geometry = bvh.geometries[g];
      // Every geometry, an empty one too (primitiveCount 0), so that gl_GeometryIndexEXT is
      // the geometry's index in its mesh.
      uint32_t maxVertex = 0;
      for (uint32_t i = 0; i < 3 * geometry.triangleCount; ++i)
        maxVertex = std::max(maxVertex, bvh.indices[geometry.firstIndex + i]);
      VkAccelerationStructureGeometryKHR ag{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_KHR};
      ag.geometryType = VK_GEOMETRY_TYPE_TRIANGLES_KHR;
      auto& t = ag.geometry.triangles;
      t.sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_TRIANGLES_DATA_KHR;
      t.vertexFormat = VK_FORMAT_R32G32B32_SFLOAT;
      t.vertexData.deviceAddress =
          positions_.address() + VkDeviceSize(geometry.vertexOffset) * sizeof(glm::vec3);
      t.vertexStride = sizeof(glm::vec3);
      t.maxVertex = maxVertex;
      t.indexType = VK_INDEX_TYPE_UINT32;
      t.indexData.deviceAddress =
          indices_.address() + VkDeviceSize(geometry.firstIndex) * sizeof(uint32_t);
      const gpu::GpuMaterial& material = materials.at(geometry.material);
      const bool alphaTested =
          (material.flags & (gpu::MATERIAL_ALPHA_MASK | gpu::MATERIAL_ALPHA_BLEND)) != 0u;
      ag.flags =
          alphaTested ? VkGeometryFlagsKHR(0) : VkGeometryFlagsKHR(VK_GEOMETRY_OPAQUE_BIT_KHR);
      b.geometries.push_back(ag);
      b.ranges.push_back({geometry.triangleCount, 0, 0, 0});
      triangles += geometry.triangleCount;
    }
    if (triangles == 0) continue;  // no BLAS; the TLAS leaves its instances out
    if (triangles > properties_.maxPrimitiveCount ||
        b.geometries.size() > properties_.maxGeometryCount)
      fail(
          "hardware ray tracing: mesh {} has {} triangles in {} geometries, more than {} allows "
          "({}, {})",
          m, triangles, b.geometries.size(), context_.info().name, properties_.maxPrimitiveCount,
          properties_.maxGeometryCount);
    b.info.sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_GEOMETRY_INFO_KHR;
    b.info.type = VK_ACCELERATION_STRUCTURE_TYPE_BOTTOM_LEVEL_KHR;
    b.info.flags = VK_BUILD_ACCELERATION_STRUCTURE_PREFER_FAST_TRACE_BIT_KHR;
    b.info.mode = VK_BUILD_ACCELERATION_STRUCTURE_MODE_BUILD_KHR;
    b.info.geometryCount = uint32_t(b.geometries.size());
    b.info.pGeometries = b.geometries.data();
    std::vector<uint32_t> counts;
    for (const auto& r : b.ranges) counts.push_back(r.primitiveCount);
    VkAccelerationStructureBuildSizesInfoKHR s{
        VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_SIZES_INFO_KHR};
    api_.getBuildSizes(context_.device(), VK_ACCELERATION_STRUCTURE_BUILD_TYPE_DEVICE_KHR, &b.info,
                       counts.data(), &s);
    b.scratch = vk::alignUp(s.buildScratchSize, properties_.minScratchOffsetAlignment);
    meshBlas_[m] = int64_t(sizes.size());
    sizes.push_back(s.accelerationStructureSize);
    stats_.geometryCount += b.info.geometryCount;
    stats_.triangles += triangles;
    builds.push_back(std::move(b));
  }
  stats_.blasCount = uint32_t(builds.size());
  if (builds.empty()) return;
  blas_ = std::make_unique<vk::AccelerationStructureSet>(
      context_, VK_ACCELERATION_STRUCTURE_TYPE_BOTTOM_LEVEL_KHR, sizes, "hw-tracer.blas");
  stats_.blasBytes = blas_->bytes();

  VkDeviceSize largest = 0, total = 0;
  for (const MeshBuild& b : builds) {
    largest = std::max(largest, b.scratch);
    total += b.scratch;
  }
  const VkDeviceSize scratchBytes = std::max(largest, std::min(total, kScratchBudget));
  vk::AlignedBuffer scratch(context_, scratchBytes, properties_.minScratchOffsetAlignment,
                            VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUse::DeviceOnly,
                            "hw-tracer.blas-scratch");
  stats_.scratchBytes = std::max<uint64_t>(stats_.scratchBytes, scratchBytes);

  vk::GpuTimer timer(context_, 2);
  context_.submitAndWait([&](VkCommandBuffer cmd) {
    timer.reset(cmd);
    timer.begin(cmd, "hw-blas-build");
    size_t next = 0;
    while (next < builds.size()) {
      // One batch: builds whose scratch regions fit side by side.
      std::vector<VkAccelerationStructureBuildGeometryInfoKHR> infos;
      std::vector<const VkAccelerationStructureBuildRangeInfoKHR*> ranges;
      VkDeviceSize offset = 0;
      while (next < builds.size() &&
             (infos.empty() || offset + builds[next].scratch <= scratchBytes)) {
        MeshBuild& b = builds[next];
        b.info.pGeometries = b.geometries.data();
        b.info.dstAccelerationStructure = blas_->handle(size_t(meshBlas_[b.mesh]));
        b.info.scratchData.deviceAddress = scratch.address() + offset;
        offset += b.scratch;
        infos.push_back(b.info);
        ranges.push_back(b.ranges.data());
        ++next;
      }
      barrierBeforeBuild(cmd);
      api_.cmdBuildAccelerationStructures(cmd, uint32_t(infos.size()), infos.data(), ranges.data());
      ++stats_.buildBatches;
    }
    timer.end(cmd);
  });
  std::vector<vk::PassTiming> t = timer.read();
  if (!t.empty()) stats_.blasGpuMilliseconds = t[0].milliseconds;
}

void HardwareTracer::buildTlas(const GpuScene& scene) {
  const rt::SceneBvh& bvh = scene.bvh();
  std::vector<VkAccelerationStructureInstanceKHR> instances;
  if (bvh.instances.size() >= (size_t(1) << 24))
    fail("hardware ray tracing: {} instances, more than the 2^24 a custom index can number",
         bvh.instances.size());
  for (size_t i = 0; i < bvh.instances.size(); ++i) {
    const gpu::GpuInstance& inst = bvh.instances[i];
    if (inst.flags & gpu::GPU_INSTANCE_HIDDEN) continue;
    const int64_t blas = meshBlas_.at(inst.mesh);
    if (blas < 0) continue;
    VkAccelerationStructureInstanceKHR v{};
    v.transform = transformOf(inst);
    v.instanceCustomIndex = uint32_t(i);  // TraceHit::instance
    v.mask = 0xFF;
    v.instanceShaderBindingTableRecordOffset = 0;  // every geometry: hit group 0
    v.flags = VK_GEOMETRY_INSTANCE_TRIANGLE_FACING_CULL_DISABLE_BIT_KHR;
    v.accelerationStructureReference = blas_->address(size_t(blas));
    instances.push_back(v);
  }
  if (instances.size() > properties_.maxInstanceCount)
    fail("hardware ray tracing: {} instances, more than {} allows ({})", instances.size(),
         context_.info().name, properties_.maxInstanceCount);
  stats_.instanceCount = uint32_t(instances.size());
  stats_.inputBytes += instances.size() * sizeof(VkAccelerationStructureInstanceKHR);
  // The instance array must be 16-byte aligned: a dedicated allocation is.
  instances_ =
      vk::uploadVector(context_, std::span<const VkAccelerationStructureInstanceKHR>(instances),
                       kBuildInput, "hw-tracer.instances");

  VkAccelerationStructureGeometryKHR geometry{
      VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_KHR};
  geometry.geometryType = VK_GEOMETRY_TYPE_INSTANCES_KHR;
  geometry.geometry.instances.sType =
      VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_INSTANCES_DATA_KHR;
  geometry.geometry.instances.arrayOfPointers = VK_FALSE;
  geometry.geometry.instances.data.deviceAddress = instances_.address();
  VkAccelerationStructureBuildGeometryInfoKHR info{
      VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_GEOMETRY_INFO_KHR};
  info.type = VK_ACCELERATION_STRUCTURE_TYPE_TOP_LEVEL_KHR;
  info.flags = VK_BUILD_ACCELERATION_STRUCTURE_PREFER_FAST_TRACE_BIT_KHR;
  info.mode = VK_BUILD_ACCELERATION_STRUCTURE_MODE_BUILD_KHR;
  info.geometryCount = 1;
  info.pGeometries = &geometry;
  const uint32_t count = uint32_t(instances.size());
  VkAccelerationStructureBuildSizesInfoKHR sizes{
      VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_SIZES_INFO_KHR};
  api_.getBuildSizes(context_.device(), VK_ACCELERATION_STRUCTURE_BUILD_TYPE_DEVICE_KHR, &info,
                     &count, &sizes);
  tlas_ = std::make_unique<vk::AccelerationStructureSet>(
      context_, VK_ACCELERATION_STRUCTURE_TYPE_TOP_LEVEL_KHR,
      std::vector<VkDeviceSize>{sizes.accelerationStructureSize}, "hw-tracer.tlas");
  stats_.tlasBytes = tlas_->bytes();
  const VkDeviceSize scratchBytes =
      std::max<VkDeviceSize>(sizes.buildScratchSize, properties_.minScratchOffsetAlignment);
  vk::AlignedBuffer scratch(context_, scratchBytes, properties_.minScratchOffsetAlignment,
                            VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUse::DeviceOnly,
                            "hw-tracer.tlas-scratch");
  stats_.scratchBytes = std::max<uint64_t>(stats_.scratchBytes, scratchBytes);
  info.dstAccelerationStructure = tlas_->handle(0);
  info.scratchData.deviceAddress = scratch.address();
  const VkAccelerationStructureBuildRangeInfoKHR range{count, 0, 0, 0};
  const VkAccelerationStructureBuildRangeInfoKHR* ranges = &range;

  vk::GpuTimer timer(context_, 2);
  context_.submitAndWait([&](VkCommandBuffer cmd) {
    timer.reset(cmd);
    timer.begin(cmd, "hw-tlas-build");
    barrierBeforeBuild(cmd);
    api_.cmdBuildAccelerationStructures(cmd, 1, &info, &ranges);
    timer.end(cmd);
    // Traversal in later submissions reads the finished TLAS (and through it the BLASes).
    vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ACCELERATION_STRUCTURE_BUILD_BIT_KHR,
                      VK_ACCESS_2_ACCELERATION_STRUCTURE_WRITE_BIT_KHR,
                      VK_PIPELINE_STAGE_2_RAY_TRACING_SHADER_BIT_KHR,
                      VK_ACCESS_2_ACCELERATION_STRUCTURE_READ_BIT_KHR);
  });
  std::vector<vk::PassTiming> t = timer.read();
  if (!t.empty()) stats_.tlasGpuMilliseconds = t[0].milliseconds;
}

void HardwareTracer::writeDescriptors() {
  setLayout_ = vk::DescriptorSetLayout(
      context_, {{gpu::HW_TRACE_BINDING_TLAS, VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR}});
  VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR, 1};
  VkDescriptorPoolCreateInfo pi{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  pi.maxSets = 1;
  pi.poolSizeCount = 1;
  pi.pPoolSizes = &size;
  VK_CHECK(vkCreateDescriptorPool(context_.device(), &pi, nullptr, &pool_));
  VkDescriptorSetLayout layout = setLayout_.handle();
  VkDescriptorSetAllocateInfo ai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  ai.descriptorPool = pool_;
  ai.descriptorSetCount = 1;
  ai.pSetLayouts = &layout;
  VK_CHECK(vkAllocateDescriptorSets(context_.device(), &ai, &set_));

  VkAccelerationStructureKHR tlas = tlas_->handle(0);
  VkWriteDescriptorSetAccelerationStructureKHR as{
      VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET_ACCELERATION_STRUCTURE_KHR};
  as.accelerationStructureCount = 1;
  as.pAccelerationStructures = &tlas;
  VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET, &as};
  w.dstSet = set_;
  w.dstBinding = gpu::HW_TRACE_BINDING_TLAS;
  w.descriptorCount = 1;
  w.descriptorType = VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR;
  vkUpdateDescriptorSets(context_.device(), 1, &w, 0, nullptr);
}

std::unique_ptr<vk::RayTracingPipeline> HardwareTracer::makePipeline(
    const std::string& raygen, uint32_t pushConstantBytes) const {
  return std::make_unique<vk::RayTracingPipeline>(
      context_, raygen, std::vector<std::string>{"rt/hw_miss.rmiss"},
      std::vector<vk::RayTracingPipeline::HitGroup>{
          {"rt/hw_closest_hit.rchit", "rt/hw_alpha_test.rahit"}},
      std::vector<const vk::DescriptorSetLayout*>{&scene_.setLayout(), &setLayout_},
      pushConstantBytes);
}

std::string HardwareTracer::describe() const {
  const HardwareTracerStats& s = stats_;
  const vk::RayTracingProperties& p = properties_;
  const double mib = double(1 << 20);
  return fmt::format(
      "hardware tracer on {} ({}): shader group handle {} B (alignment {}, base alignment {}), "
      "scratch alignment {}, max recursion {}\n"
      "hardware tracer: {} BLAS ({} geometries, {} triangles) {:.2f} MiB in {} build batch(es), "
      "TLAS of {} instances {:.3f} MiB, scratch {:.2f} MiB, inputs {:.2f} MiB\n"
      "hardware tracer: build {:.3f} s on the host, GPU {:.3f} ms (BLAS) + {:.3f} ms (TLAS)",
      context_.info().name, context_.info().driver, p.shaderGroupHandleSize,
      p.shaderGroupHandleAlignment, p.shaderGroupBaseAlignment, p.minScratchOffsetAlignment,
      p.maxRayRecursionDepth, s.blasCount, s.geometryCount, s.triangles, double(s.blasBytes) / mib,
      s.buildBatches, s.instanceCount, double(s.tlasBytes) / mib, double(s.scratchBytes) / mib,
      double(s.inputBytes) / mib, s.buildSeconds, s.blasGpuMilliseconds, s.tlasGpuMilliseconds);
}

}  // namespace bounce
