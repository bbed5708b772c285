// The hardware tracer: VK_KHR_ray_tracing_pipeline over acceleration structures built by the
// driver from the same data as the software BVH (src/rt/scene_bvh.h): one bottom-level
// acceleration structure (BLAS) per mesh with one geometry per glTF primitive, from the
// scene's own vertex and index streams, and a top-level one (TLAS) over the visible instances
// with their objectToWorld transforms. So that a hit means the same in both tracers:
//   - the TLAS instance's custom index is the GpuInstance index (gl_InstanceCustomIndexEXT is
//     TraceHit::instance); BLAS geometries keep the mesh's geometry order
//     (geometryBase + gl_GeometryIndexEXT is TraceHit::geometry) and gl_PrimitiveID is the
//     triangle within its geometry (TraceHit::primitive);
//   - opaque materials' geometries are flagged opaque; alpha-tested ones (MASK, BLEND) run the
//     any-hit shader rt/hw_alpha_test.rahit, the software tracer's alpha test;
//   - nothing is culled by facing (the software tracer has no culling either).
// Hidden instances and meshes without triangles are left out, as in the software TLAS.
// Static: built once at construction (bench-rays); the GI does not use it yet.
#pragma once
#include <memory>
#include <string>

#include "rt/gpu_scene.h"
#include "vk/context.h"
#include "vk/pipeline.h"
#include "vk/ray_tracing.h"
#include "vk/resources.h"

namespace bounce {

struct HardwareTracerStats {
  uint32_t blasCount = 0;      // meshes with triangles
  uint32_t geometryCount = 0;  // in all BLASes
  uint32_t instanceCount = 0;  // in the TLAS
  uint64_t triangles = 0;      // unique, in the BLASes
  uint64_t blasBytes = 0;      // acceleration-structure storage (all BLASes, 256-byte aligned)
  uint64_t tlasBytes = 0;
  uint64_t scratchBytes = 0;         // the build scratch buffer
  uint64_t inputBytes = 0;           // vertex, index and instance copies read by the builds
  uint32_t buildBatches = 0;         // BLAS build commands (scratch is reused between batches)
  double buildSeconds = 0.0;         // host wall clock: inputs, sizes, the build submission
  double blasGpuMilliseconds = 0.0;  // GPU timestamps around the BLAS builds
  double tlasGpuMilliseconds = 0.0;
};

class HardwareTracer {
 public:
  // Whether the context's device has hardware ray tracing enabled
  // (vk::Context::hardwareRayTracing()), and the one-line error when it has not.
  static bool supported(const vk::Context& context) { return context.hardwareRayTracing(); }
  static std::string unsupportedMessage(const vk::Context& context);

  // Builds the acceleration structures of `scene`. Throws bounce::Error with
  // unsupportedMessage() on a device without hardware ray tracing.
  HardwareTracer(vk::Context& context, const GpuScene& scene);
  ~HardwareTracer();
  HardwareTracer(const HardwareTracer&) = delete;
  HardwareTracer& operator=(const HardwareTracer&) = delete;

  // Set HW_TRACE_SET (shared/hardware_trace.h): the TLAS.
  const vk::DescriptorSetLayout& setLayout() const { return setLayout_; }
  VkDescriptorSet descriptorSet() const { return set_; }
  // A pipeline of `raygen` (an embedded ray-generation shader including rt/hw_trace.glsl) with
  // the tracer's miss and hit shaders, over set 0 (the scene) and set 1 (the TLAS).
  std::unique_ptr<vk::RayTracingPipeline> makePipeline(const std::string& raygen,
                                                       uint32_t pushConstantBytes) const;

  const HardwareTracerStats& stats() const { return stats_; }
  const vk::RayTracingProperties& properties() const { return properties_; }
  // Several lines for verbose output: device, limits, acceleration-structure sizes, build time.
  std::string describe() const;

 private:
  void buildBlas(const GpuScene& scene);
  void buildTlas(const GpuScene& scene);
  void writeDescriptors();

  vk::Context& context_;
  const GpuScene& scene_;
  vk::RayTracingApi api_;
  vk::RayTracingProperties properties_;
  HardwareTracerStats stats_;
  vk::Buffer positions_, indices_, instances_;  // build inputs
  std::vector<int64_t> meshBlas_;               // per mesh: its BLAS in blas_, or -1
  std::unique_ptr<vk::AccelerationStructureSet> blas_;
  std::unique_ptr<vk::AccelerationStructureSet> tlas_;
  vk::DescriptorSetLayout setLayout_;
  VkDescriptorPool pool_ = VK_NULL_HANDLE;
  VkDescriptorSet set_ = VK_NULL_HANDLE;
};

}  // namespace bounce
