// `di-generate-candidates` (shaders/di/di_generate_candidates.comp): each pixel's initial
// reservoir from DiSettings::lightCandidates light candidates by RIS; then
// `di-trace-candidate-visibility` (shaders/di/di_trace_candidate_visibility.comp), the kept
// sample's shadow ray. Two passes so that the candidates' loop runs without the traversal's
// registers (docs/benchmarks.md).
#pragma once
#include "di/di_pass.h"

namespace bounce {

class DiGenerateCandidatesPass {
 public:
  // `brdfCandidate`: whether DiConstants::brdfCandidates is above 0 (DI_SPEC_BRDF_CANDIDATE);
  // `visibility`: whether DiConstants::flags has DI_FLAG_CANDIDATE_VISIBILITY.
  DiGenerateCandidatesPass(vk::Context& context, const GpuScene& scene, bool brdfCandidate,
                           bool visibility);
  // di.candidate: the reservoirs (kDiReservoirFormat).
  graph::ImageHandle declare(graph::FrameGraph& graph, const DiFrame& f);
  // Compute pipelines: the candidates' and, with `visibility`, the shadow ray's.
  uint32_t pipelineCount() const { return visibility_ ? 2u : 1u; }

 private:
  DiPass generate_;
  std::optional<DiPass> visibility_;
};

}  // namespace bounce
