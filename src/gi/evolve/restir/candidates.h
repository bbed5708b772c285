// The first stage of ReSTIR GI (DESIGN.md §4 step 5): one candidate sample per GI pixel.
//
//   gi-prepare-diffuse-rays    a uniform hemisphere direction per GI pixel (blue noise); every
//                              3rd frame a validation ray along the history reservoir's sample
//   gi-trace-diffuse-rays      closest hit; sky on a miss; emission, NEE set-up, the cache lookup
//                              (Cache) or a continued path (Path) at the 2nd vertex
//   gi-trace-diffuse-nee-rays  visibility of the NEE rays, over the list of GI pixels with one
//   gi-resolve-diffuse-rays    candidate reservoirs (one sample, W = 2 pi, M = 1), or on
//                              validation rays the checked history reservoir; reservoir validity
#pragma once
#include "gi/evolve/cache/clipmap_cache.h"
#include "gi/evolve/restir/restir_gi_pass.h"

namespace bounce {

struct Candidates {
  ReservoirImages reservoir;         // gi.candidate.{sample,radiance,origin,normals}
  graph::ImageHandle estimate;       // gi.candidate-estimate: rgba16f, the candidate's estimate
  graph::ImageHandle validity;       // gi.reservoir-validity: rgba16f, of the history reservoir
  graph::ImageHandle neeVisibility;  // gi.nee-visibility: r16f, 1 = the NEE ray is unoccluded
};

// gi-trace-diffuse-rays' outputs (shared/restir_gi_io.h, GI_TRACE_BINDING_*) and
// gi-trace-diffuse-nee-rays' visibility.
struct GiHits {
  graph::ImageHandle hit, normal, radiance, neeRay, neeRadiance;
  graph::ImageHandle neeVisibility;  // gi.nee-visibility: r16f, 1 = the NEE ray is unoccluded
};

// gi-trace-diffuse-rays over `rays` (gi.rays) then gi-trace-diffuse-nee-rays over the GI pixels
// with a light sample; `cache`: the clipmap cache the 2nd vertex looks up, or nullptr. Evolve's
// candidates and Lux's trace the same way.
GiHits declareGiTrace(graph::FrameGraph& graph, const RestirFrame& f, graph::ImageHandle rays,
                      const ClipmapCache* cache, RestirGiPass& trace, RestirGiPass& traceNee);

class CandidateStage {
 public:
  CandidateStage(vk::Context& context, const GpuScene& scene);
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

  RestirGiPass prepare_, trace_, traceNee_, resolve_;
};

}  // namespace bounce
