// gi.ray-lists (shared/restir_gi_io.h, "Ray lists"): the pixels of a sparse ray pass, appended
// by the pass before it and walked by the tracing pass, one thread per entry.
#ifndef BOUNCE_GI_RAY_LIST_GLSL
#define BOUNCE_GI_RAY_LIST_GLSL
#include "shared/restir_gi_io.h"

layout(buffer_reference, scalar) buffer GiRayListsRef {
  GiRayListHeader header[2];
  uint entries[];
};

// Where `list`'s entries start: GI_RAY_LIST_RESOLVE's follow GI_RAY_LIST_NEE's, one per GI pixel.
uint rayListBase(uint list, uvec2 giResolution) {
  return list == GI_RAY_LIST_NEE ? 0u : giResolution.x * giResolution.y;
}

// Appends `pixel` with one atomic per subgroup (the lanes that call it together), and adds a
// group to the tracing pass's dispatch for every GI_RAY_LIST_GROUP_SIZE / threadsPerEntry-th
// entry (the tracing pass runs threadsPerEntry threads per entry; a power of two).
void rayListAppend(DeviceAddress lists, uint list, uvec2 giResolution, ivec2 pixel,
                   uint threadsPerEntry) {
  GiRayListsRef r = GiRayListsRef(lists);
  uvec4 lanes = subgroupBallot(true);
  uint first = 0u;
  if (subgroupElect()) first = atomicAdd(r.header[list].count, subgroupBallotBitCount(lanes));
  uint index = subgroupBroadcastFirst(first) + subgroupBallotExclusiveBitCount(lanes);
  r.entries[rayListBase(list, giResolution) + index] = uint(pixel.x) | uint(pixel.y) << 16;
  uint entriesPerGroup = GI_RAY_LIST_GROUP_SIZE / threadsPerEntry;
  if (index % entriesPerGroup == 0u && index / entriesPerGroup < GI_RAY_LIST_MAX_GROUPS)
    atomicAdd(r.header[list].groupsX, 1u);
}

uint rayListCount(DeviceAddress lists, uint list) { return GiRayListsRef(lists).header[list].count; }

ivec2 rayListPixel(DeviceAddress lists, uint list, uvec2 giResolution, uint index) {
  uint packed = GiRayListsRef(lists).entries[rayListBase(list, giResolution) + index];
  return ivec2(packed & 0xFFFFu, packed >> 16);
}

// The work items (entries x threads per entry) a thread takes: its own, and every
// GI_RAY_LIST_GROUP_SIZE x GI_RAY_LIST_MAX_GROUPS-th after it (lists longer than one dispatch
// can cover).
const uint RAY_LIST_STRIDE = GI_RAY_LIST_GROUP_SIZE * GI_RAY_LIST_MAX_GROUPS;

#endif
