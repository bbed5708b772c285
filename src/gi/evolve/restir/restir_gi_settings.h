// Settings of Evolve's ReSTIR GI chain (`--gi evolve`; seed 000, DESIGN.md §4 step 5). Every
// threshold with its unit and what changing it trades. The shader-side copy is
// gpu::RestirGiConstants (shaders/shared/restir_gi_io.h).
#pragma once
#include <cstdint>
#include <optional>

#include "denoise/library_denoiser.h"

namespace bounce {

// Which denoiser filters the resolved GI (`--denoiser`; docs/denoise.md).
enum class GiDenoiser : uint32_t {
  Evolve = 0,  // gi-temporal-denoise, then on desktop gi-spatial-denoise (seed 000), as switched
               // by temporalDenoise and spatialDenoise below
  Svgf = 1,    // SVGF (denoise/svgf.h) with the `svgf` settings below, on the demodulated signal
  None = 2,    // the resolved signal as it is
  Reblur = 3,  // ReBLUR-style (denoise/reblur.h) with the `reblur` settings below
  Hybrid = 4,  // SVGF or ReBLUR per pixel (denoise/hybrid_denoiser.h), the `hybrid` settings
};

// The library denoiser a GiDenoiser names; none for Evolve's own pair and None.
inline std::optional<DenoiserKind> libraryDenoiser(GiDenoiser d) {
  if (d == GiDenoiser::Svgf) return DenoiserKind::Svgf;
  if (d == GiDenoiser::Reblur) return DenoiserKind::Reblur;
  if (d == GiDenoiser::Hybrid) return DenoiserKind::Hybrid;
  return std::nullopt;
}

// What the radiance stored with a 2nd vertex x2 includes besides its emission.
enum class RestirGiSecondVertex : uint32_t {
  Nee = 0,    // + one NEE sample at x2: one bounce of indirect light, cheapest, biased dark
  Path = 1,   // + NEE + a path traced on from x2 like the reference's: unbiased, a path per pixel
  Cache = 2,  // + NEE + the clipmap irradiance cache at x2 (seed 000's choice): all bounces
              //   for the price of one lookup; biased by the cache's coarseness (cells of 4 cm
              //   near the camera, growing x2 per cascade) and its lag (16 frames/entry).
};

struct RestirGiSettings {
  // GI resolution = render resolution / divisor: 4 quarter (mobile preset), 2 half (desktop
  // preset), 1 full (tests: no upsampling between reservoirs and pixels). Each step down is 4x
  // fewer rays and reservoirs and a blurrier upsample at edges.
  uint32_t divisor = 2;
  RestirGiSecondVertex secondVertex = RestirGiSecondVertex::Cache;
  // Scattering events of a path counted like `bounce reference --max-bounces` (x1 is the 1st, x2
  // the 2nd): 1 leaves only x2's emission, 2 adds NEE at x2, more continues the path (Path).
  // Russian roulette ends most paths well before 16.
  uint32_t maxBounces = 16;
  // gi-restir-temporal merges last frame's reservoir. Off: raw candidates (for comparisons).
  bool temporalReuse = true;
  // Cap on history M, in units of the candidate's M (1). Higher: less noise on static views but
  // slower reaction to changed lighting (a sample lives ~maxM frames); ReSTIR GI uses 20-30.
  // 10 here: the radiance stored with a sample is the cache's at the time, and the cache's
  // multi-bounce light is still building up for many frames, so a long-lived sample holds it
  // back (docs/decisions.md).
  float temporalMaxM = 10.0f;
  // The cap where the pixel's surface moves on screen: movingTemporalMaxM from a motion of
  // movingPixels render pixels per frame on, blended linearly from temporalMaxM below it, and
  // temporalMaxM below 1/32 pixel (the motion vectors: camera and object motion, not the TAA
  // jitter). In motion the denoiser's reprojected history already averages what the
  // reservoirs would, and samples carried along from other primary vertices for 10 frames
  // showed as blotches that trail: along a camera path over sunroom (480x270, H200) HDR-FLIP
  // 0.19 -> 0.17 from frame 16 on with 2. On a still view the cap of 10 flickers less
  // (frame-to-frame FLIP 0.016 against 0.021 with 2; docs/decisions.md, "A lower temporal cap
  // in motion"). Equal to temporalMaxM: no adaptation.
  float movingTemporalMaxM = 2.0f;
  float movingPixels = 0.5f;
  // History reservoirs gi-restir-temporal may merge (seed 000: up to 5): the reprojected one
  // (sub-pixel-aware, Area ReSTIR) and up to 4 more by permutation sampling around it, until
  // the confidence reaches temporalMaxM. More: disocclusions fill in within a frame or two
  // (blurry rather than noisy) at up to 4 extra reservoir reads per pixel; 1 is plain
  // temporal reuse (the unbiased configuration: neighbours' samples carry a Jacobian and no
  // visibility test).
  uint32_t temporalHistorySamples = 5;
  // Frames a sample may live in history (frames since it was traced as a fresh candidate;
  // validation re-traces and reuse keep its age): gi-restir-temporal drops older history
  // reservoirs, so the pixel starts again from its fresh candidate. A sample much brighter
  // than its neighbourhood's mean is rarely outweighed by new candidates (a weight of ~1 against
  // a sum of ~20 at M = 10) and permutation reuse hands it to neighbours meanwhile: without a
  // limit it lingers for tens of frames as a blotch (slow boiling). Lower: shorter blotches,
  // more noise, darker. 0 = no limit, the default: a limit gave no measurable gain in
  // per-frame error on a static view (docs/decisions.md).
  uint32_t maxSampleAge = 0;
  // Validation rays (gi-prepare-diffuse-rays): every validationPeriod-th frame (seed 000: 3)
  // each pixel with history re-traces its reservoir's direction instead of a fresh candidate.
  // Smaller: faster reaction to moved geometry and changed light, fewer new candidates (slower
  // convergence). 0 = never. validationDistance: the re-traced hit counts as moved when it is
  // farther than this fraction of the old hit distance from the old hit (lower: more samples
  // dropped on slightly moving foliage). validationRadiance: a relative change of the summed
  // luminance of a neighbourhood's re-traced samples above this lowers their M by the change
  // (restir_gi_common.glsl, radianceValidity; lower: more reaction to noise; with Path at x2
  // the stored values are ~2x the re-traced ones even on a static view, because the stored
  // ones were selected for being bright, so there it always fires and only costs temporal
  // reuse). Off by default (seed 000 uses 3): on a static view validation frames bring no
  // fresh candidates (a third fewer samples) and the neighbourhood decisions show as 5x5-pixel
  // blotches in the final picture; with it the GI follows a sun jump about twice as fast and
  // the mean is unchanged with temporal reuse alone (docs/decisions.md). Use 3
  // (--restir-validation-period 3) for scenes whose lighting or geometry jumps.
  uint32_t validationPeriod = 0;
  float validationDistance = 0.1f;
  float validationRadiance = 0.25f;
  // Light that appears where no history sample points (a sun jump lighting a new patch) is
  // invisible to validation rays, which re-trace the samples reservoirs hold; it would enter
  // only as fast as the running mean over temporalMaxM candidates lets it. So
  // gi-restir-temporal sums this frame's candidate estimates over the 5x5 GI pixels around
  // (the pixel itself left out, so that the decision does not depend on its own candidate) and
  // keeps a running mean of that sum; where the sum exceeds historyBrightening times the mean
  // in two consecutive frames, history M is scaled by (historyBrightening / ratio)^2.
  // Lower: faster reaction, and more cuts on static views where a few neighbours' candidates
  // happen to find a small bright region, which select (gi_restir_temporal.comp) and brighten.
  // It speeds up a sun jump only a little and brightens static views a little
  // (docs/decisions.md), so off by default (0), like the validation rays it complements; 1.3
  // with validationPeriod 3 for jumping light. Darkening is left to validation rays: the sum of
  // 24 heavy-tailed candidates falls far below its mean often, and cutting M then would only
  // add noise. The lag it cannot remove is the cache's multi-bounce light rebuilding.
  float historyBrightening = 0.0f;
  // Reprojection and reuse accept another primary vertex when it lies within this relative
  // distance (of view depth) of this pixel's tangent plane and its normal's cosine to this one
  // is at least normalTolerance. Looser: more reuse across edges (leaks); tighter: more
  // disocclusion noise on curved or sloped surfaces.
  float planeTolerance = 0.02f;
  float normalTolerance = 0.9f;
  // Reconnection shifts with a Jacobian above this are rejected: they come from grazing or
  // close-contact geometry and make fireflies; rejecting them darkens such corners slightly
  // (bias). Static views never reach it (J = 1).
  float maxJacobian = 10.0f;
  // gi-restir-spatial-0 / -1 (seed 000: 8 samples over a large radius, then 5 over a small
  // one). Each neighbour is shifted by reconnection without a visibility test, so this reuse is
  // biased (blurs indirect shadows; gi-trace-spatial-validation-rays repairs most) and never fed
  // back. More samples: less noise after disocclusion and in rarely-lit regions (small lights),
  // cost linear; a larger radius: faster convergence of dark regions, more blur and leaking
  // across nearby surfaces. Radii in GI pixels, spiral radii growing exponentially from
  // spatialMinRadius. At most 8 samples per pass (RESTIR_GI_MAX_SPATIAL_SAMPLES).
  bool spatialReuse = true;
  // How the spatial passes normalise what they combine: by the confidence of the reservoirs
  // that could have produced the chosen sample (1/Z; Bitterli et al. 2020, Alg. 6, without
  // visibility: one reconnection Jacobian per merged reservoir, no target evaluated), or, when
  // false, by every reservoir's (ReSTIR's biased 1/M), which darkens wherever some neighbours'
  // shifts are rejected (maxJacobian, surfaces at grazing angles). The cost: extra reads of the
  // neighbours' primary vertices, and rare samples that only a few neighbours could produce
  // weigh more.
  bool producerNormalisation = true;
  // The same 1/Z in gi-restir-temporal (its merged history reservoirs' vertices read again).
  // False: 1/M, about 1 % dark in the white furnace (docs/gi/restir-gi.md, "Energy").
  bool temporalProducerNormalisation = true;
  // gi-restir-resolve's weights: the pixel's home reservoir as the canonical one (a direction
  // shift, never refused, weighted 1 - k/n where k of the n reservoirs on the surface could
  // produce its sample; each neighbour's accepted sample 1/n: unbiased over the refused
  // shifts), or, when false, the mean of the reservoirs whose shift is accepted (until session
  // 27 a refused shift counted as zero, darker by the share of refused shifts: Lux 17 %, Evolve
  // 5 % in the white furnace; now only the shifts the Jacobian cap leaves out are missing).
  // True costs variance where the home alone carries the samples its neighbours refuse (with
  // Lux's cap of 2 most of those near the pixel: LuxSettings::unbiasedReuse).
  bool canonicalResolve = true;
  // gi-restir-spatial-0, the wide pass (24 GI pixels), runs only for reservoirs whose
  // confidence M after temporal reuse is below spatialWideMaxM: disocclusions and the frames
  // after a reset or a lighting cut, where seed 000's wide reuse spreads light fast; the others
  // pass through it unchanged to gi-restir-spatial-1. Where history has converged the wide
  // pass added bias more than it removed noise: its neighbours' samples are reused without a
  // visibility test, and the floor in the umbra in front of Cornell's short box came out 30-50 %
  // too bright (docs/decisions.md, "The wide spatial pass only for young reservoirs").
  // 0: every reservoir (seed 000). 3 is also a full history in motion (movingTemporalMaxM, 2,
  // plus this frame's candidate).
  float spatialWideMaxM = 3.0f;
  uint32_t spatialSamples[2] = {8, 5};
  float spatialRadius[2] = {24.0f, 6.0f};
  float spatialMinRadius = 1.0f;
  // gi-trace-spatial-validation-rays: a shadow ray per GI pixel whose final sample came from a
  // neighbour; W = 0 when occluded. Off: cheaper, indirect shadows blur over the spatial radius.
  bool spatialValidation = true;
  // Weight of this frame in the running mean of the spatial occlusion validity mask: higher
  // reacts faster to moving occluders, lower gives a steadier mask (fewer flickering edges).
  float validityBlend = 0.2f;
  // gi-restir-patch-reservoir: rejected reservoirs take the first valid one of their 2x2 patch.
  // Off: pepper noise at indirect shadow edges (then averaged by the denoiser).
  bool patchReservoir = true;
  // gi-restir-resolve: reservoirs evaluated per pixel (own GI pixel first, then a golden-angle
  // spiral within resolveRadius GI pixels). More: smoother and blurrier. 1 with divisor 1 is the
  // unbiased estimate of the pixel's own reservoir.
  uint32_t resolveSamples = 4;
  float resolveRadius = 2.0f;
  // gi-temporal-denoise: running mean of up to denoiseMaxHistory frames with the history clipped
  // to mean +- denoiseClipSigma standard deviations of the 3x3 neighbourhood. More frames or a
  // wider box: smoother, more ghosting after a change. Off for unbiased measurements. 64 (NRD's
  // REBLUR allows 63): a static view keeps converging while the anti-lag and the fast history's
  // clip still follow a change within a few frames (16 before session 27: docs/decisions.md,
  // "A 64-frame GI history").
  // After a reset (the first frames) or a lighting cut, while the cache rebuilds its light
  // (ClipmapCacheSettings::fullRefreshFrames), the stored radiance of every history is that of
  // a darker (or otherwise different) cache: for settleFrames frames temporalMaxM is scaled by
  // settleHistoryScale (at least 1 candidate), so that reservoirs follow the new light instead
  // of averaging it with the old, and gi-temporal-denoise keeps its history length but follows
  // the light with a more sensitive anti-lag (a shorter history there was far noisier:
  // docs/gi/restir-gi.md). Longer or lower: faster convergence of the mean, noisier frames
  // while it lasts. 0 frames = off.
  // (A lighting cut also drops the light-holding histories for one frame: RestirGi::lightingCut.)
  uint32_t settleFrames = 16;
  float settleHistoryScale = 0.2f;
  GiDenoiser denoiser = GiDenoiser::Evolve;
  // With GiDenoiser::Svgf: Falcor's parameters (which measured better than the paper's on the
  // Cornell box) with RELAX's cheaper à-trous (docs/denoise.md).
  SvgfSettings svgf = SvgfSettings::relaxAtrous();
  ReblurSettings reblur;         // with GiDenoiser::Reblur (NRD's defaults)
  HybridDenoiseSettings hybrid;  // with GiDenoiser::Hybrid
  bool temporalDenoise = true;
  float denoiseMaxHistory = 64.0f;
  float denoiseClipSigma = 2.0f;
  // Anti-firefly (as NRD's denoisers have): before accumulating, gi-temporal-denoise clamps
  // the resolved value to fireflyRatio times the brightest of 8 values two GI pixels away
  // (outside the few pixels one reservoir's sample reaches in the resolve) and shares what it
  // cut out among those 8, so that the clamp keeps the energy. Rare samples of huge weight,
  // reconnection shifts with a large Jacobian along concave edges where a neighbour's hit
  // point lies next to this pixel, otherwise stay in one reservoir for frames and show as a
  // dotted line along every wall-ceiling edge. Indirect light is smooth at that scale, so only
  // outliers are touched: lower spreads more, higher lets more dots through; 0 = off.
  // (Rejecting Jacobians above 2 instead of 10 removed the dots too but darkened the picture:
  // docs/decisions.md.)
  float fireflyRatio = 2.0f;
  // gi-shade-diffuse-hits and the continued path read x2's textures at the mip at most this
  // many texels wide (seed 000: "always sample materials at a coarse mip level, to reduce
  // bandwidth"; surface.glsl, coarseTextureLod). The hits of hemisphere rays are scattered, so
  // full-resolution fetches miss the texture cache, and the GI only needs a texture's mean
  // over a footprint many texels wide. Lower: less bandwidth, albedo detail smaller than
  // 1/side of the texture averaged away; 0 = full resolution (the unbiased configuration).
  uint32_t materialTextureSide = 16;
  // Candidate directions from our void-and-cluster blue noise (seed 000; src/core/blue_noise.h)
  // rather than white noise across pixels: neighbouring pixels' directions spread evenly over
  // the hemisphere in each frame, so what the spatial passes and denoisers average has less
  // low-frequency error. Either way each pixel follows an R2 sequence over frames.
  bool blueNoise = true;
  // gi-trace-resolve-visibility: pixels beside an occluder (a GBuffer point one GI pixel away
  // in front of their tangent plane: gaps, inside corners) test the visibility of the samples
  // gi-restir-resolve reuses (up to resolveSamples shadow rays each) and are not blurred by
  // gi-spatial-denoise, so that light seen from a neighbour's primary vertex does not leak
  // behind the occluder; corners get a little darker. It costs shadow rays (most on
  // alpha-tested foliage), so it is off on the mobile preset (docs/decisions.md).
  bool occluderVisibility = true;
  // gi-spatial-denoise after the temporal denoiser (seed 000: desktop only): an edge-aware
  // (same-surface) Gaussian blur of half-width spatialDenoiseRadius pixels. Larger: smoother,
  // loses contact shadows and small indirect detail; cost grows with the square.
  bool spatialDenoise = false;
  uint32_t spatialDenoiseRadius = 2;

  // The unbiased configuration (RestirGi tests): full resolution, temporal reuse only,
  // a continued path at x2, the biased passes (neighbour reuse in the resolve, denoising) off.
  // The presets' values are the presets table's (frame/presets.cpp).
  static RestirGiSettings unbiased() {
    RestirGiSettings s;
    s.divisor = 1;
    s.validationPeriod = 0;  // a validated reservoir replaces the frame's candidate
    s.secondVertex = RestirGiSecondVertex::Path;
    s.resolveSamples = 1;
    s.temporalDenoise = false;
    s.denoiser = GiDenoiser::None;
    s.spatialReuse = false;
    s.spatialValidation = false;
    s.temporalHistorySamples = 1;
    s.movingTemporalMaxM = s.temporalMaxM;
    s.patchReservoir = false;
    s.historyBrightening = 0.0f;  // history confidence from neighbours' candidates
    s.fireflyRatio = 0.0f;
    s.materialTextureSide = 0;  // the reference reads full-resolution textures
    return s;
  }
};

// Throws bounce::Error naming the field when a setting is out of its documented range (the
// library and the command line share this one check; nothing is clamped silently).
void validate(const RestirGiSettings& settings);

}  // namespace bounce
