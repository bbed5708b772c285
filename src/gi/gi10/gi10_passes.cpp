// GI-1.0's passes on the frame graph, in frame order (gi10_gi.h).
#include "gi/gi10/gi10_gi.h"

namespace bounce {

namespace {

using graph::Access;
using graph::QueueKind;

uint32_t groupsFor(uint64_t items) {
  return uint32_t((items + gpu::GI10_GROUP_SIZE - 1) / gpu::GI10_GROUP_SIZE);
}

}  // namespace

void Gi10Gi::declareProbes(graph::FrameGraph& graph, const GiInputs& inputs, const Buffers& b,
                           const gpu::Gi10PassConstants& push, graph::ImageHandle previousGi) {
  const uint32_t current = parity_, previous = 1 - parity_;
  const GBuffer& g = inputs.gbuffer;
  const glm::uvec2 probeGrid = probeGrid_, spawnGrid = spawnGrid_;
  const uint64_t slots = uint64_t(buckets_) * gpu::GI10_BUCKET_SLOTS;
  const uint64_t tiles = uint64_t(probeGrid.x) * probeGrid.y;
  const uint64_t rays = uint64_t(spawnGrid.x) * spawnGrid.y * gpu::GI10_PROBE_CELLS;

  graph.addPass("gi10-purge-radiance-cache", QueueKind::Compute)
      .read(b.constants, Access::StorageRead)
      .write(b.cache, Access::StorageReadWrite)
      .write(b.counters, Access::StorageReadWrite)
      .sideEffects()
      .record([this, push, slots](VkCommandBuffer cmd, const graph::PassResources& r) {
        purge_.bind(cmd, push, r);
        vkCmdDispatch(cmd, groupsFor(slots), 1, 1);
      });
  graph.addPass("gi10-spawn-screen-probes", QueueKind::Compute)
      .read(b.constants, Access::StorageRead)
      .read(inputs.frame.constants, Access::StorageRead)
      .read(g.depth.current, Access::StorageRead, gpu::GI10_SPAWN_BINDING_DEPTH)
      .write(b.spawn, Access::StorageWrite)
      .record([this, push, spawnGrid](VkCommandBuffer cmd, const graph::PassResources& r) {
        spawnPass_.bind(cmd, push, r);
        vk::ComputePipeline::dispatchCovering(cmd, spawnGrid.x, spawnGrid.y, 8, 8);
      });
  graph.addPass("gi10-reproject-screen-probes", QueueKind::Compute)
      .read(b.constants, Access::StorageRead)
      .read(inputs.frame.constants, Access::StorageRead)
      .read(g.normals, Access::StorageRead, gpu::GI10_REPROJECT_BINDING_NORMALS)
      .read(g.depth.current, Access::StorageRead, gpu::GI10_REPROJECT_BINDING_DEPTH)
      .read(g.velocity, Access::StorageRead, gpu::GI10_REPROJECT_BINDING_VELOCITY)
      .read(b.spawn, Access::StorageRead)
      .read(b.probes[previous], Access::StorageRead)
      .read(b.radiance[previous], Access::StorageRead)
      .write(b.probes[current], Access::StorageWrite)
      .write(b.radiance[current], Access::StorageWrite)
      .write(b.counters, Access::StorageReadWrite)
      .record([this, push, probeGrid](VkCommandBuffer cmd, const graph::PassResources& r) {
        reproject_.bind(cmd, push, r);
        vkCmdDispatch(cmd, probeGrid.x, probeGrid.y, 1);
      });
  graph.addPass("gi10-populate-screen-probes", QueueKind::Compute)
      .read(b.constants, Access::StorageRead)
      .read(inputs.frame.constants, Access::StorageRead)
      .read(inputs.frame.instances, Access::StorageRead)
      .read(inputs.frame.tlas, Access::StorageRead)
      .read(g.normals, Access::StorageRead, gpu::GI10_POPULATE_BINDING_NORMALS)
      .read(g.depth.current, Access::StorageRead, gpu::GI10_POPULATE_BINDING_DEPTH)
      .read(g.velocity, Access::StorageRead, gpu::GI10_POPULATE_BINDING_VELOCITY)
      .read(previousGi, Access::StorageRead, gpu::GI10_POPULATE_BINDING_PREVIOUS_GI)
      .read(b.spawn, Access::StorageRead)
      .read(b.probes[current], Access::StorageRead)
      .write(b.rays, Access::StorageWrite)
      .write(b.cache, Access::StorageReadWrite)
      .write(b.counters, Access::StorageReadWrite)
      .record([this, push, spawnGrid](VkCommandBuffer cmd, const graph::PassResources& r) {
        populate_.bind(cmd, push, r);
        vkCmdDispatch(cmd, spawnGrid.x, spawnGrid.y, 1);
      });
  graph.addPass("gi10-update-radiance-cache", QueueKind::Compute)
      .read(b.constants, Access::StorageRead)
      .write(b.cache, Access::StorageReadWrite)
      .record([this, push, slots](VkCommandBuffer cmd, const graph::PassResources& r) {
        update_.bind(cmd, push, r);
        vkCmdDispatch(cmd, groupsFor(slots), 1, 1);
      });
  graph.addPass("gi10-resolve-radiance-cache", QueueKind::Compute)
      .read(b.constants, Access::StorageRead)
      .read(b.cache, Access::StorageRead)
      .read(b.spawn, Access::StorageRead)
      .write(b.rays, Access::StorageReadWrite)
      .record([this, push, rays](VkCommandBuffer cmd, const graph::PassResources& r) {
        resolve_.bind(cmd, push, r);
        vkCmdDispatch(cmd, groupsFor(rays), 1, 1);
      });
  graph.addPass("gi10-blend-screen-probes", QueueKind::Compute)
      .read(b.constants, Access::StorageRead)
      .read(b.spawn, Access::StorageRead)
      .read(b.rays, Access::StorageRead)
      .read(b.probes[current], Access::StorageRead)
      .write(b.radiance[current], Access::StorageReadWrite)
      .record([this, push, spawnGrid](VkCommandBuffer cmd, const graph::PassResources& r) {
        blend_.bind(cmd, push, r);
        vkCmdDispatch(cmd, spawnGrid.x, spawnGrid.y, 1);
      });
  graph.addPass("gi10-project-screen-probes", QueueKind::Compute)
      .read(b.constants, Access::StorageRead)
      .read(b.probes[current], Access::StorageRead)
      .read(b.radiance[current], Access::StorageRead)
      .write(b.sh, Access::StorageWrite)
      .record([this, push, tiles](VkCommandBuffer cmd, const graph::PassResources& r) {
        project_.bind(cmd, push, r);
        vkCmdDispatch(cmd, groupsFor(tiles), 1, 1);
      });
}

graph::ImageHandle Gi10Gi::declareResolve(graph::FrameGraph& graph, const GiInputs& inputs,
                                          const Buffers& b, const gpu::Gi10PassConstants& push,
                                          graph::HistoryImage gi) {
  constexpr VkFormat rgba16f = VK_FORMAT_R16G16B16A16_SFLOAT;
  const uint32_t current = parity_;
  const GBuffer& g = inputs.gbuffer;
  const VkExtent2D extent = inputs.frame.resolution;
  graph::ImageHandle irradiance = graph.createImage("gi10.irradiance", {rgba16f});
  graph::HistoryImage delta = graph.createHistoryImage("gi10.gi-delta", {VK_FORMAT_R16G16_SFLOAT});
  graph.addPass("gi10-interpolate-screen-probes", QueueKind::Compute)
      .read(b.constants, Access::StorageRead)
      .read(inputs.frame.constants, Access::StorageRead)
      .read(b.probes[current], Access::StorageRead)
      .read(b.sh, Access::StorageRead)
      .read(g.normals, Access::StorageRead, gpu::GI10_INTERPOLATE_BINDING_NORMALS)
      .read(g.depth.current, Access::StorageRead, gpu::GI10_INTERPOLATE_BINDING_DEPTH)
      .write(irradiance, Access::StorageWrite, gpu::GI10_INTERPOLATE_BINDING_OUTPUT)
      .record([this, push, extent](VkCommandBuffer cmd, const graph::PassResources& r) {
        interpolate_.bind(cmd, push, r);
        vk::ComputePipeline::dispatchCovering(cmd, extent.width, extent.height, 8, 8);
      });
  graph.addPass("gi10-reproject-gi", QueueKind::Compute)
      .read(b.constants, Access::StorageRead)
      .read(inputs.frame.constants, Access::StorageRead)
      .read(irradiance, Access::StorageRead, gpu::GI10_REPROJECT_GI_BINDING_IRRADIANCE)
      .read(g.depth.current, Access::StorageRead, gpu::GI10_REPROJECT_GI_BINDING_DEPTH)
      .read(g.depth.previous, Access::StorageRead, gpu::GI10_REPROJECT_GI_BINDING_PREVIOUS_DEPTH)
      .read(g.velocity, Access::StorageRead, gpu::GI10_REPROJECT_GI_BINDING_VELOCITY)
      .read(gi.previous, Access::StorageRead, gpu::GI10_REPROJECT_GI_BINDING_PREVIOUS)
      .write(gi.current, Access::StorageWrite, gpu::GI10_REPROJECT_GI_BINDING_OUTPUT)
      .read(delta.previous, Access::StorageRead, gpu::GI10_REPROJECT_GI_BINDING_PREVIOUS_DELTA)
      .write(delta.current, Access::StorageWrite, gpu::GI10_REPROJECT_GI_BINDING_DELTA)
      .record([this, push, extent](VkCommandBuffer cmd, const graph::PassResources& r) {
        reprojectGi_.bind(cmd, push, r);
        vk::ComputePipeline::dispatchCovering(cmd, extent.width, extent.height, 8, 8);
      });
  graph::ImageHandle filtered = graph.createImage("gi10.filter-x", {rgba16f});
  graph::ImageHandle output = createOutput(graph);
  for (uint32_t axis = 0; axis < 2; ++axis) {
    gpu::Gi10PassConstants axisPush = push;
    axisPush.axis = axis;
    graph::ImageHandle in = axis == 0 ? gi.current : filtered;
    graph::ImageHandle out = axis == 0 ? filtered : output;
    graph::PassBuilder pass =
        graph.addPass(axis == 0 ? "gi10-filter-gi-x" : "gi10-filter-gi-y", QueueKind::Compute);
    pass.read(in, Access::StorageRead, gpu::GI10_FILTER_BINDING_INPUT);
    // The history length: the same image as the input in the first pass.
    if (axis == 0)
      pass.readPlaceholder(gi.current, gpu::GI10_FILTER_BINDING_HISTORY);
    else
      pass.read(gi.current, Access::StorageRead, gpu::GI10_FILTER_BINDING_HISTORY);
    pass.read(b.constants, Access::StorageRead)
        .read(inputs.frame.constants, Access::StorageRead)
        .read(g.normals, Access::StorageRead, gpu::GI10_FILTER_BINDING_NORMALS)
        .read(g.depth.current, Access::StorageRead, gpu::GI10_FILTER_BINDING_DEPTH)
        .write(out, Access::StorageWrite, gpu::GI10_FILTER_BINDING_OUTPUT)
        .record([this, axisPush, axis, extent](VkCommandBuffer cmd, const graph::PassResources& r) {
          filter_.bind(cmd, axisPush, r, axis);
          vk::ComputePipeline::dispatchCovering(cmd, extent.width, extent.height, 8, 8);
        });
  }
  return output;
}

void Gi10Gi::declareDebugViews(graph::FrameGraph& graph, const GiInputs& inputs, const Buffers& b,
                               const gpu::Gi10PassConstants& push) {
  constexpr VkFormat rgba16f = VK_FORMAT_R16G16B16A16_SFLOAT;
  const uint32_t current = parity_;
  const VkExtent2D extent = inputs.frame.resolution;
  graph::ImageHandle probes = graph.createImage("gi10.probes-view", {rgba16f});
  graph.addPass("gi10-probes-debug", QueueKind::Compute)
      .read(b.constants, Access::StorageRead)
      .read(inputs.frame.constants, Access::StorageRead)
      .read(b.probes[current], Access::StorageRead)
      .read(b.radiance[current], Access::StorageRead)
      .write(probes, Access::StorageWrite, 0)
      .record([this, push, extent](VkCommandBuffer cmd, const graph::PassResources& r) {
        probesDebug_.bind(cmd, push, r);
        vk::ComputePipeline::dispatchCovering(cmd, extent.width, extent.height, 8, 8);
      });
  graph::ImageHandle cache = graph.createImage("gi10.cache-view", {rgba16f});
  graph.addPass("gi10-cache-debug", QueueKind::Compute)
      .read(b.constants, Access::StorageRead)
      .read(inputs.frame.constants, Access::StorageRead)
      .read(b.cache, Access::StorageRead)
      .read(inputs.gbuffer.depth.current, Access::StorageRead, 0)
      .write(cache, Access::StorageWrite, 1)
      .read(inputs.gbuffer.normals, Access::StorageRead, 2)
      .record([this, push, extent](VkCommandBuffer cmd, const graph::PassResources& r) {
        cacheDebug_.bind(cmd, push, r);
        vk::ComputePipeline::dispatchCovering(cmd, extent.width, extent.height, 8, 8);
      });
}

}  // namespace bounce
