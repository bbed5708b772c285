#include "di/di_light_grid.h"

#include <algorithm>

#include "scene/scene.h"
#include "shared/di_light_grid_io.h"

namespace bounce {

float lightGridCellSize(const DiSettings& s, const Aabb& bounds) {
  if (s.lightGridCellSize > 0.0f) return s.lightGridCellSize;
  const glm::vec3 extent = bounds.empty() ? glm::vec3(1.0f) : bounds.extent();
  const float largest = std::max(extent.x, std::max(extent.y, extent.z));
  return largest > 0.0f ? largest / 128.0f : 1.0f;
}

DiLightGridPass::DiLightGridPass(vk::Context& context, const GpuScene& scene,
                                 const DiSettings& settings, const Aabb& bounds)
    : context_(context),
      scene_(scene),
      pass_(context, scene, "di/di_light_grid", 0, sizeof(gpu::DiPassConstants)),
      slotCount_(settings.lightGridCellsX * settings.lightGridCellsY * settings.lightGridCellsZ *
                 settings.lightGridSlots),
      cellsXY_(settings.lightGridCellsX * settings.lightGridCellsY),
      cellsZ_(settings.lightGridCellsZ),
      cellSize_(lightGridCellSize(settings, bounds)),
      slots_(context, VkDeviceSize(slotCount_) * 2 * sizeof(uint32_t),
             VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUse::DeviceOnly, "di.light-grid") {
  gpu::DiLightGrid g{};
  g.slots = slots_.address();
  g.cellsX = settings.lightGridCellsX;
  g.cellsY = settings.lightGridCellsY;
  g.cellsZ = settings.lightGridCellsZ;
  g.cellSize = cellSize_;
  g.slotsPerCell = settings.lightGridSlots;
  g.buildCandidates = settings.lightGridBuildCandidates;
  g.gridCandidates = settings.lightGridCandidates;
  block_ = vk::uploadBuffer(context, std::as_bytes(std::span(&g, 1)),
                            VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "di.light-grid-constants");
}

graph::BufferHandle DiLightGridPass::declare(graph::FrameGraph& graph, const DiFrame& f) {
  graph::BufferHandle slots =
      graph.importBuffer("di.light-grid", graph::ImportedBuffer::from(slots_));
  graph::PassBuilder pass = graph.addPass("di-light-grid", graph::QueueKind::Compute);
  pass.read(f.frame.constants, graph::Access::StorageRead)
      .write(slots, graph::Access::StorageWrite)
      .record([this, f](VkCommandBuffer cmd, const graph::PassResources&) {
        pass_.bind(cmd, f.passConstants());
        // One workgroup per cell (its slots share one pool of candidates).
        vkCmdDispatch(cmd, cellsXY_, cellsZ_, 1);
      });
  return slots;
}

void DiLightGridPass::declareView(graph::FrameGraph& graph, const DiFrame& f,
                                  graph::BufferHandle slots) {
  if (!view_)
    view_.emplace(context_, scene_, "di/di_light_grid_view", gpu::DI_GRID_VIEW_BINDING_COUNT);
  graph::ImageHandle image = graph.createImage(kDiGridView, {VK_FORMAT_R32G32B32A32_SFLOAT});
  graph::PassBuilder pass = graph.addPass("di-light-grid-view", graph::QueueKind::Compute);
  readDiGBuffer(pass, f)
      .read(slots, graph::Access::StorageRead)
      .write(image, graph::Access::StorageWrite, gpu::DI_GRID_VIEW_BINDING_OUTPUT)
      .record([this, f](VkCommandBuffer cmd, const graph::PassResources& r) {
        view_->record(cmd, r, f.passConstants(), f.frame.resolution);
      });
}

}  // namespace bounce
