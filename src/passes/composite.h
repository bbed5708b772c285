// `composite` (DESIGN.md §4 step 7): the frame's radiance before exposure, with the reference's
// glTF BRDF for every light: direct sun x its denoised visibility, the KHR punctual and
// directional lights, indirect light split between the diffuse and specular lobes by the
// split-sum directional albedo (diffuse GI and the reflection signal), emission, and the sky
// where no surface is seen (shaders/passes/composite.comp, docs/reflections.md).
#pragma once
#include "graph/frame_graph.h"
#include "passes/frame_context.h"
#include "passes/gbuffer.h"
#include "passes/image_pass.h"
#include "passes/shadows_denoise.h"
#include "passes/sky.h"
#include "shared/specular_io.h"

namespace bounce {

class SpecularAlbedoTable;

// The lit signals composite adds to the direct light.
struct IndirectLight {
  graph::ImageHandle diffuse;      // gi.diffuse: radiance per unit albedo (gi/diffuse_gi.h)
  graph::ImageHandle reflections;  // reflections: demodulated specular light (shared/specular_io.h)
  // Pixels up to this perceptual roughness take their specular light from `reflections`, the
  // rest from `diffuse`; negative: no reflection pass, every pixel takes it from `diffuse`.
  float reflectionMaxRoughness = -1.0f;
};

// The direct light of the lights other than the sun.
struct DirectLightImage {
  // di.radiance (src/di/restir_di.h) where FRAME_FLAG_DI_LIGHTS is set; otherwise a zero image
  // that composite ignores, lighting the KHR lights itself, unshadowed.
  graph::ImageHandle radiance;
};

struct HdrImage {
  graph::ImageHandle radiance;  // composite.hdr: rgba16f, W/(m^2 sr)
};

class CompositePass {
 public:
  // `specularAlbedo` must outlive the pass.
  CompositePass(vk::Context& context, const GpuScene& scene,
                const SpecularAlbedoTable& specularAlbedo);
  HdrImage declare(graph::FrameGraph& graph, const FrameContext& frame, const GBuffer& gbuffer,
                   const Shadows& shadows, const DirectLightImage& direct, const SkyImage& sky,
                   const IndirectLight& indirect);

 private:
  const SpecularAlbedoTable& specularAlbedo_;
  ComputePass pass_;
};

}  // namespace bounce
