// Settings of ReSTIR DI (`di-*` passes; seed 002, DESIGN.md §4 step 3): what lights the primary
// vertex from every light of the scene's light tables (KHR point, spot and directional lights,
// emissive triangles; not the sun, which keeps its soft-shadow pass). Defaults after RTXDI
// (research/gi10_lux_denoisers.md §2.3(a)); the shader-side copy is gpu::DiConstants
// (shaders/shared/restir_di_io.h).
#pragma once
#include <cstdint>
#include <optional>
#include <string>

namespace bounce {

// Restir: candidates, temporal and spatial reuse, shade (the default, both presets). Uniform:
// the same candidates and shade without reuse (the variance baseline of the tests). Off: no DI
// passes; composite lights the KHR lights unshadowed, as before ReSTIR DI, and emissive
// triangles light the frame only through the GI's rays.
enum class DiMode { Off, Uniform, Restir };
std::optional<DiMode> diModeFromName(const std::string& name);  // "off", "uniform", "restir"
const char* diModeNames();

// The denoiser of the DI signal (di-denoise-*, di/di_denoise.h; docs/di.md "The denoiser"): one
// of the library denoisers (docs/denoise.md) on di.radiance demodulated by the surface's
// directional albedo. None: composite adds di-shade's single-frame estimate as it is.
enum class DiDenoiser { None, Svgf, Reblur };
std::optional<DiDenoiser> diDenoiserFromName(const std::string& name);  // "none", "svgf", "reblur"
const char* diDenoiserName(DiDenoiser denoiser);
const char* diDenoiserNames();

// The shadow ray of each pixel's new candidate (RTXDI's initial visibility; DiSettings).
enum class DiCandidateVisibility { Auto, On, Off };
// "auto", "on", "off"
std::optional<DiCandidateVisibility> diCandidateVisibilityFromName(const std::string& name);

struct DiSettings {
  DiMode mode = DiMode::Restir;
  // Light candidates per pixel per frame, drawn by power from the alias table (RTXDI: 8 local
  // lights). More: better initial samples, linear cost in target evaluations (no rays). 1 to 64.
  uint32_t lightCandidates = 8;
  // BRDF-sampled candidates per pixel per frame (RTXDI: 1): a ray along a direction drawn from
  // the surface's BRDF; where it hits an emissive triangle of the light table, that point is a
  // candidate. Both kinds of candidate are weighted by the balance heuristic over the two
  // strategies, so each covers what the other samples badly: light sampling the diffuse lobe,
  // BRDF sampling the near-mirror highlight of an area light. Costs a ray per pixel in scenes
  // with emissive triangles (none without). 0 or 1.
  uint32_t brdfCandidates = 1;
  // ... traced only where the surface's specular lobe is at most this rough (perceptual
  // roughness; --lambert surfaces have none): on rougher and diffuse surfaces light sampling
  // alone is good, and the ray cost 0.43 ms at 1080p on `cornell` (H200, docs/benchmarks.md)
  // for no visible gain. The choice is the pixel's own, so each pixel's RIS stays unbiased
  // (there M_B = 0). 0 to 1; 1 traces everywhere (RTXDI's default).
  float brdfCandidateMaxRoughness = 0.5f;
  // One shadow ray for the kept candidate (RTXDI's initial visibility): an occluded sample keeps
  // its M with W = 0, so that reuse does not hand it on. Without it, di-shade's final shadow
  // ray is what drops hidden lights from the history (di.reservoir-final): a ray per pixel
  // saved, and new candidates that are hidden still reach this frame's spatial reuse and come
  // out black. Measured (H100/H200, 1080p; lavapipe tests; docs/di.md "The candidates' shadow
  // ray"): off makes all di-* 17-26 % cheaper where a room's few lights are mostly in view
  // (manylights 0.92 -> 0.72 ms, cornell, spheres) for a noisier frame (manylights' 64th frame
  // relMSE 0.21 -> 0.28; one frame's variance and the mean unchanged); on `city` by night, whose
  // light grid gives each point lamps near it, off costs 0.55 ms less (H100) and the frame's
  // noise between independent runs is the same to 1 %. Off by default; Auto: on with the light
  // grid (lightGridThreshold lights or more), off below it (the default before the grid's shared
  // pool). The unbiased configuration needs it on: its ray-traced correction assumes that no
  // input reservoir holds a hidden light.
  DiCandidateVisibility candidateVisibility = DiCandidateVisibility::Off;
  // Without the candidates' shadow ray, draw the candidates in di-temporal's pass
  // (di-candidates-temporal: the same reservoirs, one surface load and one dispatch less than
  // di-generate-candidates then di-temporal; docs/di.md). false: the two passes, for
  // comparison. Ignored with the ray (it runs between them) and without reuse (--di uniform).
  bool fuseCandidatesWithTemporal = true;
  // Cap on the history reservoir's M, in candidate reservoirs (RTXDI's maxHistoryLength 20).
  // Higher: less noise on static views, slower reaction to changed light. 1 to 1000.
  float temporalMaxM = 20.0f;
  // Reuse (temporal and spatial) only between pixels whose view depths differ by at most this
  // fraction (RTXDI 0.1) and whose normals' cosine is at least normalTolerance (RTXDI 0.5).
  // Looser: more reuse at edges, and light bleeding across them. depth > 0, normal in [-1, 1].
  float depthTolerance = 0.1f;
  float normalTolerance = 0.5f;
  // Neighbours di-spatial merges per pixel (RTXDI 1) and, where the temporal reservoir's M is
  // below disocclusionM (a pixel without history), disocclusionSamples (RTXDI boosts to 8; 3
  // here, the 1-3), within spatialRadius pixels (RTXDI 32). More: less noise, more
  // blur of light across surfaces, a target evaluation (and, unbiased, a ray) each. 0 to 8
  // samples; 0 turns spatial reuse off. Radius 1 to 256 pixels.
  uint32_t spatialSamples = 1;
  uint32_t disocclusionSamples = 3;
  float disocclusionM = 4.0f;
  float spatialRadius = 32.0f;
  // The world-space light grid (ReGIR; di-light-grid, shaders/di/light_grid.glsl, docs/di.md):
  // the candidate source from lightGridThreshold local lights on (the power alias table alone
  // below it, e.g. manylights' 64: a power-proportional draw already finds a room's lights, and
  // the grid's build would cost more than it saves). Above it, a point sees a few of many lights
  // (city by night: 3,072), which the grid's cells find. 0: always the grid; a huge value:
  // never.
  uint32_t lightGridThreshold = 512;
  // Cells along x, y and z (glTF's y is up: fewer cells), 1 to 128 each; a camera-centred box
  // of cubic cells of lightGridCellSize world units (0: the scene bounds' largest extent / 128,
  // so the grid spans a quarter of the scene across and the cells are 5 m in `city`). Outside it
  // every candidate comes from the alias table. More or smaller cells: closer to each point's
  // own lights, more build work (cells x slots x build candidates target evaluations).
  uint32_t lightGridCellsX = 32;
  uint32_t lightGridCellsY = 16;
  uint32_t lightGridCellsZ = 32;
  float lightGridCellSize = 0.0f;
  // Light reservoirs per cell (RTXDI 512, GI-1.0 64; 1 to 1024): each is one light chosen by RIS
  // with the cell's target over the cell's pool of lightGridBuildCandidates power-drawn lights
  // (a multiple of 64 from 64 to 4096), which the cell's slots share. More slots: more distinct
  // lights per cell; a larger pool: the cell's few nearby lights among many found more often.
  uint32_t lightGridSlots = 16;
  uint32_t lightGridBuildCandidates = 256;
  // Of the lightCandidates, how many come from the pixel's cell; the rest from the alias table,
  // which reaches every light, so the estimate stays unbiased where the cell's bound misses one
  // (ReGIR's fallback; light_grid.glsl). At least one candidate always stays the alias table's.
  // 7 of 8: on `city` by night the alias table's draws (lamps streets away) are mostly wasted,
  // and 7 from the grid halve the frame's noise against 6 (docs/di.md, "A pool per cell").
  uint32_t lightGridCandidates = 7;
  // di-shade's final shadow ray is not traced again for a sample that this pixel's own final
  // ray found visible fewer than this many frames ago (RTXDI's reuseFinalVisibility and
  // finalVisibilityMaxAge): the sample is kept through di-temporal and taken as visible (a
  // hidden one was dropped when its ray found it hidden). Saves most final rays on a steady
  // view; a shadow that a moving object casts on a kept sample lags by up to this many frames
  // (moved or switched lights drop the reservoirs anyway). 0 = always trace (the unbiased
  // configuration's). 0 to 64. Default 4.
  uint32_t finalVisibilityMaxAge = 4;
  // Ray-traced bias correction in di-spatial (--di-unbiased): a shadow ray per neighbour to
  // count only the neighbours that could have produced the kept sample (Bitterli et al. 2020,
  // Alg. 6). Off (default, RTXDI's "basic"): no rays; slightly dark near shadow edges.
  bool unbiased = false;
  // The denoiser of the DI signal (above). None by default and in both presets: SVGF removes the
  // speckles (per-pixel variance 44x lower on manylights) but darkens the mean by 5-6 % there,
  // beyond issue 21's 2 %, and does not move Cornell's HDR-FLIP (docs/di.md, "The denoiser").
  // SVGF (SvgfSettings::relaxAtrous()) adds 3 pipelines, ReBLUR 5. Its history is
  // dropped on every frame in which a light switched, dimmed or brightened by more than 2x or
  // moved by more than RestirDi::kDropMove of the scene's extent (restir_di.h), so a
  // changed light does not linger in it.
  DiDenoiser denoiser = DiDenoiser::None;
  // Mixed into every random number of the chain: runs with different seeds are independent
  // (the variance test). 0 by default.
  uint32_t seed = 0;

  bool enabled() const { return mode != DiMode::Off; }
  bool reuses() const { return mode == DiMode::Restir; }
  // Whether the candidates get their shadow ray, with or without the light grid.
  bool tracesCandidateVisibility(bool lightGrid) const {
    return candidateVisibility == DiCandidateVisibility::On ||
           (candidateVisibility == DiCandidateVisibility::Auto && lightGrid);
  }
  // The tests' unbiased configuration.
  static DiSettings unbiasedConfiguration() {
    DiSettings s;
    s.unbiased = true;
    s.candidateVisibility = DiCandidateVisibility::On;
    s.finalVisibilityMaxAge = 0;
    return s;
  }
};

// Throws bounce::Error naming the field when a setting is out of its documented range.
void validate(const DiSettings& settings);

}  // namespace bounce
