// The first stage of ReSTIR GI (DESIGN.md §4 step 5): one candidate sample per GI pixel.
//
//   gi-prepare-diffuse-rays    a uniform hemisphere direction per GI pixel (blue noise); every
//                              3rd frame a validation ray along the history reservoir's sample
//   gi-trace-diffuse-rays      closest hit (ids and barycentrics)
//   gi-shade-diffuse-hits      x2 of the hit; sky on a miss; emission, NEE set-up, the cache
//                              lookup (Cache) or a continued path (Path) at the 2nd vertex
//   gi-trace-diffuse-nee-rays  visibility of the NEE rays, over the list of GI pixels with one
//   gi-resolve-diffuse-rays    candidate reservoirs (one sample, W = 2 pi, M = 1), or on
//                              validation rays the checked history reservoir; reservoir validity
#pragma once
#include "gi/evolve/cache/clipmap_cache.h"
#include "gi/evolve/restir/restir_gi_pass.h"
#include "gi/evolve/restir/restir_gi_settings.h"

namespace bounce {

struct Candidates {
  ReservoirImages reservoir;         // gi.candidate.{sample,radiance,origin,normals}
  graph::ImageHandle estimate;       // gi.candidate-estimate: rgba16f, the candidate's estimate
  graph::ImageHandle validity;       // gi.reservoir-validity: rgba16f, of the history reservoir
  graph::ImageHandle neeVisibility;  // gi.nee-visibility: r16f, 1 = the NEE ray is unoccluded
};

// gi-shade-diffuse-hits' outputs (shared/restir_gi_io.h, GI_SHADE_BINDING_*) and
// gi-trace-diffuse-nee-rays' visibility.
struct GiHits {
  graph::ImageHandle hit, normal, radiance, neeRay, neeRadiance;
  graph::ImageHandle neeVisibility;  // gi.nee-visibility: r16f, 1 = the NEE ray is unoccluded
};

// RestirGiConstants::secondVertex (RESTIR_GI_SECOND_VERTEX_*) of a setting.
uint32_t secondVertexConstant(RestirGiSecondVertex v);

// The passes that turn gi.rays into GiHits: Evolve's candidates and Lux's trace the same way.
struct GiTracePasses {
  // `secondVertex`: the chain's RestirGiConstants::secondVertex, which gi-shade-diffuse-hits is
  // specialized for (GI_SPEC_SECOND_VERTEX).
  GiTracePasses(vk::Context& context, const GpuScene& scene, uint32_t secondVertex);
  RestirGiPass trace, shade, traceNee;
};

// gi-trace-diffuse-rays and gi-shade-diffuse-hits over `rays` (gi.rays), then
// gi-trace-diffuse-nee-rays over the GI pixels with a light sample; `cache`: the clipmap cache
// the 2nd vertex looks up, or nullptr.
GiHits declareGiTrace(graph::FrameGraph& graph, const RestirFrame& f, graph::ImageHandle rays,
                      const ClipmapCache* cache, GiTracePasses& passes);

class CandidateStage {
 public:
  // `secondVertex`: RestirGiConstants::secondVertex (GiTracePasses).
  CandidateStage(vk::Context& context, const GpuScene& scene, uint32_t secondVertex);
  // `history`: last frame's reservoirs (validation rays retrace their samples); `cache`: the
  // clipmap cache the 2nd vertex looks up, or nullptr.
  Candidates declare(graph::FrameGraph& graph, const RestirFrame& f,
                     const ReservoirHistory& history, ClipmapCache* cache);

 private:
  graph::ImageHandle declarePrepare(graph::FrameGraph& graph, const RestirFrame& f,
                                    const ReservoirHistory& history);
  Candidates declareResolve(graph::FrameGraph& graph, const RestirFrame& f,
                            const ReservoirHistory& history, graph::ImageHandle rays,
                            const GiHits& hits);

  RestirGiPass prepare_;
  GiTracePasses trace_;
  RestirGiPass resolve_;
};

}  // namespace bounce
