// `di-generate-candidates` (shaders/di/di_generate_candidates.comp): each pixel's initial
// reservoir from DiSettings::lightCandidates light candidates by RIS, with the kept sample's
// shadow ray.
#pragma once
#include "di/di_pass.h"

namespace bounce {

class DiGenerateCandidatesPass {
 public:
  DiGenerateCandidatesPass(vk::Context& context, const GpuScene& scene);
  // di.candidate: the reservoirs (kDiReservoirFormat).
  graph::ImageHandle declare(graph::FrameGraph& graph, const DiFrame& f);

 private:
  DiPass pass_;
};

}  // namespace bounce
