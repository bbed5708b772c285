// Settings of Evolve's clipmap irradiance cache (seed 000), owned by the cache.
#pragma once
#include <cstdint>

namespace bounce {

// Evolve's clipmap irradiance cache (seed 000; src/gi/evolve/cache/clipmap_cache.h). The defaults
// are the mobile preset's; presetSettings(Desktop) sets the desktop column of DESIGN.md §4.
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
  // per frame, 8 frames bring a closed room's cache close to converged; more frames recover
  // from a sun jump only a little faster, at that much more cost (docs/decisions.md). 0 = off.
  uint32_t fullRefreshFrames = 8;
  float fullRefreshHistoryCap = 1.0f;
  // Bounces the cache adds per full-refresh frame: cache-trace-diffuse-rays and cache-build-sh
  // run this many times (the extra runs neither allocate nor touch cells). The multi-bounce
  // light of a closed room (sunroom: ~10 significant bounces) then rebuilds in a few frames
  // instead of ten or more, for that many times the refresh frames' cache cost; 1 = once.
  uint32_t fullRefreshBounces = 3;
};

// Throws bounce::Error naming the field when a setting is out of its documented range.
void validate(const ClipmapCacheSettings& settings);

}  // namespace bounce
