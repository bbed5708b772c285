// GI-1.0's world-space hash-grid radiance cache (research/gi10_lux_denoisers.md §1.4), the
// second cache level: cells sized by their distance to the camera (a power-of-two multiple of
// 1 mm covering about cacheCellPixels pixels), keyed by that level, the cell and the hit
// surface's normal (quantised); buckets of GI10_BUCKET_SLOTS cells found by one
// hash, a cell within its bucket by a second hash (the checksum), inserted by compare-and-swap.
// A full bucket drops the sample and counts it (Gi10Counters::cacheOverflow).
#ifndef BOUNCE_GI_GI10_HASH_GRID_CACHE_GLSL
#define BOUNCE_GI_GI10_HASH_GRID_CACHE_GLSL
#include "gi/gi10/gi10_common.glsl"

// One round of PCG (O'Neill 2014; Jarzynski & Olano 2020's "pcg" hash) and of xxHash32's
// avalanche (Collet), the two independent hashes of the key (bucket, checksum), as in §1.4.
uint gi10Pcg(uint v) {
  uint state = v * 747796405u + 2891336453u;
  uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}

uint gi10XxHash(uint p) {
  const uint PRIME32_2 = 2246822519u, PRIME32_3 = 3266489917u;
  const uint PRIME32_4 = 668265263u, PRIME32_5 = 374761393u;
  uint h = p + PRIME32_5;
  h = PRIME32_4 * ((h << 17u) | (h >> 15u));
  h = PRIME32_2 * (h ^ (h >> 15u));
  h = PRIME32_3 * (h ^ (h >> 13u));
  return h ^ (h >> 16u);
}

struct Gi10CellKey {
  uint bucket;
  uint checksum;  // never 0 (0 marks a free slot)
  float size;     // the cell's edge in metres
};

// The key of the cell of surface point `hit` with geometric normal n (facing the ray).
// §1.4: step = max(distance x footprint of cacheCellPixels pixels, minCellSize), cell = 1 mm x
// 2^floor(log2(1e3 step)). Capsaicin keys on the probe ray's direction (5 bins per axis) and a
// near-hit flag; here on the surface's normal (3 bins per axis): it keeps the two sides of a
// wall, and the faces of a corner, in different cells as the direction does, and every ray
// that hits a surface finds the same cell, so that secondary rays from other directions
// (indirectCacheRadiance) find the cells the probe rays filled (docs/gi/gi10.md).
Gi10CellKey gi10CellKey(Gi10Constants k, FrameConstants f, vec3 hit, vec3 n) {
  float distanceToEye = length(hit - f.camera.position);
  float step = max(distanceToEye * k.pixelFootprint * k.cacheCellPixels, k.minCellSize);
  int level = int(floor(log2(1e3 * step)));
  float size = 1e-3 * exp2(float(level));
  ivec3 c = ivec3(floor(hit / size));
  uvec3 d = uvec3(clamp(floor(0.5 + (0.5 * n + 0.5) * 2.0), vec3(0.0), vec3(2.0)));
  uint h = gi10Pcg(uint(level + 64) + gi10Pcg(uint(c.x) + gi10Pcg(uint(c.y) + gi10Pcg(uint(c.z) +
           gi10Pcg(d.x + 3u * d.y + 9u * d.z)))));
  uint s = gi10XxHash(uint(level + 64) + gi10XxHash(uint(c.x) + gi10XxHash(uint(c.y) + gi10XxHash(uint(c.z) +
           gi10XxHash(d.x + 3u * d.y + 9u * d.z)))));
  Gi10CellKey key;
  key.bucket = h & k.bucketMask;
  key.checksum = max(s, 1u);
  key.size = size;
  return key;
}

// The slot of `key`, inserted when missing; GI10_NO_CELL when its bucket is full. Two threads
// inserting the same key try the free slots in the same order, so the loser of a slot's
// compare-and-swap finds the winner's checksum there and shares the cell.
uint gi10FindOrInsertCell(Gi10CacheRef cache, Gi10CellKey key) {
  uint first = key.bucket * GI10_BUCKET_SLOTS;
  for (uint i = 0u; i < GI10_BUCKET_SLOTS; ++i)
    if (cache.v[first + i].checksum == key.checksum) return first + i;
  for (uint i = 0u; i < GI10_BUCKET_SLOTS; ++i) {
    uint previous = atomicCompSwap(cache.v[first + i].checksum, 0u, key.checksum);
    if (previous == 0u || previous == key.checksum) return first + i;
  }
  return GI10_NO_CELL;
}

// The slot of `key` when the cell exists; GI10_NO_CELL otherwise (a read, never an insert).
uint gi10FindCell(Gi10CacheRef cache, Gi10CellKey key) {
  uint first = key.bucket * GI10_BUCKET_SLOTS;
  for (uint i = 0u; i < GI10_BUCKET_SLOTS; ++i)
    if (cache.v[first + i].checksum == key.checksum) return first + i;
  return GI10_NO_CELL;
}

// Adds one sample of outgoing radiance to the cell's scratch (gi10-update-radiance-cache folds
// it into the running mean) and stamps the cell alive this frame.
void gi10AddCellSample(Gi10CacheRef cache, uint slot, vec3 radiance, uint frame) {
  cache.v[slot].lastFrame = frame;
  if (atomicAdd(cache.v[slot].scratch.w, 1u) >= GI10_CACHE_MAX_FRAME_SAMPLES) return;
  uvec3 q = uvec3(clamp(radiance, vec3(0.0), vec3(GI10_CACHE_MAX_SAMPLE)) * GI10_CACHE_QUANTIZE + 0.5);
  atomicAdd(cache.v[slot].scratch.x, q.x);
  atomicAdd(cache.v[slot].scratch.y, q.y);
  atomicAdd(cache.v[slot].scratch.z, q.z);
}

#endif
