// Evolve's world-space clipmap irradiance cache (seed 000, "Clipmap irradiance cache"; after
// kajiya's ircache): structs shared by C++ (src/gi/evolve/cache/clipmap_cache.h) and the shaders
// (shaders/gi/evolve/). Everything lives in buffers reached by device address.
//
// Geometry: CLIPMAP_CASCADES nested cascades of CLIPMAP_GRID^3 cells around the camera; the
// cell side of cascade c is finestCellSize * 2^c. A cascade's window is the cube of cells
// [origin, origin + CLIPMAP_GRID) in integer cell coordinates of that cascade; it scrolls with
// the camera. Grid slots are addressed toroidally (cell coordinate mod CLIPMAP_GRID), so a
// cell that stays inside its window keeps its slot when the window scrolls.
//
// Buffers:
//   grid       uint[CLIPMAP_CASCADES * CLIPMAP_GRID^3]: 0 = no cell, CLIPMAP_SLOT_LOCKED =
//              being allocated, else cell index + 1
//   cells      ClipmapCell[CLIPMAP_MAX_CELLS]: metadata and the cell's L1 SH
//   entries    ClipmapEntry[CLIPMAP_MAX_CELLS * CLIPMAP_ENTRIES]: one ReSTIR reservoir per
//              octahedral direction bin (equal-area octahedral map, 4x4 bins of pi/4 sr)
//   pool       uint[CLIPMAP_MAX_CELLS]: the free list; pool[k] = 0 means "cell k", else
//              cell index + 1 (so a zeroed pool is the identity list)
//   counters   ClipmapCounters (cumulative)
//   frame      ClipmapFrameCounters (reset by cache-update-lifetimes every frame)
//   liveList   uint[2 * CLIPMAP_MAX_CELLS]: this frame's live cells (cache-update-clipmap),
//              then from index CLIPMAP_MAX_CELLS those of them never traced (new cells)
//   votes      ClipmapSlotVote[CLIPMAP_CASCADES * CLIPMAP_GRID^3]: per grid slot, what this
//              frame's lookups left for cache-update-lifetimes and cache-update-clipmap (the
//              touches; the election of the cell's origin), whether or not the slot had a cell
//              when they came, so that nothing depends on the order of the lookups
#ifndef BOUNCE_SHARED_CLIPMAP_CACHE_IO_H
#define BOUNCE_SHARED_CLIPMAP_CACHE_IO_H
#include "shared/compat.h"

BOUNCE_BEGIN_SHARED

BOUNCE_CONST uint CLIPMAP_CASCADES = 12u;
BOUNCE_CONST uint CLIPMAP_GRID = 32u;
BOUNCE_CONST uint CLIPMAP_SLOTS_PER_CASCADE = CLIPMAP_GRID * CLIPMAP_GRID * CLIPMAP_GRID;
BOUNCE_CONST uint CLIPMAP_ENTRIES = 16u;       // 4x4 octahedral bins per cell
BOUNCE_CONST uint CLIPMAP_MAX_CELLS = 65535u;  // seed 000: hard cap of live cells
BOUNCE_CONST uint CLIPMAP_SLOT_LOCKED = 0xFFFFFFFFu;

// ClipmapCell.flags
BOUNCE_CONST uint CLIPMAP_CELL_ALIVE = 1u;
BOUNCE_CONST uint CLIPMAP_CELL_SH_VALID = 2u;  // cache-build-sh has written its SH
BOUNCE_CONST uint CLIPMAP_CELL_DIRECT = 4u;    // a consumer (not a cache ray) used it last frame
// Bits 8..11: the cell's touch level last frame (1 = a consumer looked it up, k = a cache ray of
// a level k-1 cell did; 0 = nobody). Set by cache-update-lifetimes from its slot's `touched`.
BOUNCE_CONST uint CLIPMAP_CELL_LEVEL_SHIFT = 8u;
BOUNCE_CONST uint CLIPMAP_CELL_LEVEL_MASK = 0xF00u;

// ClipmapSlotVote.touched: who looked the slot up this frame, one bit per level (bit k-1 =
// level k).
BOUNCE_CONST uint CLIPMAP_TOUCH_DIRECT = 1u;    // level 1: a consumer (gi, ReSTIR GI, ...)
BOUNCE_CONST uint CLIPMAP_TOUCH_INDIRECT = 2u;  // level 2: a cache ray from a level-1 cell
// Cells of a level below this touch and allocate the cells their rays look up (with level + 1);
// cells of this level (or untouched ones) only read. Bounded levels let the cache reach the
// surfaces that light the view three bounces deep (out of view, behind the camera) without
// letting cells keep each other alive for ever: a chain dies CLIPMAP_TOUCH_LEVELS - 1 frames
// after its consumer stops looking. Fewer than 4 levels lose light in the furnace test (a ray
// hitting where no cell may be allocated reads zero); more gain nothing (docs/decisions.md).
BOUNCE_CONST uint CLIPMAP_TOUCH_LEVELS = 4u;

// ClipmapCacheConstants.flags
BOUNCE_CONST uint CLIPMAP_FLAG_ALPHA_TEST = 1u;

struct ClipmapCell {
  ivec4 coord;  // xyz: integer cell coordinate in its cascade; w: cascade
  vec3 origin;  // where its rays start: the elected lookup's surface point, offset
  uint age;     // frames since a lookup last touched it
  vec3 normal;  // the elected lookup's surface normal
  // Closeness of the elected lookup (ClipmapSlotVote.key >> 16); 0: none yet, and the cell is
  // neither traced nor listed live until one is (cache-update-clipmap).
  uint originCloseness;
  vec4 shR;  // L1 SH of incoming radiance, coefficients (Y00, Y1-1 ~ y, Y10 ~ z, Y11 ~ x)
  vec4 shG;
  vec4 shB;
  uint flags;  // CLIPMAP_CELL_*
  uint validEntries;
  // Exact / SH irradiance at `normal` (cache-build-sh): what lookups with that normal scale the
  // SH's irradiance by (less for other normals; cache_lookup.glsl).
  float irradianceScale;
  uint pad1;
};
BOUNCE_CHECK_SIZE(ClipmapCell, 112);

// A grid slot's votes this frame (cache_lookup.glsl, clipmapVote; cache-update-clipmap counts
// them and clears them). The election of the cell's origin: each lookup that may allocate the
// slot's cell is a candidate with a 16-bit closeness (cache_lookup.glsl, clipmapVote); the
// highest wins, whatever the order. Its origin is 4 16-bit numbers, each stored as closeness << 16
// | number and raised by atomicMax, so every word ends with the winner's number: no word mixes in
// another candidate's, except between candidates of equal closeness, which `key`'s hash catches.
struct ClipmapSlotVote {
  uint touched;  // CLIPMAP_TOUCH_* bits of this frame's lookups (the cell's, if any)
  uint key;      // closeness << 16 | hash of the winner's 4 numbers; 0: no candidate
  // closeness << 16 | x, y, z of the origin (cell units from the centre in 16-bit fixed point,
  // cache_lookup.glsl) and the normal (octahedral, 8 + 8 bits)
  uint data[4];
};
BOUNCE_CHECK_SIZE(ClipmapSlotVote, 24);

// One direction bin's reservoir (ReSTIR GI, Ouyang et al. 2021): the chosen sample (direction,
// the radiance it brought, where it was traced from and how far it went), the number of
// candidates it stands for (M), the sum of their resampling weights and the contribution weight
// W = weightSum / (M * target(sample)), target = luminance of the radiance.
struct ClipmapEntry {
  vec3 radiance;
  float M;
  vec3 direction;
  float W;
  vec3 origin;
  float weightSum;
  float hitDistance;
  uint pad0;
  uint pad1;
  uint pad2;
};
BOUNCE_CHECK_SIZE(ClipmapEntry, 64);

struct ClipmapCounters {
  uint allocated;         // live cells = top of the pool
  uint allocationsTotal;  // since the last reset
  uint freesTotal;
  uint allocationFailures;  // lookups that found the pool exhausted
};
BOUNCE_CHECK_SIZE(ClipmapCounters, 16);

struct ClipmapFrameCounters {
  uvec3 traceDispatch;  // indirect dispatch over the live list, a thread per cell (cache-build-sh)
  uint liveCount;       // cells in liveList
  uint liveCells[CLIPMAP_CASCADES];
  uint scrollFrees;  // cells freed by cache-update-clipmap (left their window)
  // Indirect dispatch of cache-trace-diffuse-rays: first clipmapTraceLanes() threads per live
  // cell (its candidate and validation rays; a warp's lanes all busy), then a thread per
  // entry of every new cell (all 16 entries traced at once), so that a cell's rays run in
  // parallel rather than one after another in one thread.
  uvec3 rayDispatch;
  uint newCount;  // new cells, at liveList[CLIPMAP_MAX_CELLS ...]
};
BOUNCE_CHECK_SIZE(ClipmapFrameCounters, 84);

struct ClipmapCacheAddresses {
  DeviceAddress grid;
  DeviceAddress cells;
  DeviceAddress entries;
  DeviceAddress pool;
  DeviceAddress counters;
  DeviceAddress frame;
  DeviceAddress liveList;
  DeviceAddress votes;
};
BOUNCE_CHECK_SIZE(ClipmapCacheAddresses, 64);

// Written each frame by cache-update-lifetimes; every consumer reads the cache through it
// (shaders/gi/evolve/cache/cache_lookup.glsl, clipmapCacheView()).
struct ClipmapCacheConstants {
  ClipmapCacheAddresses buffers;
  DeviceAddress lights;                   // LightTables (src/lighting/gpu_light_tables.h)
  ivec4 cascadeOrigin[CLIPMAP_CASCADES];  // xyz: first cell of the window; w unused
  vec3 cameraPosition;
  float finestCellSize;  // metres
  uint frameIndex;
  uint raysPerCell;
  uint validationRaysPerCell;
  uint flags;        // CLIPMAP_FLAG_*
  float historyCap;  // largest M a reservoir keeps
  uint maxStaleFrames;
  uint poolCapacity;         // live cells at most: CLIPMAP_MAX_CELLS, or fewer for tests
  uint materialTextureSide;  // the cells' rays read textures at mips at most this wide (0 = full)
  // Non-zero in the frames after a reset or a lighting cut (ClipmapCache::beginFullRefresh):
  // every live cell traces all its entries, its history capped at fullRefreshHistoryCap.
  uint fullRefresh;
  float fullRefreshHistoryCap;
  uint pad0, pad1;
};
BOUNCE_CHECK_SIZE(ClipmapCacheConstants, 64 + 8 + 192 + 48 + 16);

// Push constants of the cache passes.
struct ClipmapPassConstants {
  DeviceAddress cache;  // ClipmapCacheConstants (unused by cache-update-lifetimes)
  DeviceAddress frame;  // FrameConstants (shared/hybrid_frame_io.h)
  ClipmapCacheAddresses buffers;
  uint maxStaleFrames;
  // cache-trace-diffuse-rays: 0 for the frame's trace; k >= 1 for the k-th extra bounce of a
  // full refresh (ClipmapCacheSettings::fullRefreshBounces), whose lookups neither allocate nor
  // touch cells (the frame's trace did) and whose candidates draw other directions.
  uint bounce;
};
BOUNCE_CHECK_SIZE(ClipmapPassConstants, 88);

BOUNCE_CONST uint CLIPMAP_GROUP_SIZE = 64u;

// Storage images (set 1) of the passes that read the GBuffer.
BOUNCE_CONST uint CACHE_LOOKUP_BINDING_NORMALS = 0u;
BOUNCE_CONST uint CACHE_LOOKUP_BINDING_DEPTH = 1u;
BOUNCE_CONST uint CACHE_LOOKUP_BINDING_FLAGS = 2u;
BOUNCE_CONST uint CACHE_LOOKUP_BINDING_OUTPUT = 3u;
BOUNCE_CONST uint CACHE_LOOKUP_IMAGES = 4u;

// The live-cell bar chart (view `cache.live-cells`): one bar per cascade.
BOUNCE_CONST uint CLIPMAP_LIVE_VIEW_WIDTH = 256u;
BOUNCE_CONST uint CLIPMAP_LIVE_VIEW_BAR = 8u;
BOUNCE_CONST uint CACHE_LIVE_VIEW_BINDING_OUTPUT = 0u;  // rgba16f
BOUNCE_CONST uint CACHE_LIVE_VIEW_BINDING_COUNT = 1u;

// Test support (shaders/gi/evolve/reference_irradiance.comp): irradiance / pi at points by
// path tracing with the same tracer, Lambert materials.
struct IrradianceProbe {
  vec3 position;
  float pad0;
  vec3 normal;
  float pad1;
};
BOUNCE_CHECK_SIZE(IrradianceProbe, 32);

struct ReferenceIrradianceConstants {
  DeviceAddress frame;   // FrameConstants
  DeviceAddress probes;  // IrradianceProbe[probeCount]
  DeviceAddress sums;    // vec4[probeCount * CLIPMAP_GROUP_SIZE]: per thread (sum rgb, samples)
  DeviceAddress lights;  // LightTables (src/lighting/gpu_light_tables.h)
  uint probeCount;
  uint samplesPerThread;
  uint maxBounces;  // scattering events after the probe: 1 = light from directly lit surfaces
  uint seed;
};
BOUNCE_CHECK_SIZE(ReferenceIrradianceConstants, 48);

BOUNCE_END_SHARED
#endif
