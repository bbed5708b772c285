// `di-temporal` (shaders/di/di_temporal.comp): the candidate merged with last frame's reservoir
// at the reprojected pixel (M capped at DiSettings::temporalMaxM). Its output, di.reservoir
// (with di.reservoir-surface: the normal and depth it belongs to), is the history fed back.
#pragma once
#include "di/di_pass.h"

namespace bounce {

class DiTemporalPass {
 public:
  DiTemporalPass(vk::Context& context, const GpuScene& scene);
  // The current side of di.reservoir.
  graph::ImageHandle declare(graph::FrameGraph& graph, const DiFrame& f,
                             graph::ImageHandle candidates);

 private:
  DiPass pass_;
};

}  // namespace bounce
