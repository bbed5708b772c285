// `di-temporal` (shaders/di/di_temporal.comp): the candidate merged with last frame's reservoir
// at the reprojected pixel (M capped at DiSettings::temporalMaxM): di.reservoir. The history is
// last frame's di.reservoir-final, which di-shade writes (with di.reservoir-surface, written here:
// the normal and depth it belongs to).
#pragma once
#include "di/di_pass.h"

namespace bounce {

class DiTemporalPass {
 public:
  DiTemporalPass(vk::Context& context, const GpuScene& scene);
  // di.reservoir; reads f.finalReservoirs' previous side.
  graph::ImageHandle declare(graph::FrameGraph& graph, const DiFrame& f,
                             graph::ImageHandle candidates);

 private:
  DiPass pass_;
};

}  // namespace bounce
