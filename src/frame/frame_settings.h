// Settings of the hybrid frame (DESIGN.md §4): the frame's own fields and, by value, the
// settings structs of the components it runs (each documented where it is owned). The two
// presets of seed 000 are one table in frame/presets.h.
#pragma once
#include <cstdint>
#include <optional>
#include <string>

#include <vulkan/vulkan.h>

#include "di/di_settings.h"
#include "gi/evolve/cache/clipmap_cache_settings.h"
#include "gi/evolve/restir/restir_gi_settings.h"
#include "gi/gi10/gi10_settings.h"
#include "gi/lux/lux_settings.h"
#include "passes/auto_exposure.h"
#include "passes/reflections_denoise.h"
#include "passes/reflections_trace.h"
#include "passes/shadows_trace.h"
#include "passes/taa.h"
#include "passes/vbuffer.h"

namespace bounce {

// Which diffuse GI the composite receives. `None`: the GI slot reads zero, so the frame shows
// direct light (plus the optional placeholder ambient below). `Evolve`: seed 000's ReSTIR GI
// chain (src/gi/evolve/restir/restir_gi.h, settings in `restirGi`). `Cache`: Evolve's clipmap
// irradiance cache alone (src/gi/evolve/cache_gi.h): irradiance at the primary hit. `Lux`: seed
// 002's ReSTIR indirect over the cache as a probe field (src/gi/lux/lux_gi.h, settings in `lux`).
// `Gi10`: AMD's GI-1.0 (src/gi/gi10/gi10_gi.h, settings in `gi10`).
enum class GiMode { None, Evolve, Cache, Lux, Gi10 };
// "none", "evolve", "cache", "lux", "gi10"
std::optional<GiMode> giModeFromName(const std::string& name);
const char* giModeNames();

struct HybridSettings {
  // Render resolution in pixels. Presets: mobile 1170x540, desktop 1920x1080 (seed 000).
  uint32_t width = 1920;
  uint32_t height = 1080;
  ShadowSettings shadows;          // shadows-trace, shadows-denoise
  ReflectionSettings reflections;  // reflections-trace, the reuse passes, -trace-mirrors
  ReflectionDenoiseSettings reflectionDenoise;  // reflections-denoise-temporal, -spatial
  // Exposure before the tone curve. Automatic (the default, both presets): metered from each
  // frame's luminance histogram and adapted over frames (passes/auto_exposure.h, settings in
  // `exposure`), with `exposureStops` as compensation (+1: twice as bright); 0 = middle grey
  // where the scene's metered level is. Fixed (autoExposure = false, `--exposure STOPS`): radiance
  // is multiplied by 2^exposureStops; at -5 stops a white Lambert surface under a sun of
  // E = 100 W/m^2 (the built-in scenes' sun) maps to about 0.8 on the display. -64 to 64.
  bool autoExposure = true;
  float exposureStops = 0.0f;
  AutoExposureSettings exposure;
  // Weight of a placeholder ambient (unoccluded sky irradiance on the diffuse albedo) for
  // previews while no GI mode exists. Off by default: it ignores occlusion, so closed rooms
  // under a bright sky glow with light that cannot reach them.
  float skyAmbientStrength = 0.0f;
  // Every material pure Lambert with its base colour (--lambert), for comparisons.
  bool lambert = false;
  GiMode gi = GiMode::None;
  // Raster is seed 000's choice and the default; Trace gives the same ids (pixel centres, same
  // alpha test) and is faster on GPUs with little raster hardware (docs/frame.md).
  VBufferMode vbuffer = VBufferMode::Raster;
  // A sun that turns by more than this many degrees from one frame to the next (or whose
  // irradiance, or the sky's radiance, changes by more than half) makes a lighting cut
  // (HybridFrame::setSunAndSky). A day that lasts 24 minutes turns the sun 0.004 degrees per
  // frame at 60 fps; a jump is a scripted change of the time of day. 0 = every change is a cut;
  // a negative value: never.
  float lightingCutDegrees = 5.0f;
  // ReSTIR DI: every light but the sun, shadowed, at the primary vertex (--di; restir in both
  // presets and by default). Off: composite's unshadowed loop over the KHR lights.
  DiSettings di;
  // Temporal anti-aliasing (`taa` after composite, src/passes/taa.h): off here, so library
  // frames and the tests sample pixel centres unless they ask; `bounce render` turns it on
  // (--no-taa: off).
  TaaSettings taa;
  RestirGiSettings restirGi;   // --gi evolve
  ClipmapCacheSettings cache;  // --gi cache (and the cache ReSTIR GI reads)
  LuxSettings lux;             // --gi lux (its reuse takes restirGi's settings)
  Gi10Settings gi10;           // --gi gi10
  // Added to the frame index that seeds every pass's random numbers: frames of two seeds draw
  // independent noise (tests compare independent runs of one view). 0 by default.
  uint32_t noiseSeed = 0;

  VkExtent2D resolution() const { return {width, height}; }
};

// Throws bounce::Error naming the field when a setting, the frame's own or a component's, is
// out of its documented range: the one check the library and the command line share.
void validate(const HybridSettings& settings);

}  // namespace bounce
