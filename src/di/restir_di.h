// ReSTIR DI (seed 002's "ReSTIR Direct"; DESIGN.md §4 step 3; docs/di.md): every light of the
// scene's light tables (KHR point, spot and directional lights, emissive triangles) sampled and
// shadowed at the primary vertex by resampling, a straight chain of passes:
//
//   di-light-grid           (many lights only) the world-space light grid around the camera
//   di-generate-candidates  RIS over DiSettings::lightCandidates candidates (+ 1 shadow ray,
//                           DiSettings::candidateVisibility)
//   di-temporal             + last frame's reservoir at the reprojected pixel (M <= 20); the
//                           two as one pass, di-candidates-temporal, without the shadow ray
//   di-spatial              + 1-3 neighbours within 32 px, bias correction
//   di-shade                the final sample with the full BRDF and a shadow ray: di.radiance
//   di-denoise-*            (DiSettings::denoiser) SVGF or ReBLUR on the demodulated
//                           di.radiance: di.denoised (di_denoise.h)
//
// DiMode::Uniform declares only the candidates and the shade (no reuse). The sun is not among
// the lights: its dedicated soft-shadow pass (shadows-trace, shadows-denoise) shades it with one
// cone sample per pixel and a denoiser, which one light does not need resampling for. A scene
// without any of these lights runs no DI pass at all (hasLights(); the frame then drops its
// RestirDi and composite reads no DI).
//
// The GI and reflection rays of the frame skip the emission of every emitter DI samples
// (FRAME_FLAG_DI_LIGHTS: the light tables' materials with materialLightAreaPdf > 0), so that
// direct and indirect light add up without double counting; large emitters, which the tables
// leave to rays, stay the GI's.
//
// Light animation: setLights() and instancesMoved() rewrite the light tables in place (every
// light keeps its index for the scene's lifetime, lighting/light_table.h), uploaded by
// `di-lights-update` at the start of the next frame; nothing is allocated on the GPU. Stored
// reservoirs therefore never name another light than the one they sampled; they hold a light's
// index and its u, and every pass re-evaluates the sample with the light's current state, so a
// moved, dimmed or switched-off light is accounted for from the next frame on. A light that
// switches on (or brightens by more than kHistoryDropRise), or moves into view, is missing from
// every reservoir's history, which would hold it back by up to the M cap (20 frames): that frame
// drops di-temporal's history (docs/di.md, "Light animation"), and the DI denoiser's.
#pragma once
#include <optional>
#include <span>
#include <vector>

#include "di/di_denoise.h"
#include "di/di_generate_candidates.h"
#include "di/di_light_grid.h"
#include "di/di_settings.h"
#include "di/di_shade.h"
#include "di/di_spatial.h"
#include "di/di_temporal.h"
#include "lighting/gpu_light_tables.h"

namespace bounce {

class RestirDi {
 public:
  // `settings` must be enabled() and valid. Compiles no pipeline when the scene has no lights.
  RestirDi(vk::Context& context, const GpuScene& gpuScene, const Scene& scene,
           const DiSettings& settings);

  // Whether the light tables hold any light (local or distant; the sun is not DI's): without,
  // every pass would find nothing, so the frame runs none (and declare() must not be called).
  bool hasLights() const { return shade_.has_value(); }
  // Whether di-light-grid runs (at least DiSettings::lightGridThreshold local lights).
  bool usesLightGrid() const { return grid_.has_value(); }
  // Whether frames declare the grid's debug view (kDiGridView, di-light-grid-view); only with
  // the grid.
  void showLightGrid(bool on) { showLightGrid_ = on && grid_.has_value(); }

  // The chain; the returned radiance is di.denoised when a denoiser is on (di.radiance, the
  // raw estimate, stays di-shade's image).
  DirectLight declare(graph::FrameGraph& graph, const FrameContext& frame, const GBuffer& gbuffer);

  // The scene's punctual lights from the next frame on: Scene::lights with positions,
  // directions, colours and intensities changed (0: off), the same count and types.
  void setLights(std::span<const PunctualLight> lights);
  // The GpuScene's instances moved (GpuScene::setInstanceTransforms): emissive triangles follow.
  void instancesMoved();

  // A light whose power rises by more than this factor in one frame, or a punctual light or
  // emissive triangle that moves by more than kDropMove of the scene bounds' largest extent,
  // drops the DI history: di-temporal's reservoirs miss a light that came on or moved into
  // view, and their confidence (M up to 20) would hold it back for up to 20 frames. Small steps
  // (manylights' lights bob by at most 2 cm a frame in a 12-m room at 30 fps) keep it.
  static constexpr double kHistoryDropRise = 2.0;
  static constexpr double kDropMove = 0.01;
  // The DI denoiser's history is dropped on those changes and also when a light dims or
  // switches off (power falls by more than kHistoryDropRise) or a spot turns by more than about
  // 8 degrees: the reservoirs re-evaluate their samples, but the denoiser averages some 20-40
  // frames without a per-pixel anti-lag, and would fade the old light out over as many.

  // Compute pipelines the chain compiles (one per pass; di-lights-update is a copy).
  uint32_t pipelineCount() const;

 private:
  bool lightsChanged(std::span<const PunctualLight> lights, bool reservoirs) const;
  bool emittersMoved(const std::vector<gpu::GpuEmissiveTriangle>& before) const;

  DiSettings settings_;
  GpuLightTables lights_;
  double dropDistance_ = 0.0;                           // kDropMove x the scene's largest extent
  bool dropDenoiseHistory_ = false;                     // for the next frame that runs
  std::vector<PunctualLight> lightState_;               // the lights as last set
  bool dropHistory_ = false;                            // for the next frame that runs
  bool showLightGrid_ = false;                          // declare the grid's debug view
  vk::Buffer constants_;                                // gpu::DiConstants
  std::optional<DiLightGridPass> grid_;                 // from lightGridThreshold local lights on
  std::optional<DiGenerateCandidatesPass> candidates_;  // none where di-temporal draws them
  std::optional<DiTemporalPass> temporal_;              // DiMode::Restir only
  std::optional<DiSpatialPass> spatial_;                // DiMode::Restir with spatial samples
  std::optional<DiShadePass> shade_;
  std::optional<DiDenoise> denoise_;  // DiSettings::denoiser != None
};

}  // namespace bounce
