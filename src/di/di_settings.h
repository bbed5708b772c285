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
  // One shadow ray for the kept candidate (RTXDI's initial visibility, on): an occluded sample
  // keeps its M with W = 0, so reuse does not hand it to neighbours. Off saves a ray per pixel
  // and shows as light leaking across shadow edges after reuse; the unbiased configuration
  // needs it on.
  bool candidateVisibility = true;
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
  // Ray-traced bias correction in di-spatial (--di-unbiased): a shadow ray per neighbour to
  // count only the neighbours that could have produced the kept sample (Bitterli et al. 2020,
  // Alg. 6). Off (default, RTXDI's "basic"): no rays; slightly dark near shadow edges.
  bool unbiased = false;
  // Mixed into every random number of the chain: runs with different seeds are independent
  // (the variance test). 0 by default.
  uint32_t seed = 0;

  bool enabled() const { return mode != DiMode::Off; }
  bool reuses() const { return mode == DiMode::Restir; }
  // The tests' unbiased configuration.
  static DiSettings unbiasedConfiguration() {
    DiSettings s;
    s.unbiased = true;
    return s;
  }
};

// Throws bounce::Error naming the field when a setting is out of its documented range.
void validate(const DiSettings& settings);

}  // namespace bounce
