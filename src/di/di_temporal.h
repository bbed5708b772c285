// `di-temporal` (shaders/di/di_temporal.comp): the candidate merged with last frame's reservoir
// at the reprojected pixel (M capped at DiSettings::temporalMaxM): di.reservoir. The history is
// last frame's di.reservoir-final, which di-shade writes (with di.reservoir-surface, written here:
// the normal and depth it belongs to).
// Where no shadow ray comes between the candidates and this merge (the candidates' ray off, the
// default), the pass draws the candidates itself: `di-candidates-temporal`
// (shaders/di/di_candidates_temporal.comp), the same output as di-generate-candidates followed by
// di-temporal, in one pass.
#pragma once
#include "di/di_pass.h"

namespace bounce {

class DiTemporalPass {
 public:
  // `drawsCandidates`: the fused pass (no di.candidate input); `brdfCandidate` as
  // DiGenerateCandidatesPass's (DI_SPEC_BRDF_CANDIDATE), used only then.
  DiTemporalPass(vk::Context& context, const GpuScene& scene, bool drawsCandidates = false,
                 bool brdfCandidate = false);
  // di.reservoir; reads f.finalReservoirs' previous side, and `candidates` unless it draws them.
  graph::ImageHandle declare(graph::FrameGraph& graph, const DiFrame& f,
                             std::optional<graph::ImageHandle> candidates);
  bool drawsCandidates() const { return drawsCandidates_; }

 private:
  bool drawsCandidates_;
  DiPass pass_;
};

}  // namespace bounce
