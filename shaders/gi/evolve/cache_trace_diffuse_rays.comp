// cache-trace-diffuse-rays (seed 000): per live cell, raysPerCell new candidates for as many
// of its 16 entries (so every entry is refreshed each 16 / raysPerCell frames), each a uniform
// direction in the entry's bin, merged into the entry's reservoir; then validationRaysPerCell
// rays re-trace the kept samples of other entries. A cell that has never been traced (new this
// frame) traces one candidate for every entry at once, so that it has a complete SH the frame
// after it was allocated instead of filling in over 16 frames (the talk leaves this open; the
// cost is bounded by the allocations per frame).
// Cells touched last frame at a level below CLIPMAP_TOUCH_LEVELS allocate and keep alive the
// cells their rays look up (shared/clipmap_cache_io.h); the others only read, so that cells
// cannot keep each other alive for ever.
#version 460
#include "gi/evolve/cache_radiance.glsl"
#include "gi/evolve/cache_reservoir.glsl"

layout(local_size_x = CLIPMAP_GROUP_SIZE) in;
layout(push_constant, scalar) uniform Push { ClipmapPassConstants pc; };

// The touch bit this cell's rays set on the cells they look up (0: read only).
uint rayTouch(uint cellFlags) {
  uint level = (cellFlags & CLIPMAP_CELL_LEVEL_MASK) >> CLIPMAP_CELL_LEVEL_SHIFT;
  return level >= 1u && level < CLIPMAP_TOUCH_LEVELS ? (1u << level) : 0u;
}

void traceCandidate(FrameConstants f, ClipmapCacheView cache, uint cell, ClipmapCell c, uint e,
                    bool alphaTest, uint touch) {
  uvec4 seed = uvec4(cell, f.frameIndex, e, 0x0CAC4E01u);
  vec4 u = uniformFromHash(pcg4d(seed));
  vec3 dir = clipmapEntryDirection(e, u.xy);
  float hitDistance;
  vec3 radiance = cacheRayRadiance(f, cache, c.origin, dir, alphaTest, touch, touch != 0u,
                                   seed ^ uvec4(0u, 0u, 0u, 0x5BD1E995u), hitDistance);
  ClipmapEntry entry = cache.entries.v[cell * CLIPMAP_ENTRIES + e];
  reservoirMerge(entry, radiance, dir, c.origin, hitDistance, CLIPMAP_ENTRY_PDF,
                 cache.constants.v.historyCap, u.z);
  cache.entries.v[cell * CLIPMAP_ENTRIES + e] = entry;
}

void traceValidation(FrameConstants f, ClipmapCacheView cache, uint cell, uint e,
                     bool alphaTest, uint touch) {
  ClipmapEntry entry = cache.entries.v[cell * CLIPMAP_ENTRIES + e];
  if (!(entry.M > 0.0)) return;
  float hitDistance;
  vec3 radiance = cacheRayRadiance(f, cache, entry.origin, entry.direction, alphaTest, touch,
                                   touch != 0u, uvec4(cell, f.frameIndex, e, 0x7A11DA7Eu),
                                   hitDistance);
  reservoirValidate(entry, radiance, 2.0);
  cache.entries.v[cell * CLIPMAP_ENTRIES + e] = entry;
}

// A thread per (live cell, entry): lane e of a cell traces entry e's candidate when the cell is
// new, else lanes [0, rays) trace this round's candidates and the next `validations` lanes
// re-trace the entries of the round half a cycle ago; the other lanes idle. Lanes of one cell
// touch different entries, so they need no synchronisation.
void main() {
  ClipmapFrameRef frameCounters = ClipmapFrameRef(pc.buffers.frame);
  uint index = gl_GlobalInvocationID.x / CLIPMAP_ENTRIES;
  uint lane = gl_GlobalInvocationID.x % CLIPMAP_ENTRIES;
  if (index >= frameCounters.v.liveCount) return;
  uint cell = ClipmapLiveListRef(pc.buffers.liveList).v[index];
  ClipmapCacheView cache = clipmapCacheView(pc.cache);
  ClipmapCacheConstants k = cache.constants.v;
  settings = ReferenceSettingsBlock(k.lights).v;
  FrameConstants f = FrameBlock(pc.frame).v;
  ClipmapCell c = cache.cells.v[cell];
  uint touch = rayTouch(c.flags);
  bool alphaTest = (k.flags & CLIPMAP_FLAG_ALPHA_TEST) != 0u;

  if (c.validEntries == 0u) {  // never traced: fill every entry now
    traceCandidate(f, cache, cell, c, lane, alphaTest, touch);
    return;
  }
  uint rays = k.raysPerCell;
  uint rounds = CLIPMAP_ENTRIES / rays;  // raysPerCell divides 16 (checked on the CPU)
  uint round = (f.frameIndex + cell) % rounds;
  uint validations = rounds >= 2u ? min(k.validationRaysPerCell, rays) : 0u;
  if (lane < rays) {
    traceCandidate(f, cache, cell, c, round * rays + lane, alphaTest, touch);
  } else if (lane < rays + validations) {
    uint validationRound = (round + rounds / 2u) % rounds;
    traceValidation(f, cache, cell, validationRound * rays + (lane - rays), alphaTest, touch);
  }
}
