// The spatial stage of ReSTIR GI (DESIGN.md §4 step 5), as enabled by the settings:
//
//   gi-restir-spatial-0/-1     spatial reuse, 8 samples / large radius then 5 / small radius
//   gi-trace-spatial-validation-rays  visibility of reused samples (W = 0 when occluded); the
//                              spatial occlusion validity mask (history)
//   gi-restir-patch-reservoir  rejected reservoirs take the first valid one of their 2x2 patch
#pragma once
#include <optional>

#include "gi/evolve/restir/restir_gi_pass.h"
#include "gi/evolve/restir/restir_gi_settings.h"
#include "gi/evolve/restir/temporal.h"

namespace bounce {

class SpatialStage {
 public:
  SpatialStage(vk::Context& context, const GpuScene& scene, const RestirGiSettings& settings);
  // Returns the reservoir the resolve reads (`temporal` itself without spatial reuse).
  // `occlusionValidity`: written by the validation pass; present exactly when it runs.
  Reservoirs declare(graph::FrameGraph& graph, const RestirFrame& f, const Reservoirs& temporal,
                     const std::optional<graph::HistoryImage>& occlusionValidity);

 private:
  Reservoirs declareReservoirPass(graph::FrameGraph& graph, const RestirFrame& f, const char* name,
                                  RestirGiPass& pass, uint32_t variant,
                                  const ReservoirImages& input, const Reservoirs& output);
  Reservoirs declareValidation(graph::FrameGraph& graph, const RestirFrame& f,
                               const Reservoirs& temporal, const Reservoirs& spatial,
                               const graph::HistoryImage& validity);

  RestirGiSettings settings_;
  RestirGiPass spatial0_, spatial1_, validation_, patch_;
};

}  // namespace bounce
