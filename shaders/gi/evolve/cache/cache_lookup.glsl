// The clipmap cache's lookup, used by every consumer (the cache's own rays, `gi-cache-lookup`,
// ReSTIR GI):
//   ClipmapCacheView clipmapCacheView(DeviceAddress cacheConstants);
//   vec3 cacheLookupIrradiance(ClipmapCacheView cache, vec3 position, vec3 normal, uint randomSeed);
// The caller declares the cache's buffers on its pass (ClipmapCache::declareLookup): a lookup
// marks the cell it uses and allocates a missing one from the pool.
//
// The cascade is the finest one whose window holds the point with a margin of two cells
// (Chebyshev distance to the camera). The point is moved half a cell along the normal, so the
// cell sits in front of the surface, then shifted in two ways that hide the grid (seed 000's
// picture; Gautron 2022, "Advances in spatial hashing"): a periodic wobble that bends cell
// boundaries, and a random jitter of up to half a cell in the tangent plane, which averages to
// a smooth interpolation over frames and pixels. A new cell has no SH until its first
// cache-build-sh; until then the lookup falls back to the coarser cascades.
//
// Nothing a lookup leaves depends on the order of the lookups (so a frame's image does not
// depend on thread scheduling): its touches go to the grid slot, cell or not, and a cell's
// origin is not the allocating lookup's hit but elected among all the lookups that may allocate
// it (clipmapVote).
#ifndef BOUNCE_GI_EVOLVE_CACHE_LOOKUP_GLSL
#define BOUNCE_GI_EVOLVE_CACHE_LOOKUP_GLSL
#include "common/ray_offset.glsl"
#include "gi/evolve/cache/cache_common.glsl"

// The factor a lookup with `normal` scales the cell's SH irradiance by (cache-build-sh): the
// cell's scale for its own normal, fading to 1 as the normals part (cos^4: 0.7 at 25 degrees,
// 0.25 at 45), since the SH's L1 error depends on the normal and a corner cell serves
// surfaces of other orientations too.
float clipmapIrradianceScale(float cellScale, vec3 cellNormal, vec3 normal) {
  float agreement = clamp(dot(cellNormal, normal), 0.0, 1.0);
  agreement *= agreement;
  return mix(1.0, cellScale, agreement * agreement);
}

// The finest cascade for `position`; CLIPMAP_CASCADES when it lies beyond all of them.
uint clipmapCascadeFor(ClipmapCacheView cache, vec3 position) {
  vec3 d = abs(position - cache.cameraPosition);
  float ratio = max(d.x, max(d.y, d.z)) /
                (cache.finestCellSize * float(CLIPMAP_GRID / 2u - 2u));
  if (!(ratio > 1.0)) return 0u;
  return min(uint(ceil(log2(ratio))), CLIPMAP_CASCADES);
}

// The sample point in cascade cell units before flooring (see the top of the file).
vec3 clipmapSamplePoint(vec3 position, vec3 normal, float cellSize, vec2 jitter) {
  vec3 p = position + normal * (0.5 * cellSize);
  // Periodic wobble of a quarter cell with a period of about 3.7 cells (an irrational ratio,
  // so it does not line up with the grid).
  // The phase is reduced to one period before the sine: p / cellSize reaches thousands far from
  // the origin, where sin's own range reduction differs between devices (GPU fast paths,
  // lavapipe with and without FMA) and would move cell boundaries.
  p += (0.25 * cellSize) * sin((2.0 * PI) * fract(p.yzx / (3.7 * cellSize)));
  vec3 t, b;
  orthonormalBasis(normal, t, b);
  p += cellSize * (jitter.x * t + jitter.y * b);
  return p / cellSize;
}

// Takes a cell from the pool for `slot`, which was found empty. Returns the grid value
// (cell + 1), or 0 when another lookup is allocating it or the pool is exhausted. The cell has
// no origin until cache-update-clipmap counts the election (clipmapVote); its touch level comes
// from the slot's touches (cache-update-lifetimes).
uint clipmapAllocate(ClipmapCacheView cache, uint slot, ivec3 coord, uint cascade) {
  if (atomicCompSwap(cache.grid.v[slot], 0u, CLIPMAP_SLOT_LOCKED) != 0u) return 0u;
  uint top = atomicAdd(cache.counters.v.allocated, 1u);
  if (top >= cache.poolCapacity) {
    // Allocations and frees never share a pass, so undoing the increment is exact.
    atomicAdd(cache.counters.v.allocated, 0xFFFFFFFFu);
    atomicAdd(cache.counters.v.allocationFailures, 1u);
    atomicExchange(cache.grid.v[slot], 0u);
    return 0u;
  }
  uint stored = cache.pool.v[top];
  uint cell = stored == 0u ? top : stored - 1u;
  cache.cells.v[cell].coord = ivec4(coord, int(cascade));
  cache.cells.v[cell].origin = vec3(0.0);
  cache.cells.v[cell].age = 0u;
  cache.cells.v[cell].normal = vec3(0.0, 0.0, 1.0);
  cache.cells.v[cell].originCloseness = 0u;
  cache.cells.v[cell].shR = vec4(0.0);
  cache.cells.v[cell].shG = vec4(0.0);
  cache.cells.v[cell].shB = vec4(0.0);
  cache.cells.v[cell].flags = CLIPMAP_CELL_ALIVE;
  cache.cells.v[cell].validEntries = 0u;
  cache.cells.v[cell].irradianceScale = 1.0;
  for (uint e = 0u; e < CLIPMAP_ENTRIES; ++e) {
    uint i = cell * CLIPMAP_ENTRIES + e;
    cache.entries.v[i].radiance = vec3(0.0);
    cache.entries.v[i].M = 0.0;
    cache.entries.v[i].direction = vec3(0.0, 0.0, 1.0);
    cache.entries.v[i].W = 0.0;
    cache.entries.v[i].origin = vec3(0.0);
    cache.entries.v[i].weightSum = 0.0;
    cache.entries.v[i].hitDistance = 0.0;
  }
  atomicAdd(cache.counters.v.allocationsTotal, 1u);
  // Publish. No memoryBarrierBuffer() here: on lavapipe 22.3 a memory barrier in divergent
  // control flow ends the invocation early (the pass's later image stores were lost). None is
  // needed: a lookup that finds the cell in this pass reads only its flags (SH_VALID is set by
  // the next frame's cache-build-sh, after the graph's barriers) and its originCloseness, 0
  // both here and where the cell was last freed (clipmapFreeCell).
  atomicExchange(cache.grid.v[slot], cell + 1u);
  return cell + 1u;
}

// A lookup's candidacy for the origin of the cell of `slot` (ClipmapSlotVote): its closeness
// is a hash of its numbers, or with CLIPMAP_ELECT_CENTRE that of its unjittered sample point to
// the cell's centre (cache_common.glsl says why not). The winner is the same whatever the order of the
// lookups: the key and each word of the origin only rise (atomicMax), and each starts with the
// closeness. A lookup that cannot replace the cell's current origin does not vote
// (cache-update-clipmap would not move it), so that in a settled cell lookups read one word
// more and write none. `value`: the slot's grid value.
void clipmapVote(ClipmapCacheView cache, uint slot, ivec3 coord, uint cascade, vec3 position,
                 vec3 normal, uint value) {
  uint current = value != 0u && value != CLIPMAP_SLOT_LOCKED
                     ? cache.cells.v[value - 1u].originCloseness
                     : 0u;
  if (!CLIPMAP_ELECT_CENTRE && current != 0u) return;  // elected once
  float cellSize = clipmapCellSize(cache, cascade);
  vec3 centre = vec3(coord) + 0.5;
  vec3 origin = offsetRayOrigin(position, normal) + normal * (1e-3 * cellSize);
  vec3 offset = origin / cellSize - centre;
  uvec4 numbers = uvec4(clipmapVoteQuantize(offset.x), clipmapVoteQuantize(offset.y),
                        clipmapVoteQuantize(offset.z), clipmapVotePackNormal(normal));
  uint closeness;
  if (CLIPMAP_ELECT_CENTRE) {
    float distance = length(clipmapSamplePoint(position, normal, cellSize, vec2(0.0)) - centre);
    closeness = 65535u - min(uint(round(distance * CLIPMAP_VOTE_STEPS_PER_CELL)), 65534u);
    if (closeness <= current) return;
  } else {
    closeness = 1u + clipmapVoteHash(numbers ^ uvec4(0x2C1B3C6Du)) % 65535u;
  }
  uint key = (closeness << 16u) | clipmapVoteHash(numbers);
  // Only a closer candidate stops this one: every candidate of the winning closeness writes its
  // numbers, whatever its hash and order, so that a mix of equally close ones is the same mix
  // (and refused the same way) in every schedule.
  if (closeness < (cache.votes.v[slot].key >> 16u)) return;  // keys only rise
  if ((atomicMax(cache.votes.v[slot].key, key) >> 16u) > closeness) return;
  for (uint k = 0u; k < 4u; ++k)
    atomicMax(cache.votes.v[slot].data[k], (closeness << 16u) | numbers[k]);
}

// Finds the cell serving `position`: the chosen cascade's, else the first coarser one holding a
// cell with SH. touch: CLIPMAP_TOUCH_* to mark the cells used (0: a pure read, as the debug view
// does); allocate: take a cell for a missing one in the chosen cascade. Returns the cell + 1, or
// 0 when no cell with SH serves the point; `cascadeUsed` is the cascade that did
// (CLIPMAP_CASCADES when none). Lux's candidates read the cell's SH itself (gi/lux/).
uint clipmapFindCell(ClipmapCacheView cache, vec3 position, vec3 normal, vec2 jitter, uint touch,
                     bool allocate, out uint cascadeUsed) {
  cascadeUsed = CLIPMAP_CASCADES;
  uint first = clipmapCascadeFor(cache, position);
  for (uint cascade = first; cascade < CLIPMAP_CASCADES; ++cascade) {
    float cellSize = clipmapCellSize(cache, cascade);
    ivec3 coord = ivec3(floor(clipmapSamplePoint(position, normal, cellSize, jitter)));
    if (!clipmapInWindow(cache.constants.v.cascadeOrigin[cascade].xyz, coord)) continue;
    uint slot = clipmapSlot(cascade, coord);
    // The touch goes to the slot, so that it counts whether the cell was there yet or being
    // allocated by another lookup.
    if (touch != 0u && (cache.votes.v[slot].touched & touch) != touch)
      atomicOr(cache.votes.v[slot].touched, touch);
    uint value = cache.grid.v[slot];
    if (allocate && cascade == first) {
      if (value == 0u) value = clipmapAllocate(cache, slot, coord, cascade);
      clipmapVote(cache, slot, coord, cascade, position, normal, value);
    }
    if (value == 0u || value == CLIPMAP_SLOT_LOCKED) continue;
    uint cell = value - 1u;
    if ((cache.cells.v[cell].flags & CLIPMAP_CELL_SH_VALID) == 0u) continue;
    cascadeUsed = cascade;
    return value;
  }
  return 0u;
}

// The general query: clipmapFindCell's cell, its SH evaluated for `normal`. Returns false when
// no cell with SH serves the point.
bool clipmapQueryCell(ClipmapCacheView cache, vec3 position, vec3 normal, vec2 jitter,
                      uint touch, bool allocate, out vec3 irradianceOverPi, out uint cascadeUsed) {
  irradianceOverPi = vec3(0.0);
  uint value = clipmapFindCell(cache, position, normal, jitter, touch, allocate, cascadeUsed);
  if (value == 0u) return false;
  uint cell = value - 1u;
  vec3 e = vec3(shIrradianceOverPi(cache.cells.v[cell].shR, normal),
                shIrradianceOverPi(cache.cells.v[cell].shG, normal),
                shIrradianceOverPi(cache.cells.v[cell].shB, normal)) *
           clipmapIrradianceScale(cache.cells.v[cell].irradianceScale,
                                  cache.cells.v[cell].normal, normal);
  irradianceOverPi = clipmapFinite(e) ? e : vec3(0.0);
  return true;
}

// clipmapQueryCell's irradiance / pi, zero where no cell serves the point.
vec3 clipmapQuery(ClipmapCacheView cache, vec3 position, vec3 normal, vec2 jitter, uint touch,
                  bool allocate) {
  vec3 irradianceOverPi;
  uint cascadeUsed;
  clipmapQueryCell(cache, position, normal, jitter, touch, allocate, irradianceOverPi,
                   cascadeUsed);
  return irradianceOverPi;
}

// Irradiance / pi (diffuse radiance per unit albedo) at `position` with unit normal `normal`,
// from the clipmap cache; marks the cell used and requests allocation of a missing cell.
// randomSeed: a hash of (pixel, frame, purpose); it picks the jitter.
vec3 cacheLookupIrradiance(ClipmapCacheView cache, vec3 position, vec3 normal, uint randomSeed) {
  vec2 jitter = uniformFromHash(pcg4d(uvec4(randomSeed, 0x1B873593u, 0xCC9E2D51u, 7u))).xy - 0.5;
  return clipmapQuery(cache, position, normal, jitter, CLIPMAP_TOUCH_DIRECT, true);
}

#endif
