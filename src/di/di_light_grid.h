// `di-light-grid` (shaders/di/di_light_grid.comp): ReSTIR DI's world-space light grid (ReGIR;
// shared/di_light_grid_io.h, docs/di.md), rebuilt every frame around the camera: each cell's
// slots get a light each by RIS with the cell's target. di-generate-candidates draws most of its
// candidates from the pixel's cell (shaders/di/light_grid.glsl). Its buffers are allocated once
// here, for the settings' cell and slot counts: nothing per frame.
#pragma once
#include "di/di_pass.h"
#include "di/di_settings.h"

namespace bounce {

struct Aabb;

class DiLightGridPass {
 public:
  // `bounds`: the scene's, for the automatic cell size (DiSettings::lightGridCellSize 0).
  DiLightGridPass(vk::Context& context, const GpuScene& scene, const DiSettings& settings,
                  const Aabb& bounds);

  // The gpu::DiLightGrid block (DiConstants::lightGrid).
  VkDeviceAddress address() const { return block_.address(); }
  float cellSize() const { return cellSize_; }

  // Declares the pass; returns the slots buffer it writes (di-generate-candidates reads it).
  graph::BufferHandle declare(graph::FrameGraph& graph, const DiFrame& f);
  // The debug view di.grid-cells (di-light-grid-view, shaders/di/di_light_grid_view.comp): each
  // pixel's cell and how many distinct lights its slots hold. Its pipeline is made at the first
  // request; a frame that does not ask for the view declares no such pass.
  void declareView(graph::FrameGraph& graph, const DiFrame& f, graph::BufferHandle slots);

 private:
  vk::Context& context_;
  const GpuScene& scene_;
  ComputePass pass_;
  std::optional<DiPass> view_;  // made at the first declareView
  uint32_t slotCount_ = 0;
  uint32_t cellsXY_ = 0;  // dispatched as cellsXY_ x cellsZ_ workgroups, one per cell
  uint32_t cellsZ_ = 0;
  float cellSize_ = 1.0f;
  vk::Buffer slots_;  // uvec2 per slot
  vk::Buffer block_;  // gpu::DiLightGrid
};

// The light grid's debug view (DiLightGridPass::declareView).
inline constexpr const char* kDiGridView = "di.grid-cells";

// The cell size a grid of these settings uses in a scene of these bounds (world units, > 0).
float lightGridCellSize(const DiSettings& settings, const Aabb& bounds);

}  // namespace bounce
