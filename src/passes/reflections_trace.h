// `reflections-trace` (DESIGN.md §4 step 6; docs/reflections.md): one reflection ray per pixel
// of the traced image (render resolution / ReflectionSettings::divisor), its direction drawn
// from the GGX lobe's visible normals (the reference's sampler), lit at the hit by emission, one
// sample of each light kind with shadow rays, and the clipmap cache for the 3rd vertex on
// (shaders/passes/reflections_trace.comp). Writes `reflections.traced`, the demodulated
// reflection signal (shaders/shared/specular_io.h); `reflections-upsample` brings it to render
// resolution for composite.
#pragma once
#include <functional>

#include "graph/frame_graph.h"
#include "graph/resource_desc.h"
#include "lighting/gpu_light_tables.h"
#include "passes/frame_context.h"
#include "passes/gbuffer.h"
#include "passes/image_pass.h"
#include "shared/specular_io.h"

namespace bounce {

class SpecularAlbedoTable;
struct Scene;

// How reflections are traced. Each knob: unit, default (both presets), what it trades.
struct ReflectionSettings {
  // Reflection rays are traced at render resolution / divisor: 2 = half resolution on both
  // presets (seed 000), 1 = full resolution (4x the rays, no upsampling blur). 0 = no
  // reflection rays: every surface takes its specular light from the diffuse GI. 0 to 16.
  uint32_t divisor = 2;
  // Perceptual roughness below which a surface traces its single mirror direction instead of a
  // GGX sample: the lobe is then narrower than a pixel's footprint, so sampling it only adds
  // noise (roughness 0.05 is a lobe of about 0.3 degrees). 0 = always sample the lobe.
  float mirrorRoughness = 0.05f;
  // Perceptual roughness above which no ray is traced and the specular light is the diffuse
  // GI's irradiance / pi, the cosine-weighted mean of incident light: a lobe that wide sees
  // nearly what the diffuse lobe sees, and one ray per pixel of it would be as noisy as diffuse
  // GI without its reuse and denoising. kajiya cuts its reflections at 0.7 the same way (rough
  // specular from its irradiance cache), Lumen at 0.4 by default. 1 = trace every surface.
  float maxTracedRoughness = 0.7f;
  // Textures at the hit are read at mips at most this many texels wide (0 = full resolution),
  // as the GI's rays read them (RestirGiSettings::materialTextureSide): incoherent hits, and a
  // glossy reflection blurs texel detail anyway; mirrors show the coarse mip's blur.
  uint32_t materialTextureSide = 16;

  bool enabled() const { return divisor != 0; }
  // The traced image's size for a render resolution.
  VkExtent2D resolution(VkExtent2D render) const {
    return graph::ImageSize::dividedRes(divisor).resolve(render);
  }
};

// Throws bounce::Error naming the field when a setting is out of its documented range.
void validate(const ReflectionSettings& settings);

// How a pass reads the frame's radiance cache (the clipmap cache of the GI system, when it has
// one): the cache's constants and the accesses a lookup needs on the pass.
struct RadianceCacheLookup {
  VkDeviceAddress constants = 0;  // 0: no cache
  std::function<graph::PassBuilder(graph::PassBuilder)> declare;
};

struct TracedReflections {
  graph::ImageHandle traced;  // reflections.traced (shared/specular_io.h)
};

class ReflectionsTracePass {
 public:
  // `specularAlbedo` must outlive the pass; `scene` is the one `gpuScene` was built from.
  ReflectionsTracePass(vk::Context& context, const GpuScene& gpuScene, const Scene& scene,
                       const SpecularAlbedoTable& specularAlbedo,
                       const ReflectionSettings& settings);
  TracedReflections declare(graph::FrameGraph& graph, const FrameContext& frame,
                            const GBuffer& gbuffer, const RadianceCacheLookup& cache);
  // The push constants of the reflection passes this frame.
  gpu::ReflectionPassConstants constants(const FrameContext& frame,
                                         VkDeviceAddress cache = 0) const;

 private:
  ReflectionSettings settings_;
  const SpecularAlbedoTable& specularAlbedo_;
  GpuLightTables lights_;
  ComputePass pass_;
};

}  // namespace bounce
