// ReSTIR-style reuse of the glossy reflection samples (issue 19 item 2; docs/reflections.md
// "Reuse"): between reflections-trace and the passes that filter and upsample its signal,
//   reflections-temporal  the fresh candidate merged with last frame's reservoir (history)
//   reflections-spatial   merged with a few neighbours' reservoirs
//   reflections-resolve   the chosen sample as the demodulated signal, reflections.resolved,
//                         in reflections.traced's format and meaning
// (shaders/passes/reflections_{temporal,spatial,resolve}.comp; the reservoirs and constants in
// shared/reflections_reuse_io.h). Mirrors and lobes below ReflectionSettings::reuseMinRoughness
// pass through unchanged.
#pragma once
#include "passes/reflections_resolve.h"
#include "passes/reflections_spatial.h"
#include "passes/reflections_temporal.h"

namespace bounce {

class SpecularAlbedoTable;

class ReflectionsReuse {
 public:
  // `specularAlbedo` must outlive this.
  ReflectionsReuse(vk::Context& context, const GpuScene& gpuScene,
                   const SpecularAlbedoTable& specularAlbedo, const ReflectionSettings& settings);
  // The three passes on `traced`; returns the resolved signal as the traced reflections the
  // passes after it read (its `candidate` images are the trace's).
  TracedReflections declare(graph::FrameGraph& graph, const FrameContext& frame,
                            const GBuffer& gbuffer, const TracedReflections& traced);

 private:
  gpu::ReflectionReuseConstants constants(const FrameContext& frame) const;

  ReflectionSettings settings_;
  const SpecularAlbedoTable& specularAlbedo_;
  ReflectionsTemporalPass temporal_;
  ReflectionsSpatialPass spatial_;
  ReflectionsResolvePass resolve_;
};

}  // namespace bounce
