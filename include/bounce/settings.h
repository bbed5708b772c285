// How a Renderer renders: resolution, the quality preset, the diffuse GI system, exposure.
#pragma once
#include <cstdint>

#include "bounce/config.h"

namespace bounce::api {

// Seed 000's two quality presets (DESIGN.md §4), which differ in more than the resolution:
//
//   |                                        | mobile   | desktop          |
//   | render resolution                      | 1170x540 | 1920x1080        |
//   | sun shadows                            | half     | half             |
//   | diffuse GI resolution (GiMode::Evolve) | quarter  | half             |
//   | cache rays per cell per frame          | 1        | 4 + 4 validation |
//   | alpha test in cache traces             | no       | yes              |
//   | final spatial denoise of the GI        | no       | yes: pass "gi-spatial-denoise" |
enum class Preset { Mobile, Desktop };

// Which diffuse global illumination the frame gets. Evolve: seed 000's ReSTIR GI over the
// clipmap irradiance cache (the full system). Cache: the irradiance cache alone, looked up at
// the primary hit (cheaper, blurrier). None: direct light only (sun, sky, emitters). Lux: seed
// 002's ReSTIR indirect over the same cache as a probe field (docs/gi/lux.md). Gi10: AMD's
// GI-1.0, screen probes over a world-space hash-grid radiance cache (docs/gi/gi10.md).
enum class GiMode { Evolve, Cache, None, Lux, Gi10 };

// The defaults are presetSettings(Preset::Mobile).
struct RendererSettings {
  // Render resolution in pixels, each side 1 .. 16384. The preset's by default, but any size
  // works with either preset (the preset's other choices stay).
  uint32_t width = 1170;
  uint32_t height = 540;
  Preset preset = Preset::Mobile;
  GiMode gi = GiMode::Evolve;
  // Exposure before the tone curve (ACES filmic) of the "tonemap" image. Automatic (the
  // default): metered from each frame's luminance histogram (the mean log luminance of the
  // pixels between the 50th and 95th percentiles mapped to middle grey, 0.18) and adapted over
  // frames as engines do (to brighter light in about 0.3 s, to darker in about 1 s; each
  // render() counts as 1/60 s, and the first frame and the first after resetHistory() take the
  // metered exposure directly), so a scene shows whatever its light; `exposureStops` is then a
  // compensation (+1: twice as bright). Fixed (autoExposure = false): radiance is multiplied by
  // 2^exposureStops; at -5 a white Lambert surface under a sun of E = 100 W/m^2 (the built-in
  // scenes' sun) maps to about 0.8 on the display. exposureStops in [-64, 64].
  bool autoExposure = true;
  float exposureStops = 0.0f;
};

// The preset's resolution and the preset itself; gi and exposure keep their defaults.
RendererSettings presetSettings(Preset preset);

}  // namespace bounce::api
