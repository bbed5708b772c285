// Settings of `--gi gi10` (src/gi/gi10/gi10_gi.h; research/gi10_lux_denoisers.md §1.9 for
// Capsaicin's defaults). Defaults are the desktop preset's; frame/presets.cpp sets mobile's.
#pragma once
#include <cstdint>

namespace bounce {

struct Gi10Settings {
  // Side in pixels of the tile that spawns one new 64-ray probe per frame: 16 is Capsaicin's
  // QuarterSpp (0.25 probe rays per pixel; desktop), 32 its SixteenthSpp (mobile). A multiple
  // of 8 (the probe tile), 8 to 64.
  uint32_t spawnTile = 16;
  // Hash-grid cells cover about this many pixels' footprint at their distance (Capsaicin: 32).
  float cacheCellPixels = 32.0f;
  // Smallest hash-grid cell edge in metres (Capsaicin: 0.1).
  float minCellSize = 0.1f;
  // A cell no probe ray hit for this many frames is evicted (Capsaicin: 50). At least 1.
  uint32_t decayFrames = 50;
  // The cells' running mean counts at most this many samples (Capsaicin: 16). At least 1.
  uint32_t maxSampleCount = 16;
  // Render pixels per hash-grid slot: the table has the next power of two above
  // width x height / pixelsPerCacheSlot slots (at least 4,096), in buckets of 16, 40 bytes
  // each. 2 gives 1,048,576 slots (40 MiB) at 1920x1080 and keeps the table under a third
  // full on the test scenes (a fuller table overflows buckets: docs/gi/gi10.md). 1 to 1024.
  uint32_t pixelsPerCacheSlot = 2;
  // gi10-reproject-gi averages at most this many frames (Capsaicin: up to 64). 16: feedback
  // (§1.6) reads this history, so each bounce waits on it; at 64 the furnace reached 1.86 of 2
  // after 96 frames, at 16 1.97 (docs/gi/gi10.md). At least 1.
  float historyCap = 16.0f;
  // Temporal radiance feedback (§1.6): probe hits on screen take last frame's GI there.
  bool feedback = true;
  // gi10-blend-screen-probes holds a probe cell back where its new radiance is more than twice
  // the reprojected one (Capsaicin's brightening-only hysteresis, §1.3). Off: each cell holds one
  // ray per trace here, so keeping the darker of old and new biases the probes dark (Cornell box
  // 128x128, 64 frames: mean 0.93 of the path tracer's with it, 0.96 without; docs/gi/gi10.md).
  bool probeHysteresis = false;
  // gi10-filter-gi blurs pixels with fewer than 8 frames of history (§1.7).
  bool filter = true;
  // Probe and shadow rays run the alpha test (desktop); mobile skips it.
  bool alphaTest = true;
  // Probe hits read textures at the mip at most this many texels wide (0: full resolution),
  // as ReSTIR GI's rays do (RestirGiSettings::materialTextureSide).
  uint32_t materialTextureSide = 16;
};

// Throws bounce::Error naming the field when a setting is out of its documented range.
void validate(const Gi10Settings& settings);

}  // namespace bounce
