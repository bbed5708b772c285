// Settings of the hybrid frame (DESIGN.md §4) and the two presets of seed 000. Every field has
// its default here, with its unit and what changing it trades.
#pragma once
#include <cstdint>
#include <optional>
#include <string>

namespace bounce {

// Which diffuse GI the composite receives. Only `None` exists yet: the GI slot reads zero, so
// the frame shows direct light (plus the optional placeholder ambient below).
enum class GiMode { None };
std::optional<GiMode> giModeFromName(const std::string& name);  // "none"
const char* giModeNames();

// How the vbuffer finds the triangle at each pixel: rasterisation (seed 000) or one camera ray
// per pixel centre through the BVH (for GPUs with little raster hardware, e.g. H100/H200).
enum class VBufferMode { Raster, Trace };
std::optional<VBufferMode> vbufferModeFromName(const std::string& name);  // "raster", "trace"

enum class Preset { Mobile, Desktop };
std::optional<Preset> presetFromName(const std::string& name);  // "mobile", "desktop"
const char* presetNames();

struct HybridSettings {
  // Render resolution in pixels. Presets: mobile 1170x540, desktop 1920x1080 (seed 000).
  uint32_t width = 1920;
  uint32_t height = 1080;
  // Shadow rays are traced at render resolution / shadowDivisor (2 = half res on both presets,
  // as seed 000 does; 1 = full res, 4x the rays, no upsampling blur on thin features).
  uint32_t shadowDivisor = 2;
  // The shadow denoiser's running mean spans at most this many frames: more smooths the soft
  // penumbra (one cone sample per pixel per frame) further but lets moving shadows lag.
  float shadowMaxHistory = 16.0f;
  // Radiance multiplier before the tone curve. At 0.03 a white Lambert surface under a sun of
  // E = 100 W/m^2 (the built-in scenes' sun) maps to about 0.8 on the display.
  float exposure = 0.03f;
  // Weight of a placeholder ambient (unoccluded sky irradiance on the diffuse albedo) for
  // previews while no GI mode exists. Off by default: it ignores occlusion, so closed rooms
  // under a bright sky glow with light that cannot reach them.
  float skyAmbientStrength = 0.0f;
  // Every material pure Lambert with its base colour (--lambert), for comparisons.
  bool lambert = false;
  GiMode gi = GiMode::None;
  // Raster is seed 000's choice and the default; Trace gives the same ids (pixel centres, same
  // alpha test) and is ~3-10x faster on the H200 (README, "The hybrid frame").
  VBufferMode vbuffer = VBufferMode::Raster;
};

// The preset's settings (resolution and shadow resolution); other fields keep their defaults.
HybridSettings presetSettings(Preset preset);

}  // namespace bounce
