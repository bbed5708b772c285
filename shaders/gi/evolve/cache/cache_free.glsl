// Returning a cell to the pool (cache-update-lifetimes, cache-update-clipmap; never in a pass
// that allocates, see clipmapAllocate).
#ifndef BOUNCE_GI_EVOLVE_CACHE_FREE_GLSL
#define BOUNCE_GI_EVOLVE_CACHE_FREE_GLSL
#include "gi/evolve/cache/cache_common.glsl"

void clipmapFreeCell(ClipmapCacheAddresses b, uint cell, uint slot) {
  ClipmapGridRef(b.grid).v[slot] = 0u;
  ClipmapCellsRef(b.cells).v[cell].flags = 0u;
  // A lookup that finds the cell reallocated in a later pass reads 0 here whatever the order
  // of the writes (clipmapVote).
  ClipmapCellsRef(b.cells).v[cell].originCloseness = 0u;
  ClipmapCountersRef counters = ClipmapCountersRef(b.counters);
  uint top = atomicAdd(counters.v.allocated, 0xFFFFFFFFu) - 1u;
  ClipmapPoolRef(b.pool).v[top] = cell + 1u;
  atomicAdd(counters.v.freesTotal, 1u);
}

#endif
