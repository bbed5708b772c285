// What every clipmap-cache shader shares: buffer views of the cache (shared/clipmap_cache_io.h),
// the cell addressing, the equal-area octahedral direction bins and L1 spherical harmonics.
#ifndef BOUNCE_GI_EVOLVE_CACHE_COMMON_GLSL
#define BOUNCE_GI_EVOLVE_CACHE_COMMON_GLSL
#include "common/random.glsl"
#include "common/sampling.glsl"
#include "common/sh.glsl"
#include "shared/clipmap_cache_io.h"

layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer ClipmapConstantsRef {
  ClipmapCacheConstants v;
};
layout(buffer_reference, scalar, buffer_reference_align = 4) coherent buffer ClipmapGridRef {
  uint v[];
};
layout(buffer_reference, scalar, buffer_reference_align = 4) coherent buffer ClipmapCellsRef {
  ClipmapCell v[];
};
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer ClipmapEntriesRef {
  ClipmapEntry v[];
};
layout(buffer_reference, scalar, buffer_reference_align = 4) coherent buffer ClipmapPoolRef {
  uint v[];
};
layout(buffer_reference, scalar, buffer_reference_align = 4) coherent buffer ClipmapCountersRef {
  ClipmapCounters v;
};
layout(buffer_reference, scalar, buffer_reference_align = 4) coherent buffer ClipmapFrameRef {
  ClipmapFrameCounters v;
};
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer ClipmapLiveListRef {
  uint v[];
};
layout(buffer_reference, scalar, buffer_reference_align = 4) coherent buffer ClipmapVotesRef {
  ClipmapSlotVote v[];
};

// The cache as a consumer sees it: its constants and its buffers.
struct ClipmapCacheView {
  ClipmapConstantsRef constants;
  ClipmapGridRef grid;
  ClipmapCellsRef cells;
  ClipmapEntriesRef entries;
  ClipmapPoolRef pool;
  ClipmapCountersRef counters;
  ClipmapVotesRef votes;
  vec3 cameraPosition;
  float finestCellSize;
  uint frameIndex;
  uint poolCapacity;
};

ClipmapCacheView clipmapCacheView(DeviceAddress cacheConstants) {
  ClipmapConstantsRef c = ClipmapConstantsRef(cacheConstants);
  ClipmapCacheAddresses b = c.v.buffers;
  ClipmapCacheView view;
  view.constants = c;
  view.grid = ClipmapGridRef(b.grid);
  view.cells = ClipmapCellsRef(b.cells);
  view.entries = ClipmapEntriesRef(b.entries);
  view.pool = ClipmapPoolRef(b.pool);
  view.counters = ClipmapCountersRef(b.counters);
  view.votes = ClipmapVotesRef(b.votes);
  view.cameraPosition = c.v.cameraPosition;
  view.finestCellSize = c.v.finestCellSize;
  view.frameIndex = c.v.frameIndex;
  view.poolCapacity = c.v.poolCapacity;
  return view;
}

float clipmapCellSize(ClipmapCacheView cache, uint cascade) {
  return cache.finestCellSize * float(1u << cascade);
}

// Toroidal slot of an integer cell coordinate in its cascade.
uint clipmapSlot(uint cascade, ivec3 coord) {
  ivec3 t = coord & ivec3(int(CLIPMAP_GRID) - 1);  // two's complement: a true modulo for 2^k
  return cascade * CLIPMAP_SLOTS_PER_CASCADE +
         uint(t.x) + CLIPMAP_GRID * (uint(t.y) + CLIPMAP_GRID * uint(t.z));
}

// A number of the cell's own, whichever pool cell holds it: the seed of its rays' random
// numbers and its refresh round (cache-trace-diffuse-rays), so that neither depends on the
// order in which the lookups allocated cells.
uint clipmapCellKey(ivec4 coord) { return pcg4d(uvec4(coord) ^ uvec4(0x9E3779B9u)).x; }

bool clipmapInWindow(ivec3 origin, ivec3 coord) {
  return all(greaterThanEqual(coord, origin)) &&
         all(lessThan(coord, origin + ivec3(int(CLIPMAP_GRID))));
}

// Equal-area octahedral map (Clarberg 2008, "Fast Equal-Area Mapping of the (Hemi)Sphere using
// SIMD"): the unit square onto the sphere with constant Jacobian 4 pi, so each of the 4x4
// entry bins covers pi/4 sr and a uniform point in a bin is a uniform direction in it.
vec3 equalAreaSquareToSphere(vec2 p) {
  vec2 uv = 2.0 * p - 1.0;
  vec2 a = abs(uv);
  float signedDistance = 1.0 - (a.x + a.y);
  float r = 1.0 - abs(signedDistance);
  float phi = (r == 0.0 ? 1.0 : (a.y - a.x) / r + 1.0) * (PI / 4.0);
  float z = signedDistance >= 0.0 ? 1.0 - r * r : -(1.0 - r * r);
  float s = r * sqrt(max(0.0, 2.0 - r * r));
  float cosPhi = uv.x >= 0.0 ? cos(phi) : -cos(phi);
  float sinPhi = uv.y >= 0.0 ? sin(phi) : -sin(phi);
  return normalize(vec3(cosPhi * s, sinPhi * s, z));
}

// Direction bin e (0..15) of a cell, u uniform in [0,1)^2 within it.
vec3 clipmapEntryDirection(uint e, vec2 u) {
  return equalAreaSquareToSphere((vec2(float(e % 4u), float(e / 4u)) + u) * 0.25);
}

const float CLIPMAP_ENTRY_PDF = 4.0 / PI;  // 1 / (pi/4 sr)

// Mean of the unit directions over each bin (a vector of length 0.93, not normalised):
// integral of d over the bin / (pi/4). Numerically integrated (64x64 points per bin) over
// equalAreaSquareToSphere. cache-build-sh projects a bin's radiance integral onto the L1 basis
// with it: exact for radiance constant over the bin, and, unlike the direction of the one kept
// sample, free of noise.
const vec3 CLIPMAP_ENTRY_MEAN_DIRECTION[CLIPMAP_ENTRIES] = vec3[](
    vec3(-0.42398, -0.42398, -0.70834), vec3(-0.27872, -0.87340, 0.0),
    vec3(0.27872, -0.87340, 0.0), vec3(0.42398, -0.42398, -0.70834),
    vec3(-0.87340, -0.27872, 0.0), vec3(-0.42398, -0.42398, 0.70834),
    vec3(0.42398, -0.42398, 0.70834), vec3(0.87340, -0.27872, 0.0),
    vec3(-0.87340, 0.27872, 0.0), vec3(-0.42398, 0.42398, 0.70834),
    vec3(0.42398, 0.42398, 0.70834), vec3(0.87340, 0.27872, 0.0),
    vec3(-0.42398, 0.42398, -0.70834), vec3(-0.27872, 0.87340, 0.0),
    vec3(0.27872, 0.87340, 0.0), vec3(0.42398, 0.42398, -0.70834));

// cache-trace-diffuse-rays' rays per live cell and frame: raysPerCell new candidates, each
// entry refreshed every clipmapTraceRounds() frames, and validation rays (at most raysPerCell,
// none when one round covers every entry).
uint clipmapTraceRounds(ClipmapCacheConstants k) { return CLIPMAP_ENTRIES / k.raysPerCell; }
uint clipmapValidationRays(ClipmapCacheConstants k) {
  return clipmapTraceRounds(k) >= 2u ? min(k.validationRaysPerCell, k.raysPerCell) : 0u;
}
// Threads per live cell in cache-trace-diffuse-rays: its rays rounded up to a power of two
// (raysPerCell is one), so that a workgroup holds whole cells and no lane idles.
uint clipmapTraceLanes(ClipmapCacheConstants k) {
  return clipmapValidationRays(k) > 0u ? 2u * k.raysPerCell : k.raysPerCell;
}

// The numbers of a candidate origin in the election of a cell's origin (ClipmapSlotVote in
// shared/clipmap_cache_io.h; cache_lookup.glsl votes, cache-update-clipmap counts). An
// origin's offset from the cell's centre lies within 2 cells on each axis (the surface point
// is half a cell behind its sample point, which the wobble and the jitter move by at most a
// quarter and 0.71 of a cell): 16-bit fixed point over [-2.5, 2.5] keeps it to 4e-5 cells,
// well inside the 1e-3 cells that the origin sits in front of its surface.
const float CLIPMAP_VOTE_RANGE = 2.5;
// Which candidate wins: false, a pseudo-random one (a hash of its numbers), once, as
// unbiased as the first-come lookup that allocated the cell used to be but free of the order;
// true, the one whose unjittered sample point lies closest to the cell's centre, re-elected
// whenever a closer one comes. The closest lost 27 % in a furnace pixel (1.46 for 2, bound
// 1.8): where a cell's centre lies beyond a wall the closest surface point is on the edge
// where two faces meet, and rays from there leak (docs/gi/clipmap-cache.md).
const bool CLIPMAP_ELECT_CENTRE = false;
// Closeness steps per cell of distance: 65535 steps over 2.5 cells.
const float CLIPMAP_VOTE_STEPS_PER_CELL = 26214.0;

uint clipmapVoteQuantize(float x) {
  return uint(round(clamp(x / (2.0 * CLIPMAP_VOTE_RANGE) + 0.5, 0.0, 1.0) * 65535.0));
}
float clipmapVoteDequantize(uint q) {
  return (float(q) / 65535.0 - 0.5) * (2.0 * CLIPMAP_VOTE_RANGE);
}
vec2 clipmapSignNotZero(vec2 v) { return vec2(v.x >= 0.0 ? 1.0 : -1.0, v.y >= 0.0 ? 1.0 : -1.0); }
// Octahedral normal (Cigolle et al. 2014) in 8 + 8 bits: within a degree, which is all the
// cell's normal needs (cache-build-sh's normalisation, the lookups' agreement weight).
uint clipmapVotePackNormal(vec3 n) {
  vec2 p = n.xy / (abs(n.x) + abs(n.y) + abs(n.z));
  if (n.z < 0.0) p = (1.0 - abs(p.yx)) * clipmapSignNotZero(p);
  uvec2 q = uvec2(round(clamp(p * 0.5 + 0.5, 0.0, 1.0) * 255.0));
  return q.x | (q.y << 8u);
}
vec3 clipmapVoteUnpackNormal(uint q) {
  vec2 e = vec2(float(q & 255u), float((q >> 8u) & 255u)) * (2.0 / 255.0) - 1.0;
  vec3 n = vec3(e, 1.0 - abs(e.x) - abs(e.y));
  if (n.z < 0.0) n.xy = (1.0 - abs(n.yx)) * clipmapSignNotZero(n.xy);
  return normalize(n);
}
// The 16-bit hash of a candidate's numbers (x, y, z, normal) kept in its key.
uint clipmapVoteHash(uvec4 numbers) { return pcg4d(numbers ^ uvec4(0x51ED270Bu)).x & 0xFFFFu; }

float clipmapLuminance(vec3 c) { return dot(c, vec3(0.2126, 0.7152, 0.0722)); }

bool clipmapFinite(vec3 v) { return !any(isnan(v)) && !any(isinf(v)); }

#endif
