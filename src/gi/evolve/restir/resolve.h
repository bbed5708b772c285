// The last stage of ReSTIR GI (DESIGN.md §4 step 5): from reservoirs at GI resolution to
// irradiance at render resolution.
//
//   gi-resolve-find-occluders    pixels beside an occluder: no spatial denoise there, and a
//                                list of them (when RestirGiSettings::occluderVisibility)
//   gi-trace-resolve-visibility  which of the resolve's samples the listed pixels cannot see
//                                (shadow rays)
//   gi-restir-resolve            reservoirs -> L1 SH -> irradiance / pi per unit albedo
#pragma once
#include <optional>

#include "gi/evolve/restir/restir_gi_pass.h"
#include "gi/evolve/restir/restir_gi_settings.h"
#include "gi/evolve/restir/temporal.h"

namespace bounce {

struct ResolvedGi {
  graph::ImageHandle diffuse;  // rgba16f, render resolution: the `target` given to declare()
  // gi.resolve-occlusion: r32ui, which resolve samples each pixel cannot see and whether it is
  // beside an occluder (shared/restir_gi_io.h); absent without gi-trace-resolve-visibility.
  std::optional<graph::ImageHandle> occlusion;
};

class ResolveStage {
 public:
  ResolveStage(vk::Context& context, const GpuScene& scene, const RestirGiSettings& settings);
  // Writes `target` (gi.diffuse, or gi.resolved when a denoiser follows).
  ResolvedGi declare(graph::FrameGraph& graph, const RestirFrame& f, const Reservoirs& reservoirs,
                     graph::ImageHandle target);

 private:
  enum class RayListUse { None, Fills, Walks };
  graph::PassBuilder declarePass(graph::FrameGraph& graph, const RestirFrame& f, const char* name,
                                 RestirGiPass& pass, const Reservoirs& reservoirs,
                                 uint32_t outputBinding, graph::ImageHandle output,
                                 RayListUse rayList);

  RestirGiSettings settings_;
  RestirGiPass findOccluders_, visibility_, resolve_;
};

}  // namespace bounce
