// cache-build-sh (seed 000): each live cell's 16 entries, radiance x contribution weight (an
// estimate of the radiance integral over the entry's bin), projected onto L1 spherical
// harmonics of incoming radiance. The projection uses the bin's mean direction
// (CLIPMAP_ENTRY_MEAN_DIRECTION), not the kept sample's, so the L1 (directional) terms carry no
// sampling noise; with a noisy direction a cell's SH could point anywhere and its irradiance
// clamp to zero for some normals. Entries without a sample yet are left out and the rest
// scaled up to the whole sphere.
// L1 SH loses the higher-order part of the clamped-cosine kernel (A2 = pi / 4, Ramamoorthi &
// Hanrahan 2001): for light arriving from a small solid angle its irradiance is 1/4 + cos / 2
// of the exact cos, 25 % dark where the light faces the surface (a small lamp seen from the
// floor). So each cell also stores the factor that
// makes its SH irradiance at the normal of the surface that allocated it (the normal its
// lookups mostly use) equal the irradiance of the same 16 bin integrals, each spread evenly
// over its bin, with the exact clamped cosine (a quadrature of BIN_QUADRATURE^2 directions per
// bin, fixed, so it adds no noise). Lookups apply it in full for that normal and less for
// others (cache_lookup.glsl). For radiance even over the sphere both agree (factor 1); the
// factor is bounded by NORMALISATION_LIMIT.
#version 460
#include "gi/evolve/cache/cache_common.glsl"

layout(local_size_x = CLIPMAP_GROUP_SIZE) in;
layout(push_constant, scalar) uniform Push { ClipmapPassConstants pc; };

const uint BIN_QUADRATURE = 4u;
const uint QUADRATURE_POINTS = BIN_QUADRATURE * BIN_QUADRATURE;
const float NORMALISATION_LIMIT = 4.0;

// The quadrature's directions, bin after bin, computed once per workgroup (each costs a few
// transcendental functions; every cell of the group needs all of them).
shared vec3 quadratureDirections[CLIPMAP_ENTRIES * QUADRATURE_POINTS];

void computeQuadratureDirections() {
  for (uint k = gl_LocalInvocationIndex; k < CLIPMAP_ENTRIES * QUADRATURE_POINTS; k += CLIPMAP_GROUP_SIZE) {
    uint e = k / QUADRATURE_POINTS, i = k % QUADRATURE_POINTS;
    vec2 u = (vec2(float(i % BIN_QUADRATURE), float(i / BIN_QUADRATURE)) + 0.5) / float(BIN_QUADRATURE);
    quadratureDirections[k] = clipmapEntryDirection(e, u);
  }
  barrier();
}

// The mean of max(0, n . w) over the directions w of bin e.
float binMeanCosine(uint e, vec3 n) {
  float sum = 0.0;
  [[dont_unroll]] for (uint i = 0u; i < QUADRATURE_POINTS; ++i)
    sum += max(dot(n, quadratureDirections[e * QUADRATURE_POINTS + i]), 0.0);
  return sum / float(QUADRATURE_POINTS);
}

void main() {
  computeQuadratureDirections();  // before any thread leaves: the barrier needs them all
  uint index = gl_GlobalInvocationID.x;
  if (index >= ClipmapFrameRef(pc.buffers.frame).v.liveCount) return;
  uint cell = ClipmapLiveListRef(pc.buffers.liveList).v[index];
  ClipmapEntriesRef entries = ClipmapEntriesRef(pc.buffers.entries);
  ClipmapCellsRef cells = ClipmapCellsRef(pc.buffers.cells);
  vec4 r = vec4(0.0), g = vec4(0.0), b = vec4(0.0);
  vec3 normal = cells.v[cell].normal;
  vec3 exactOverPi = vec3(0.0);  // irradiance / pi at `normal` by the quadrature
  uint valid = 0u;
  [[dont_unroll]] for (uint e = 0u; e < CLIPMAP_ENTRIES; ++e) {
    ClipmapEntry entry = entries.v[cell * CLIPMAP_ENTRIES + e];
    if (!(entry.M > 0.0)) continue;
    vec3 integral = entry.radiance * entry.W;
    if (!clipmapFinite(integral)) continue;
    vec4 y = shBasisL1(CLIPMAP_ENTRY_MEAN_DIRECTION[e]);
    r += integral.r * y;
    g += integral.g * y;
    b += integral.b * y;
    exactOverPi += integral * (binMeanCosine(e, normal) / PI);
    ++valid;
  }
  uint flags = cells.v[cell].flags;
  if (valid > 0u) {
    float shOverPi = clipmapLuminance(vec3(shIrradianceOverPi(r, normal),
                                           shIrradianceOverPi(g, normal),
                                           shIrradianceOverPi(b, normal)));
    float k = shOverPi > 1e-8 ? clipmapLuminance(exactOverPi) / shOverPi : 1.0;
    float scale = float(CLIPMAP_ENTRIES) / float(valid);
    cells.v[cell].shR = r * scale;
    cells.v[cell].shG = g * scale;
    cells.v[cell].shB = b * scale;
    cells.v[cell].irradianceScale = clamp(k, 1.0 / NORMALISATION_LIMIT, NORMALISATION_LIMIT);
    flags |= CLIPMAP_CELL_SH_VALID;
  } else {
    flags &= ~CLIPMAP_CELL_SH_VALID;
  }
  cells.v[cell].flags = flags;
  cells.v[cell].validEntries = valid;
}
