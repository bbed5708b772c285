// `reflections-trace` (DESIGN.md §4 step 6; docs/reflections.md): one reflection ray per pixel
// of the traced image (render resolution / ReflectionSettings::divisor), its direction drawn
// from the GGX lobe's visible normals (the reference's sampler), lit at the hit by emission, one
// sample of each light kind with shadow rays, and the clipmap cache for the 3rd vertex on
// (shaders/passes/reflections_trace.comp). Writes `reflections.traced`, the demodulated
// reflection signal (shaders/shared/specular_io.h); `reflections-upsample` brings it to render
// resolution for composite.
#pragma once
#include <array>
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
  // Mirrors (roughness below mirrorRoughness) trace their own ray at a render pixel
  // (reflections-trace-mirrors) where the traced rays reflections-upsample reads there reflect
  // more than mirrorDirectionToleranceDegrees away from the pixel's own mirror direction. A
  // mirror shows what its exact direction sees, and on a curved mirror that direction turns by
  // twice the normal's turn per pixel: a shared ray shows the neighbour's view (on `spheres` at
  // 96x54 the roughness-0.02 balls' lower halves showed the lit floor where the dark floor
  // under the ball belongs). A flat mirror's pixels reflect nearly parallel rays, so a window
  // keeps its shared, denoised rays. Own rays skip reuse and the denoiser (a mirror's one
  // direction has no lobe noise; what is left is the hit's light samples, which TAA averages).
  // false: mirrors are upsampled like every other surface. Tolerance 0 = every mirror pixel
  // traces its own ray; 0 to 180. Default true, 1 degree (both presets).
  bool mirrorsAtFullResolution = true;
  float mirrorDirectionToleranceDegrees = 1.0f;
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
  // Path regularization at the hit (lighting/regularize.glsl; docs/reflections.md "Accuracy"):
  // the hit's light samples (the sun's above all) see its specular lobe at least this many
  // times as wide (GGX alpha) as the reflecting pixel's own lobe. Sun -> near-mirror -> glossy
  // -> eye is a caustic path that one ray per pixel finds once in thousands of samples, with a
  // weight of thousands (fireflies that reuse and the denoiser's history keep for many frames);
  // widening the mirror's lobe by about what the glossy lobe blurs anyway spreads that spot
  // over more of the mirror. Higher: fewer fireflies, blurrier glints of the sun seen in glossy
  // reflections. 0 = none (unbiased). 0 to 16.
  float hitRegularization = 1.0f;

  // ReSTIR-style reuse of the glossy samples (reflections-temporal, reflections-spatial,
  // reflections-resolve; docs/reflections.md "Reuse"): each traced pixel resamples its own
  // sample, last frame's reservoir and a few neighbours' by the GGX target. Default on (both
  // presets): on `spheres` (uniform sky) the glossy rows' per-pixel variance falls 26-32x for
  // three passes of a few image reads each; the price is the bias of reuse without visibility
  // tests (a neighbour's hit may be hidden from this pixel; measured -3 %, within the noise).
  // false = the traced signal as it is.
  bool reuse = true;
  // Perceptual roughness below which samples are not reused (the traced signal passes through
  // unchanged): a second threshold above mirrorRoughness for lobes so narrow that neighbours'
  // samples cannot serve. Default 0.05 = mirrorRoughness: the GGX target already gives a
  // neighbour's sample outside a narrow lobe ~no weight, so every sampled lobe is reused. Raise it
  // where sharp reflections of nearby objects smear under motion. mirrorRoughness to
  // maxTracedRoughness.
  float reuseMinRoughness = 0.05f;
  // Cap on the history reservoir's confidence M (frames of samples it stands for): RTXDI's and
  // ReSTIR GI's ~20. Higher: lower variance on a static view, slower response to change (a
  // stale sample lasts ~M frames). 0 = no temporal reuse. 0 to 1000. Default 20.
  float temporalMaxM = 20.0f;
  // Where the view moved at a pixel, its history reservoir is reused only if its sample lies at
  // the depth of this frame's candidate: their parallaxes (hit distance / (camera distance of
  // x1 + hit distance), 1 for the sky) within this much. A history that reflected another
  // object (a reflection-space disocclusion: the sample a neighbouring surface point saw last
  // frame) would otherwise carry that object's light into this pixel for up to temporalMaxM
  // frames (docs/reflections.md, "Motion"). A static view is never tested. Lower: fewer stale
  // samples under motion, less reuse (noisier) while moving. 0 = no test. 0 to 1. Default 0.05.
  float motionParallaxTolerance = 0.05f;
  // Neighbours each pixel resamples in reflections-spatial. More: lower variance, more time and
  // more bias from unchecked visibility. 0 = no spatial reuse. 0 to 8. Default 4.
  uint32_t spatialSamples = 4;
  // Radius of that neighbourhood in traced pixels at roughness 1, scaled by the pixel's
  // perceptual roughness (a narrower lobe's neighbours reflect other directions), at least 1.5.
  // Larger: more independent neighbours, more blur of reflection detail. 0 to 64. Default 8.
  float spatialRadius = 8.0f;
  // Mixed into the reflection passes' random numbers: frames of different seeds draw independent
  // samples (tests measure variance across seeds). Default 0.
  uint32_t seed = 0;

  bool enabled() const { return divisor != 0; }
  bool reuseEnabled() const { return enabled() && reuse; }
  // Whether reflections-trace-mirrors runs (at divisor 1 every pixel has its own ray anyway).
  bool mirrorPassEnabled() const { return mirrorsAtFullResolution && divisor > 1; }
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

// The four images of a reflection reservoir (shared/reflections_reuse_io.h): sample, radiance,
// origin, normals (ReSTIR GI's encoding).
using ReflectionReservoirImages = std::array<graph::ImageHandle, 4>;

struct TracedReflections {
  graph::ImageHandle traced;  // reflections.traced (shared/specular_io.h)
  // reflections.candidate.*: the same samples as reservoirs of one candidate, for reuse
  ReflectionReservoirImages candidate;
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
