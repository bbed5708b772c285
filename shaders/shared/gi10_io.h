// `--gi gi10`: AMD's GI-1.0 as Capsaicin implements it (research/gi10_lux_denoisers.md §1;
// src/gi/gi10/gi10_gi.h). The layouts its passes share with the C++ side.
//
// Buffers (made once, sized from the resolution; Gi10Constants holds their addresses):
//   probes[2]        Gi10Probe per 8x8-pixel tile, ping-pong (current / previous frame)
//   radiance[2]      uvec2 per probe cell (64 per tile): fp16 rgb radiance, fp16 hit distance
//   sh               9 x vec3 per tile: the probe's radiance projected on L2 SH
//   spawn            uvec2 per spawn tile: this frame's new probe's pixel (GI10_NO_SPAWN: none)
//   rays             Gi10Ray per spawned probe cell
//   cache            Gi10CacheCell per hash-grid slot: buckets x GI10_BUCKET_SLOTS
//   counters         Gi10Counters, zeroed each frame (live cells: counted by the purge)
// Images (set 1):
//   gi10.irradiance  RGBA16F  gi10-interpolate-screen-probes: irradiance / pi, a = 1 where
//                             some probe matched the pixel (the denoiser's hint, §1.3)
//   gi10.gi          RGBA16F  (history) gi10-reproject-gi: accumulated irradiance / pi,
//                             a = history length in frames
//   gi10.gi-delta    RG16F    (history) gi10-reproject-gi: x = exponential mean of the luma
//                             change (§1.7's alpha blend)
//   gi10.filter-x    RGBA16F  gi10-filter-gi's first (horizontal) pass
#ifndef BOUNCE_SHARED_GI10_IO_H
#define BOUNCE_SHARED_GI10_IO_H
#include "shared/compat.h"

BOUNCE_BEGIN_SHARED

BOUNCE_CONST uint GI10_PROBE_SIZE = 8u;     // probe: 8x8 cells; probe tile: 8x8 pixels (§1.3)
BOUNCE_CONST uint GI10_PROBE_CELLS = 64u;   // GI10_PROBE_SIZE^2
BOUNCE_CONST uint GI10_BUCKET_SLOTS = 16u;  // cells per hash bucket, probed linearly (§1.4)
BOUNCE_CONST uint GI10_NO_CELL = 0xFFFFFFFFu;
BOUNCE_CONST uint GI10_NO_SPAWN = 0xFFFFFFFFu;
BOUNCE_CONST uint GI10_GROUP_SIZE = 64u;  // 1-D passes
// Radiance added into a cell's scratch as uint, times this (§1.12: uint atomics, no float ones).
BOUNCE_CONST float GI10_CACHE_QUANTIZE = 1000.0f;
// A sample's radiance is clamped to this before quantizing, and a cell takes at most
// GI10_CACHE_MAX_FRAME_SAMPLES samples a frame: the uint sums cannot overflow.
BOUNCE_CONST float GI10_CACHE_MAX_SAMPLE = 1000.0f;
BOUNCE_CONST uint GI10_CACHE_MAX_FRAME_SAMPLES = 1024u;
// A probe ray that leaves the scene: its hit distance is stored as this (fp16's largest value).
BOUNCE_CONST float GI10_MISS_DISTANCE = 65504.0f;

BOUNCE_CONST uint GI10_PROBE_VALID = 1u;    // the tile has a probe this frame
BOUNCE_CONST uint GI10_PROBE_HISTORY = 2u;  // its radiance was reprojected from last frame's
BOUNCE_CONST uint GI10_PROBE_SPAWNED = 4u;  // traced this frame

BOUNCE_CONST uint GI10_FLAG_ALPHA_TEST = 1u;  // probe and shadow rays run the alpha test
BOUNCE_CONST uint GI10_FLAG_FEEDBACK = 2u;    // temporal radiance feedback (§1.6)
BOUNCE_CONST uint GI10_FLAG_FILTER = 4u;      // gi10-filter-gi blurs short-history pixels (§1.7)
BOUNCE_CONST uint GI10_FLAG_HYSTERESIS = 8u;  // gi10-blend-screen-probes damps brightening (§1.3)

struct Gi10Probe {
  vec3 position;  // world position of the probe's seed pixel
  uint flags;     // GI10_PROBE_*
  vec3 normal;    // geometric normal there: the probe's hemisphere
  float depth;    // view depth of the seed pixel
};
BOUNCE_CHECK_SIZE(Gi10Probe, 32);

struct Gi10Ray {
  vec3 radiance;      // what reaches the probe without the cache: sky, emission, bypassed hits
  float hitDistance;  // GI10_MISS_DISTANCE on a miss
  uint cell;          // the hash-grid cell whose filtered radiance is added; GI10_NO_CELL: none
};
BOUNCE_CHECK_SIZE(Gi10Ray, 20);

struct Gi10CacheCell {
  uint checksum;     // 0: free
  uint lastFrame;    // the frame a probe ray last hit it (eviction after decayFrames)
  uint sampleCount;  // samples in `radiance`, at most Gi10Constants::maxSampleCount
  vec3 radiance;     // outgoing radiance of the cell's surface (direct light + feedback)
  uvec4 scratch;     // this frame's samples: quantized rgb sums and the count
};
BOUNCE_CHECK_SIZE(Gi10CacheCell, 40);

struct Gi10Counters {
  uint probeRays;          // probe rays traced
  uint spawnedProbes;      // probes traced this frame
  uint reprojectedProbes;  // tiles whose probe came from last frame
  uint emptyTiles;         // surface tiles without a probe this frame
  uint cacheInserts;       // probe-ray samples added to the cache
  uint cacheOverflow;      // samples dropped: their bucket was full
  uint liveCells;          // cells alive after the purge
  uint feedbackHits;       // probe-ray hits lit by last frame's GI (§1.6)
};
BOUNCE_CHECK_SIZE(Gi10Counters, 32);

// Written each frame by gi10-clear-counters; every pass reads it through Gi10PassConstants.
struct Gi10Constants {
  DeviceAddress lights;  // gpu::LightTables
  DeviceAddress probes;  // Gi10Probe[], this frame's
  DeviceAddress previousProbes;
  DeviceAddress radiance;  // uvec2[], this frame's
  DeviceAddress previousRadiance;
  DeviceAddress sh;  // vec3[9 * tiles]
  DeviceAddress spawn;
  DeviceAddress rays;
  DeviceAddress cache;
  DeviceAddress counters;
  uvec2 probeGrid;  // tiles of 8x8 pixels
  uvec2 spawnGrid;  // spawn tiles of spawnTile x spawnTile pixels
  uint spawnTile;
  uint bucketMask;  // buckets - 1 (a power of two)
  uint historyValid;
  uint flags;  // GI10_FLAG_*
  // World size of one pixel's footprint at view depth 1: 2 tan(fovY / 2) / height.
  float pixelFootprint;
  float cacheCellPixels;  // hash cells cover this many pixels' footprint (32)
  float minCellSize;      // metres
  uint decayFrames;       // a cell untouched this long is evicted (50)
  uint maxSampleCount;    // the cache's running mean counts at most this many samples (16)
  uint materialTextureSide;
  uint frame;        // frames since the last reset (Halton index, decay stamps)
  float historyCap;  // gi10-reproject-gi: at most this many frames averaged
};
BOUNCE_CHECK_SIZE(Gi10Constants, 144);

struct Gi10PassConstants {
  DeviceAddress frame;  // FrameConstants
  DeviceAddress gi10;   // Gi10Constants
  uint axis;            // gi10-filter-gi: 0 horizontal, 1 vertical
  uint pad0;
};
BOUNCE_CHECK_SIZE(Gi10PassConstants, 24);

// Set 1 bindings, per pass.
BOUNCE_CONST uint GI10_REPROJECT_BINDING_NORMALS = 0u;
BOUNCE_CONST uint GI10_REPROJECT_BINDING_DEPTH = 1u;
BOUNCE_CONST uint GI10_REPROJECT_BINDING_VELOCITY = 2u;
BOUNCE_CONST uint GI10_REPROJECT_BINDING_COUNT = 3u;

BOUNCE_CONST uint GI10_POPULATE_BINDING_NORMALS = 0u;
BOUNCE_CONST uint GI10_POPULATE_BINDING_DEPTH = 1u;
BOUNCE_CONST uint GI10_POPULATE_BINDING_VELOCITY = 2u;
BOUNCE_CONST uint GI10_POPULATE_BINDING_PREVIOUS_GI = 3u;
BOUNCE_CONST uint GI10_POPULATE_BINDING_COUNT = 4u;

BOUNCE_CONST uint GI10_SPAWN_BINDING_DEPTH = 0u;
BOUNCE_CONST uint GI10_SPAWN_BINDING_COUNT = 1u;

BOUNCE_CONST uint GI10_INTERPOLATE_BINDING_NORMALS = 0u;
BOUNCE_CONST uint GI10_INTERPOLATE_BINDING_DEPTH = 1u;
BOUNCE_CONST uint GI10_INTERPOLATE_BINDING_OUTPUT = 2u;
BOUNCE_CONST uint GI10_INTERPOLATE_BINDING_COUNT = 3u;

BOUNCE_CONST uint GI10_REPROJECT_GI_BINDING_IRRADIANCE = 0u;
BOUNCE_CONST uint GI10_REPROJECT_GI_BINDING_DEPTH = 1u;
BOUNCE_CONST uint GI10_REPROJECT_GI_BINDING_PREVIOUS_DEPTH = 2u;
BOUNCE_CONST uint GI10_REPROJECT_GI_BINDING_VELOCITY = 3u;
BOUNCE_CONST uint GI10_REPROJECT_GI_BINDING_PREVIOUS = 4u;
BOUNCE_CONST uint GI10_REPROJECT_GI_BINDING_OUTPUT = 5u;
BOUNCE_CONST uint GI10_REPROJECT_GI_BINDING_PREVIOUS_DELTA = 6u;
BOUNCE_CONST uint GI10_REPROJECT_GI_BINDING_DELTA = 7u;
BOUNCE_CONST uint GI10_REPROJECT_GI_BINDING_COUNT = 8u;

BOUNCE_CONST uint GI10_FILTER_BINDING_INPUT = 0u;
BOUNCE_CONST uint GI10_FILTER_BINDING_HISTORY = 1u;  // gi10.gi: the history length in a
BOUNCE_CONST uint GI10_FILTER_BINDING_NORMALS = 2u;
BOUNCE_CONST uint GI10_FILTER_BINDING_DEPTH = 3u;
BOUNCE_CONST uint GI10_FILTER_BINDING_OUTPUT = 4u;
BOUNCE_CONST uint GI10_FILTER_BINDING_COUNT = 5u;

BOUNCE_END_SHARED

#endif
