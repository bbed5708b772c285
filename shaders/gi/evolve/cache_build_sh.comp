// cache-build-sh (seed 000): each live cell's 16 entries, radiance x contribution weight (an
// estimate of the radiance integral over the entry's bin), projected onto L1 spherical
// harmonics of incoming radiance. The projection uses the bin's mean direction
// (CLIPMAP_ENTRY_MEAN_DIRECTION), not the kept sample's, so the L1 (directional) terms carry no
// sampling noise; with a noisy direction a cell's SH could point anywhere and its irradiance
// clamp to zero for some normals. Entries without a sample yet are left out and the rest
// scaled up to the whole sphere.
#version 460
#include "gi/evolve/cache_common.glsl"

layout(local_size_x = CLIPMAP_GROUP_SIZE) in;
layout(push_constant, scalar) uniform Push { ClipmapPassConstants pc; };

void main() {
  uint index = gl_GlobalInvocationID.x;
  if (index >= ClipmapFrameRef(pc.buffers.frame).v.liveCount) return;
  uint cell = ClipmapLiveListRef(pc.buffers.liveList).v[index];
  ClipmapEntriesRef entries = ClipmapEntriesRef(pc.buffers.entries);
  ClipmapCellsRef cells = ClipmapCellsRef(pc.buffers.cells);
  vec4 r = vec4(0.0), g = vec4(0.0), b = vec4(0.0);
  uint valid = 0u;
  for (uint e = 0u; e < CLIPMAP_ENTRIES; ++e) {
    ClipmapEntry entry = entries.v[cell * CLIPMAP_ENTRIES + e];
    if (!(entry.M > 0.0)) continue;
    vec3 integral = entry.radiance * entry.W;
    if (!clipmapFinite(integral)) continue;
    vec4 y = shBasisL1(CLIPMAP_ENTRY_MEAN_DIRECTION[e]);
    r += integral.r * y;
    g += integral.g * y;
    b += integral.b * y;
    ++valid;
  }
  uint flags = cells.v[cell].flags;
  if (valid > 0u) {
    float scale = float(CLIPMAP_ENTRIES) / float(valid);
    cells.v[cell].shR = r * scale;
    cells.v[cell].shG = g * scale;
    cells.v[cell].shB = b * scale;
    flags |= CLIPMAP_CELL_SH_VALID;
  } else {
    flags &= ~CLIPMAP_CELL_SH_VALID;
  }
  cells.v[cell].flags = flags;
  cells.v[cell].validEntries = valid;
}
