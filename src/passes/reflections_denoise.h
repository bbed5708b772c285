// `reflections-denoise-temporal` and `reflections-denoise-spatial` (DESIGN.md §4 step 6;
// docs/reflections.md): the reflection denoiser between the traced (or reused) reflection signal
// and reflections-upsample, at the traced resolution.
//   - temporal: a running mean of the demodulated signal, reprojected by the reflected virtual
//     image point for smooth surfaces and by the surface for rough ones, its length set by
//     roughness, validated against the surface history keeps, cut where the neighbourhood's
//     fresh samples disagree with its history (shaders/passes/reflections_denoise_temporal.comp);
//   - spatial: a few-tap edge-stopping filter within the reflection lobe's footprint
//     (shaders/passes/reflections_denoise_spatial.comp).
// The input is any image of reflections.traced's format and meaning (shared/specular_io.h): the
// passes do not care whether one ray or a resampling pass produced it. The signal is demodulated
// (divided by the lobe's weight; composite multiplies the split-sum reflectance back), so both
// filters average incident radiance, never albedo or Fresnel: GI-1.1's ratio estimator.
#pragma once
#include "passes/reflections_trace.h"
#include "shared/reflections_denoise_io.h"

namespace bounce {

// The reflection denoiser's knobs. Each: unit, default (both presets), what it trades.
struct ReflectionDenoiseSettings {
  // Off (`--reflection-denoise off`): reflections-upsample reads the traced signal as it is.
  bool enabled = true;
  // History length in frames of a mirror (perceptual roughness 0): the running mean averages at
  // most this many frames. A mirror's signal carries little noise (one direction; only the light
  // sampling at the hit varies), and what it shows moves with everything the mirror sees, so a
  // short history keeps it responsive. 1 to 256.
  float mirrorHistoryFrames = 6.0f;
  // History length in frames at glossyHistoryRoughness and above; in between it grows linearly
  // with roughness. One ray per pixel of a wide lobe is noisy, and a wide lobe blurs motion
  // anyway: a long history costs little lag there. The variance of a converged pixel falls as
  // 1 / frames. mirrorHistoryFrames to 256.
  float glossyHistoryFrames = 32.0f;
  float glossyHistoryRoughness = 0.5f;  // perceptual roughness, > 0 and <= 1
  // Perceptual roughness at and above which history is reprojected with the surface alone
  // (velocity). Below it, a share 1 - roughness / limit of the history comes from where the
  // reflected virtual image point (camera + view ray x (surface distance + hit distance)) was
  // last frame: for a narrow lobe the reflection moves like that point, not like the surface;
  // for a wide lobe the hit distance of one sample says little about what the lobe sees. 0 =
  // surface reprojection only. 0 to 1.
  float virtualRoughnessLimit = 0.5f;
  // History and spatial taps count only on this pixel's surface: within planeTolerance x view
  // depth of its tangent plane (0.02: 2 cm at 1 m), with perceptual roughness within
  // roughnessTolerance (0.1) and shading normals within mirrorNormalToleranceDegrees +
  // atan(alpha), at most normalToleranceDegrees: a normal turned by t turns the reflection by
  // 2 t, which a lobe of GGX alpha = roughness^2 hides while t <= atan(alpha); a mirror's
  // reflection differs from its neighbour's as soon as the normal does. Tighter: less bleeding
  // of one reflection into another (ghosts on curved mirrors), more pixels without history
  // after motion (noisier).
  float planeTolerance = 0.02f;
  float mirrorNormalToleranceDegrees = 5.0f;  // > 0 to normalToleranceDegrees
  float normalToleranceDegrees = 25.0f;       // > 0 to 180
  float roughnessTolerance = 0.1f;            // > 0
  // History is cut to responsiveFrames where the 8 neighbours' fresh samples disagree with
  // their histories by more than ghostSigma standard errors (of the samples' variance, pooled):
  // what the reflection shows changed (a moving object, light). The test never looks at the
  // pixel's own samples, so it cannot bias the pixel's mean. Lower: faster response, more
  // cuts from noise alone. 0 = never cut (> 0 otherwise).
  float ghostSigma = 3.0f;
  float responsiveFrames = 2.0f;  // 1 to mirrorHistoryFrames
  // The fast history: a running mean of at most fastHistoryFrames frames kept beside the slow
  // one (reflections.temporal-fast). Where the 8 neighbours' slow histories differ from their
  // fast ones by more than lagSigma standard errors (a paired Student-t test, 7 degrees of
  // freedom; the default 5.4 is its two-sided 0.1 % level), the slow histories lag a change (a
  // ghost left by motion) and this pixel's restarts from its fast one. The fast history
  // follows a change within a few frames; longer: a more precise test, slower to notice. Lower
  // lagSigma: ghosts leave sooner, more restarts from noise alone on static views (each a
  // shorter, noisier history). 0 = never. fastHistoryFrames 1 to mirrorHistoryFrames; lagSigma
  // 0 or more.
  float fastHistoryFrames = 4.0f;
  float lagSigma = 5.4f;
  // Where the view moved at a pixel, a history pixel counts only if it reflected what this
  // frame's sample reflects: its running mean of the parallax (hit distance / (camera distance
  // + hit distance), 1 for a miss) within this much of the sample's. Reprojected by its virtual
  // image point or by the surface, a pixel next to a reflection's edge lands on history that
  // saw another object at another depth (a disocclusion in the reflected scene, which the
  // surface tests cannot see on a flat floor); each frame of motion moved some of that light,
  // and the running mean kept it for glossyHistoryFrames (docs/reflections.md, "Motion"; NRD
  // ReBLUR checks the virtual history's hit distance for the same reason). A static view is
  // never tested, so its running mean is as before. Lower: fewer trails, shorter histories
  // while moving. 0 = no test. 0 to 1.
  float motionParallaxTolerance = 0.05f;
  // The spatial filter's radius in traced pixels: the reflection lobe's footprint on screen
  // (a lobe of half-angle ~2 alpha, seen at the hit distance through the surface) times
  // spatialFootprintScale, at most spatialMaxRadius. A mirror's footprint is 0: no spatial
  // blur. Larger: smoother glossy reflections, blurred beyond what the lobe itself blurs.
  // spatialMaxRadius 0 = no spatial filter; 0 to 16. spatialFootprintScale 0 to 4.
  float spatialMaxRadius = 4.0f;
  float spatialFootprintScale = 1.0f;
  // Tests only: every 5th traced sample becomes NaN or Inf before the temporal pass sanitizes
  // it (tests/test_reflections_denoise.cpp shows history stays finite).
  bool poisonInput = false;
};

// Throws bounce::Error naming the field when a setting is out of its documented range.
void validate(const ReflectionDenoiseSettings& settings);

class ReflectionsDenoisePass {
 public:
  ReflectionsDenoisePass(vk::Context& context, const GpuScene& gpuScene,
                         const ReflectionDenoiseSettings& settings);
  // `traced`: the signal to denoise (reflections.traced's format); `constants`: the trace's
  // push constants this frame (ReflectionsTracePass::constants). `lightingCut`-free frames keep
  // history; after a lighting cut it starts afresh. Returns reflections.denoised, of the same
  // format at the same resolution.
  TracedReflections declare(graph::FrameGraph& graph, const FrameContext& frame,
                            const GBuffer& gbuffer, const TracedReflections& traced,
                            const gpu::ReflectionPassConstants& constants);

 private:
  gpu::ReflectionDenoiseConstants constants(const gpu::ReflectionPassConstants& trace) const;

  ReflectionDenoiseSettings settings_;
  ComputePass temporal_;
  ComputePass spatial_;
};

}  // namespace bounce
