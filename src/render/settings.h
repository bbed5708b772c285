// Settings of the hybrid frame (DESIGN.md §4) and the two presets of seed 000. Every field has
// its default here, with its unit and what changing it trades.
#pragma once
#include <cstdint>
#include <optional>
#include <string>

#include "gi/evolve/restir_gi_settings.h"

namespace bounce {

// Which diffuse GI the composite receives. `None`: the GI slot reads zero, so the frame shows
// direct light (plus the optional placeholder ambient below). `Evolve`: seed 000's ReSTIR GI
// chain (src/gi/evolve/restir_gi.h, settings in `restirGi`). `Cache`: Evolve's clipmap
// irradiance cache alone (src/gi/evolve/cache_gi.h): irradiance at the primary hit.
enum class GiMode { None, Evolve, Cache };
std::optional<GiMode> giModeFromName(const std::string& name);  // "none", "evolve", "cache"
const char* giModeNames();

// How the vbuffer finds the triangle at each pixel: rasterisation (seed 000) or one camera ray
// per pixel centre through the BVH (for GPUs with little raster hardware, e.g. H100/H200).
enum class VBufferMode { Raster, Trace };
std::optional<VBufferMode> vbufferModeFromName(const std::string& name);  // "raster", "trace"

enum class Preset { Mobile, Desktop };
std::optional<Preset> presetFromName(const std::string& name);  // "mobile", "desktop"
const char* presetNames();

// Evolve's clipmap irradiance cache (seed 000; src/gi/evolve/clipmap_cache.h). The defaults are
// the mobile preset's; presetSettings(Desktop) sets the desktop column of DESIGN.md §4.
struct ClipmapCacheSettings {
  // Side of a cell of the finest cascade, metres; cascade c has cells 2^c times larger (12
  // cascades of 32^3 cells). Smaller cells resolve more detail near the camera but need more
  // live cells (and rays) for the same view.
  float finestCellSize = 0.04f;
  // New candidates per cell per frame (1, 2, 4, 8 or 16): every entry of a cell is refreshed
  // each 16 / raysPerCell frames. Mobile 1, desktop 4. Cost is linear in it.
  uint32_t raysPerCell = 1;
  // Rays per cell per frame that re-trace kept samples so that entries follow lighting changes
  // at once (at most raysPerCell). Mobile 0, desktop 4.
  uint32_t validationRaysPerCell = 0;
  // Alpha-tested cache rays: exact cut-outs (foliage) at the cost of texture reads in
  // traversal. Mobile off (cut-outs count as solid: some darkening), desktop on.
  bool alphaTest = false;
  // Largest candidate count M a reservoir keeps: more averages out noise over more frames
  // (x 16 / raysPerCell) but reacts more slowly when light changes without validation.
  float historyCap = 16.0f;
  // Frames without a lookup after which a cell is freed (seed 000: 4).
  uint32_t maxStaleFrames = 4;
  // Most live cells: seed 000's hard cap of 65,535 (the buffers are sized for it). Lower values
  // exist for tests of what happens when the pool runs dry (lookups then fall back to coarser
  // cells and count an allocation failure).
  uint32_t maxLiveCells = 65535;
  // The cells' rays read textures at the mip at most this many texels wide, as ReSTIR GI's
  // rays do (RestirGiSettings::materialTextureSide: seed 000's coarse mip, less bandwidth for
  // incoherent hits; a cell only needs mean albedos). 0 = full resolution.
  uint32_t materialTextureSide = 16;
  // Frames after a reset (the first frames) or a lighting cut (HybridFrame::setSunAndSky: the
  // sun jumped) in which every live cell traces all 16 entries each frame, with history capped
  // at fullRefreshHistoryCap candidates, instead of raysPerCell, fullRefreshBounces times. Light
  // then crosses that many bounces per frame (otherwise one per refresh round of 16 /
  // raysPerCell frames, each diluted by the entry's 1/M). Cost: 16 rays per cell and bounce in
  // those frames (desktop 2x, mobile 16x the usual cache rays, per bounce). With three bounces
  // per frame, 8 frames (24 bounces) bring sunroom's cache to 0.97 of converged; 16 frames
  // recovered from a sun jump a little faster (README), at twice the cost. 0 = off.
  uint32_t fullRefreshFrames = 8;
  float fullRefreshHistoryCap = 1.0f;
  // Bounces the cache adds per full-refresh frame: cache-trace-diffuse-rays and cache-build-sh
  // run this many times (the extra runs neither allocate nor touch cells). The multi-bounce
  // light of a closed room (sunroom: ~10 significant bounces) then rebuilds in a few frames
  // instead of ten or more, for that many times the refresh frames' cache cost; 1 = once.
  uint32_t fullRefreshBounces = 3;
};

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
  // A sun that turns by more than this many degrees from one frame to the next (or whose
  // irradiance, or the sky's radiance, changes by more than half) makes a lighting cut
  // (HybridFrame::setSunAndSky). A day that lasts 24 minutes turns the sun 0.004 degrees per
  // frame at 60 fps; a jump is a scripted change of the time of day. 0 = every change is a cut;
  // a negative value: never.
  float lightingCutDegrees = 5.0f;
  RestirGiSettings restirGi;  // --gi evolve
  ClipmapCacheSettings cache;  // --gi cache (and the cache ReSTIR GI reads)
};

// The preset's settings (resolution, shadow resolution, cache rays); other fields keep their
// defaults.
HybridSettings presetSettings(Preset preset);

}  // namespace bounce
