// cache-update-clipmap (seed 000): the cascades have scrolled with the camera (new window
// origins in the constants). Slots are toroidal, so a cell still inside its window keeps its
// slot and its metadata stays valid as it is; a cell now outside is freed. Survivors go to the
// live list that cache-trace-diffuse-rays and cache-build-sh walk (indirect dispatch), and are
// counted per cascade; cells never traced also go to the new-cell list (liveList from
// CLIPMAP_MAX_CELLS), whose every entry cache-trace-diffuse-rays traces at once. One thread
// per grid slot.
#version 460
#include "gi/evolve/cache/cache_free.glsl"

layout(local_size_x = CLIPMAP_GROUP_SIZE) in;
layout(push_constant, scalar) uniform Push { ClipmapPassConstants pc; };

void main() {
  uint slot = gl_GlobalInvocationID.x;
  if (slot >= CLIPMAP_CASCADES * CLIPMAP_SLOTS_PER_CASCADE) return;
  uint value = ClipmapGridRef(pc.buffers.grid).v[slot];
  if (value == 0u || value == CLIPMAP_SLOT_LOCKED) return;
  uint cell = value - 1u;
  uint cascade = slot / CLIPMAP_SLOTS_PER_CASCADE;
  ivec4 coord = ClipmapCellsRef(pc.buffers.cells).v[cell].coord;
  ivec3 origin = ClipmapConstantsRef(pc.cache).v.cascadeOrigin[cascade].xyz;
  if (uint(coord.w) != cascade || !clipmapInWindow(origin, coord.xyz)) {
    clipmapFreeCell(pc.buffers, cell, slot);
    atomicAdd(ClipmapFrameRef(pc.buffers.frame).v.scrollFrees, 1u);
    return;
  }
  ClipmapFrameRef frame = ClipmapFrameRef(pc.buffers.frame);
  ClipmapLiveListRef list = ClipmapLiveListRef(pc.buffers.liveList);
  uint index = atomicAdd(frame.v.liveCount, 1u);
  list.v[index] = cell;
  if (index % CLIPMAP_GROUP_SIZE == 0u) atomicAdd(frame.v.traceDispatch.x, 1u);
  uint lanes = clipmapTraceLanes(ClipmapConstantsRef(pc.cache).v);
  if (index % (CLIPMAP_GROUP_SIZE / lanes) == 0u) atomicAdd(frame.v.rayDispatch.x, 1u);
  // A full refresh (ClipmapCacheConstants.fullRefresh) traces every cell as a new one.
  if (ClipmapCellsRef(pc.buffers.cells).v[cell].validEntries == 0u ||
      ClipmapConstantsRef(pc.cache).v.fullRefresh != 0u) {
    uint fresh = atomicAdd(frame.v.newCount, 1u);
    list.v[CLIPMAP_MAX_CELLS + fresh] = cell;
    if (fresh % (CLIPMAP_GROUP_SIZE / CLIPMAP_ENTRIES) == 0u) atomicAdd(frame.v.rayDispatch.x, 1u);
  }
  atomicAdd(frame.v.liveCells[cascade], 1u);
}
