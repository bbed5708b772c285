// cache-update-clipmap (seed 000): the cascades have scrolled with the camera (new window
// origins in the constants). Slots are toroidal, so a cell still inside its window keeps its
// slot and its metadata stays valid as it is; a cell now outside is freed. Survivors go to the
// live list that cache-trace-diffuse-rays and cache-build-sh walk (indirect dispatch), and are
// counted per cascade; cells never traced also go to the new-cell list (liveList from
// CLIPMAP_MAX_CELLS), whose every entry cache-trace-diffuse-rays traces at once. Before that,
// the cell takes the origin its slot's lookups elected last frame when it is closer to the
// cell's centre than the one it has (cache_lookup.glsl, clipmapVote); a cell without one yet
// is not listed. The slot's votes are cleared for this frame's lookups. One thread per grid
// slot.
#version 460
#include "gi/evolve/cache/cache_free.glsl"

layout(local_size_x = CLIPMAP_GROUP_SIZE) in;
layout(push_constant, scalar) uniform Push { ClipmapPassConstants pc; };

// The origin elected in `slot` last frame, for a cell without one (with CLIPMAP_ELECT_CENTRE:
// when it is closer to the cell's centre than the cell's, so the origin only moves closer and
// settles). Equal-closeness candidates may
// have mixed their numbers; the key's hash of the winner's refuses such a mix (the cell keeps
// its origin, or waits a frame for its first). The entries stay: their samples keep their own
// origins, which validation re-traces from, and new candidates replace them (clearing them when
// the normal turned by more than 60 degrees made sunroom 3 % darker, docs/gi/clipmap-cache.md).
void adoptElectedOrigin(uint cell, uint cascade, uint key, uvec4 words) {
  ClipmapCellsRef cells = ClipmapCellsRef(pc.buffers.cells);
  uint closeness = key >> 16u;
  uint current = cells.v[cell].originCloseness;
  if (CLIPMAP_ELECT_CENTRE ? closeness <= current : current != 0u) return;
  uvec4 numbers = words & 0xFFFFu;
  if (clipmapVoteHash(numbers) != (key & 0xFFFFu)) return;
  float cellSize =
      ClipmapConstantsRef(pc.cache).v.finestCellSize * float(1u << cascade);
  vec3 offset = vec3(clipmapVoteDequantize(numbers.x), clipmapVoteDequantize(numbers.y),
                     clipmapVoteDequantize(numbers.z));
  vec3 normal = clipmapVoteUnpackNormal(numbers.w);
  cells.v[cell].origin = (vec3(cells.v[cell].coord.xyz) + 0.5 + offset) * cellSize;
  cells.v[cell].normal = normal;
  cells.v[cell].originCloseness = closeness;
}

void main() {
  uint slot = gl_GlobalInvocationID.x;
  if (slot >= CLIPMAP_CASCADES * CLIPMAP_SLOTS_PER_CASCADE) return;
  ClipmapVotesRef votes = ClipmapVotesRef(pc.buffers.votes);
  uint touched = votes.v[slot].touched;
  uint key = votes.v[slot].key;
  uvec4 words = uvec4(0u);
  if (key != 0u) {
    for (uint k = 0u; k < 4u; ++k) {
      words[k] = votes.v[slot].data[k];
      votes.v[slot].data[k] = 0u;
    }
  }
  if (touched != 0u || key != 0u) votes.v[slot].touched = votes.v[slot].key = 0u;
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
  if (key != 0u) adoptElectedOrigin(cell, cascade, key, words);
  if (ClipmapCellsRef(pc.buffers.cells).v[cell].originCloseness == 0u) return;
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
