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

// The cache as a consumer sees it: its constants and its buffers.
struct ClipmapCacheView {
  ClipmapConstantsRef constants;
  ClipmapGridRef grid;
  ClipmapCellsRef cells;
  ClipmapEntriesRef entries;
  ClipmapPoolRef pool;
  ClipmapCountersRef counters;
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

float clipmapLuminance(vec3 c) { return dot(c, vec3(0.2126, 0.7152, 0.0722)); }

bool clipmapFinite(vec3 v) { return !any(isnan(v)) && !any(isinf(v)); }

#endif
