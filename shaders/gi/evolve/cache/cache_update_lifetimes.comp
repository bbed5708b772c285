// cache-update-lifetimes (seed 000): a cell that no lookup touched last frame ages by one; at
// maxStaleFrames (4) it goes back to the pool. A touched cell records its touch level (the
// lowest level that touched it, CLIPMAP_TOUCH_LEVELS in shared/clipmap_cache_io.h), which
// decides whether its cache rays may keep other cells alive this frame. The touches are the
// grid slot's (ClipmapSlotVote; cache-update-clipmap clears them next). One thread per pool
// cell.
#version 460
#include "gi/evolve/cache/cache_free.glsl"

layout(local_size_x = CLIPMAP_GROUP_SIZE) in;
layout(push_constant, scalar) uniform Push { ClipmapPassConstants pc; };

// Level of the lowest touch bit (1 = a consumer), 0 when untouched.
uint touchLevel(uint touched) { return touched == 0u ? 0u : uint(findLSB(touched)) + 1u; }

void main() {
  uint cell = gl_GlobalInvocationID.x;
  if (cell >= CLIPMAP_MAX_CELLS) return;
  ClipmapCellsRef cells = ClipmapCellsRef(pc.buffers.cells);
  ClipmapCell c = cells.v[cell];
  if ((c.flags & CLIPMAP_CELL_ALIVE) == 0u) return;
  uint slot = clipmapSlot(uint(c.coord.w), c.coord.xyz);
  uint level = touchLevel(ClipmapVotesRef(pc.buffers.votes).v[slot].touched);
  uint age = level > 0u ? 0u : c.age + 1u;
  if (age >= pc.maxStaleFrames) {
    clipmapFreeCell(pc.buffers, cell, slot);
    return;
  }
  uint flags = c.flags & ~(CLIPMAP_CELL_DIRECT | CLIPMAP_CELL_LEVEL_MASK);
  flags |= level << CLIPMAP_CELL_LEVEL_SHIFT;
  if (level == 1u) flags |= CLIPMAP_CELL_DIRECT;
  cells.v[cell].age = age;
  cells.v[cell].flags = flags;
}
