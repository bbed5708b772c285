// `gi-restir-temporal` (DESIGN.md §4 step 5): sub-pixel-aware reprojection and up to 5 history
// reservoirs merged with this frame's candidate (permutation sampling); its output is the only
// reservoir fed back (gi.reservoir.*, a history).
#pragma once
#include <optional>

#include "gi/evolve/restir/candidates.h"
#include "gi/evolve/restir/restir_gi_pass.h"

namespace bounce {

// A reservoir per GI pixel and its estimate (the pass's debug view).
struct Reservoirs {
  ReservoirImages reservoir;
  graph::ImageHandle estimate;  // rgba16f
};

class TemporalStage {
 public:
  TemporalStage(vk::Context& context, const GpuScene& scene);
  // Writes `history`'s current side. `occlusionValidity`: gi-trace-spatial-validation-rays'
  // history (its previous side is read), absent without that pass.
  Reservoirs declare(graph::FrameGraph& graph, const RestirFrame& f, const Candidates& candidates,
                     const ReservoirHistory& history,
                     const std::optional<graph::HistoryImage>& occlusionValidity);

 private:
  RestirGiPass temporal_;
};

}  // namespace bounce
