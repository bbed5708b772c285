// cache-trace-diffuse-rays (seed 000): per live cell, raysPerCell new candidates for as many
// of its 16 entries (so every entry is refreshed each 16 / raysPerCell frames), each a uniform
// direction in the entry's bin, merged into the entry's reservoir; then validationRaysPerCell
// rays re-trace the kept samples of other entries. A cell that has never been traced (new this
// frame) traces one candidate for every entry at once, so that it has a complete SH the frame
// after it was allocated instead of filling in over 16 frames (the talk leaves this open; the
// cost is bounded by the allocations per frame). During a full refresh (the frames after a reset
// or a lighting cut, ClipmapCacheSettings::fullRefreshFrames) every live cell is traced that way,
// its entries' history capped at fullRefreshHistoryCap, and the pass runs fullRefreshBounces
// times (each followed by cache-build-sh): light then crosses that many bounces per frame
// instead of one per refresh round.
// A cell's random numbers and its refresh round follow clipmapCellKey (its coordinates), not
// its pool index, which depends on the order of the allocating lookups.
// Cells touched last frame at a level below CLIPMAP_TOUCH_LEVELS allocate and keep alive the
// cells their rays look up (shared/clipmap_cache_io.h); the others only read, so that cells
// cannot keep each other alive for ever.
#version 460
#include "gi/evolve/cache/cache_radiance.glsl"
#include "gi/evolve/cache/cache_reservoir.glsl"

layout(local_size_x = CLIPMAP_GROUP_SIZE) in;
layout(push_constant, scalar) uniform Push { ClipmapPassConstants pc; };

// The touch bit this cell's rays set on the cells they look up (0: read only).
uint rayTouch(uint cellFlags) {
  uint level = (cellFlags & CLIPMAP_CELL_LEVEL_MASK) >> CLIPMAP_CELL_LEVEL_SHIFT;
  return level >= 1u && level < CLIPMAP_TOUCH_LEVELS ? (1u << level) : 0u;
}

// One ray of entry e: a new candidate in the entry's bin, merged into its reservoir, or
// (validation) the entry's kept sample traced again. Both through one cacheRayRadiance call:
// every call is inlined whole (a closest-hit trace, the surface, shadow rays, a cache lookup),
// and a CPU driver compiles each copy (docs/startup.md).
void traceEntry(FrameConstants f, ClipmapCacheView cache, uint cell, ClipmapCell c, uint e,
                bool validation, bool alphaTest, uint touch, float historyCap) {
  ClipmapEntry entry;
  uint key = clipmapCellKey(c.coord);
  vec3 origin = c.origin;
  vec3 dir;
  vec4 u;
  uvec4 seed;
  if (validation) {
    entry = cache.entries.v[cell * CLIPMAP_ENTRIES + e];
    if (!(entry.M > 0.0)) return;
    origin = entry.origin;
    dir = entry.direction;
    seed = uvec4(key, f.frameIndex, e, 0x7A11DA7Eu);
  } else {
    uvec4 candidateSeed = uvec4(key, f.frameIndex, e, 0x0CAC4E01u + pc.bounce);
    u = uniformFromHash(pcg4d(candidateSeed));
    dir = clipmapEntryDirection(e, u.xy);
    seed = candidateSeed ^ uvec4(0u, 0u, 0u, 0x5BD1E995u);
  }
  float hitDistance;
  vec3 radiance = cacheRayRadiance(f, cache, origin, dir, alphaTest, touch, touch != 0u, seed,
                                   hitDistance);
  if (validation) {
    reservoirValidate(entry, radiance, 2.0);
  } else {
    entry = cache.entries.v[cell * CLIPMAP_ENTRIES + e];
    reservoirMerge(entry, radiance, dir, origin, hitDistance, CLIPMAP_ENTRY_PDF, historyCap, u.z);
  }
  cache.entries.v[cell * CLIPMAP_ENTRIES + e] = entry;
}

// Two ranges of threads (cache-update-clipmap sized the dispatch): clipmapTraceLanes() threads
// per live cell, lanes [0, rays) tracing this round's candidates and the next `validations`
// lanes re-tracing the entries of the round half a cycle ago; then CLIPMAP_ENTRIES threads per
// new cell, lane e tracing entry e. A new cell's lanes in the first range idle (few: cells are
// new for one frame). Lanes of one cell touch different entries: no synchronisation needed.
// (A thread per entry of every live cell left 3/4 of the lanes idle on desktop, 15/16 on
// mobile.)
void main() {
  ClipmapFrameRef frameCounters = ClipmapFrameRef(pc.buffers.frame);
  ClipmapCacheView cache = clipmapCacheView(pc.cache);
  ClipmapCacheConstants k = cache.constants.v;
  uint lanes = clipmapTraceLanes(k);
  uint liveCount = frameCounters.v.liveCount;
  uint liveThreads = ((liveCount * lanes + CLIPMAP_GROUP_SIZE - 1u) / CLIPMAP_GROUP_SIZE) *
                     CLIPMAP_GROUP_SIZE;
  uint thread = gl_GlobalInvocationID.x;
  bool newCell = thread >= liveThreads;
  uint index, lane, cell;
  ClipmapLiveListRef list = ClipmapLiveListRef(pc.buffers.liveList);
  if (newCell) {
    index = (thread - liveThreads) / CLIPMAP_ENTRIES;
    lane = (thread - liveThreads) % CLIPMAP_ENTRIES;
    if (index >= frameCounters.v.newCount) return;
    cell = list.v[CLIPMAP_MAX_CELLS + index];
  } else {
    index = thread / lanes;
    lane = thread % lanes;
    if (index >= liveCount) return;
    cell = list.v[index];
  }
  lightTables = LightTablesBlock(k.lights).v;
  FrameConstants f = FrameBlock(pc.frame).v;
  ClipmapCell c = cache.cells.v[cell];
  uint touch = pc.bounce == 0u ? rayTouch(c.flags) : 0u;
  bool alphaTest = (k.flags & CLIPMAP_FLAG_ALPHA_TEST) != 0u;

  bool fullRefresh = k.fullRefresh != 0u;
  uint entry;
  bool validation = false;
  float historyCap = k.historyCap;
  if (newCell) {  // never traced, or a full refresh: every entry now
    entry = lane;
    if (fullRefresh) historyCap = k.fullRefreshHistoryCap;
  } else {
    if (c.validEntries == 0u || fullRefresh) return;  // traced in the second range
    uint rays = k.raysPerCell;
    uint rounds = clipmapTraceRounds(k);  // raysPerCell divides 16 (checked on the CPU)
    uint round = (f.frameIndex + clipmapCellKey(c.coord)) % rounds;
    if (lane < rays) {
      entry = round * rays + lane;
    } else if (lane < rays + clipmapValidationRays(k)) {
      uint validationRound = (round + rounds / 2u) % rounds;
      entry = validationRound * rays + (lane - rays);
      validation = true;
    } else {
      return;
    }
  }
  traceEntry(f, cache, cell, c, entry, validation, alphaTest, touch, historyCap);
}
