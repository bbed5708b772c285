// gi10-reproject-screen-probes (§1.2 #2, §1.3 "reprojection"): one 8x8 group per probe tile.
// Each pixel of the tile proposes last frame's probe under its velocity-reprojected position;
// a proposal counts when the probe lies within one 8-pixel footprint of the pixel's plane and
// faces the same way (normals within acos 0.95), and the pixel nearest the old probe wins.
// The tile's probe is re-anchored there (or at this frame's spawn pixel when a new probe is
// traced in this tile) and each of the old probe's cells is re-binned through its hit point
// (p + dir x hit distance) into the new hemisphere; cells nothing lands in get the mean of the
// filled ones. A surface tile with neither counts as empty (Gi10Counters::emptyTiles).
#version 460
#include "gi/gi10/gi10_common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(push_constant, scalar) uniform Push { Gi10PassConstants pc; };
layout(set = 1, binding = GI10_REPROJECT_BINDING_NORMALS, rgba16f) uniform readonly image2D normals;
layout(set = 1, binding = GI10_REPROJECT_BINDING_DEPTH, r32f) uniform readonly image2D depths;
layout(set = 1, binding = GI10_REPROJECT_BINDING_VELOCITY, rg16f) uniform readonly image2D velocities;

const uint NONE = 0xFFFFFFFFu;
shared uint bestScore;
shared uint anySurface;
shared uint proposal[GI10_PROBE_CELLS];  // the previous tile each pixel proposes
shared uint target[GI10_PROBE_CELLS];    // the new cell each old cell lands in
shared vec4 moved[GI10_PROBE_CELLS];     // its radiance and hit distance from the new anchor
shared vec4 rebinned[GI10_PROBE_CELLS];  // per new cell: mean radiance, hit distance; w < 0: empty

bool pixelGeometry(FrameConstants f, ivec2 pixel, out vec3 position, out vec3 normal, out float depth) {
  position = vec3(0.0);
  normal = vec3(0.0, 0.0, 1.0);
  depth = 0.0;
  if (any(greaterThanEqual(uvec2(pixel), f.resolution))) return false;
  depth = imageLoad(depths, pixel).x;
  if (!(depth > 0.0)) return false;
  normal = decodeOctahedral(imageLoad(normals, pixel).zw);
  position = positionFromDepth(f, vec2(pixel) + 0.5, depth);
  return true;
}

// Last frame's probe tile that `pixel` proposes, with its score (NONE: no acceptable one).
uint propose(FrameConstants f, Gi10Constants k, ivec2 pixel, vec3 x, vec3 n, float depth, out uint score) {
  score = NONE;
  vec2 previousPixel = vec2(pixel) + 0.5 - imageLoad(velocities, pixel).xy;
  if (any(lessThan(previousPixel, vec2(0.0))) || any(greaterThanEqual(previousPixel, vec2(f.resolution)))) return NONE;
  uvec2 previousTile = uvec2(previousPixel) / GI10_PROBE_SIZE;
  uint index = previousTile.y * k.probeGrid.x + previousTile.x;
  Gi10Probe p = Gi10ProbesRef(k.previousProbes).v[index];
  if ((p.flags & GI10_PROBE_VALID) == 0u) return NONE;
  float cell = gi10Footprint(k, depth, float(GI10_PROBE_SIZE));
  if (abs(dot(p.position - x, n)) >= cell || dot(n, p.normal) <= 0.95) return NONE;
  score = uint(min(length(p.position - x) / cell, 63.0) * 1023.0);
  return index;
}

void main() {
  FrameConstants f = FrameBlock(pc.frame).v;
  Gi10Constants k = Gi10ConstantsRef(pc.gi10).v;
  uvec2 tile = gl_WorkGroupID.xy;
  uint lane = gl_LocalInvocationIndex;
  uint tileIndex = tile.y * k.probeGrid.x + tile.x;
  ivec2 pixel = ivec2(tile * GI10_PROBE_SIZE + gl_LocalInvocationID.xy);
  if (lane == 0u) {
    bestScore = NONE;
    anySurface = 0u;
  }
  barrier();

  vec3 x, n;
  float depth;
  bool surface = pixelGeometry(f, pixel, x, n, depth);
  uint score = NONE;
  proposal[lane] = NONE;
  if (surface) {
    anySurface = 1u;
    if (k.historyValid != 0u) proposal[lane] = propose(f, k, pixel, x, n, depth, score);
    if (score != NONE) atomicMin(bestScore, (score << 6u) | lane);
  }
  barrier();

  uvec2 spawnPixel = Gi10SpawnRef(k.spawn).v[(tile.y * GI10_PROBE_SIZE / k.spawnTile) * k.spawnGrid.x +
                                              tile.x * GI10_PROBE_SIZE / k.spawnTile];
  bool spawned = spawnPixel.x != GI10_NO_SPAWN && all(equal(spawnPixel / GI10_PROBE_SIZE, tile));
  bool reprojected = bestScore != NONE;
  Gi10ProbesRef probes = Gi10ProbesRef(k.probes);
  if (!spawned && !reprojected) {
    if (lane == 0u) {
      probes.v[tileIndex].flags = 0u;
      if (anySurface != 0u) GI10_COUNT(k, emptyTiles)
    }
    return;
  }
  uint bestLane = bestScore & 63u;
  ivec2 anchor = spawned ? ivec2(spawnPixel) : ivec2(tile * GI10_PROBE_SIZE + uvec2(bestLane % 8u, bestLane / 8u));
  vec3 anchorPosition, anchorNormal;
  float anchorDepth;
  pixelGeometry(f, anchor, anchorPosition, anchorNormal, anchorDepth);
  if (lane == 0u) {
    Gi10Probe p;
    p.position = anchorPosition;
    p.normal = anchorNormal;
    p.depth = anchorDepth;
    p.flags = GI10_PROBE_VALID | (reprojected ? GI10_PROBE_HISTORY : 0u) | (spawned ? GI10_PROBE_SPAWNED : 0u);
    probes.v[tileIndex] = p;
    if (reprojected) GI10_COUNT(k, reprojectedProbes)
  }
  if (!reprojected) return;

  // Re-bin: old cell `lane` through its hit point into the new hemisphere.
  Gi10Probe old = Gi10ProbesRef(k.previousProbes).v[proposal[bestLane]];
  vec4 cell = gi10UnpackCell(Gi10RadianceRef(k.previousRadiance).v[proposal[bestLane] * GI10_PROBE_CELLS + lane]);
  vec3 dir = gi10HemisphereDirection(old.normal, gi10CellCentre(lane));
  float distance = GI10_MISS_DISTANCE;
  if (cell.w < GI10_MISS_DISTANCE) {
    vec3 v = old.position + dir * cell.w - anchorPosition;
    distance = length(v);
    dir = distance > 0.0 ? v / distance : dir;
  }
  bool lands = dot(dir, anchorNormal) > 0.0;
  target[lane] = lands ? gi10CellOfSquare(gi10HemisphereSquare(anchorNormal, dir)) : NONE;
  moved[lane] = vec4(cell.rgb, distance);
  barrier();

  vec4 sum = vec4(0.0);
  float count = 0.0;
  for (uint i = 0u; i < GI10_PROBE_CELLS; ++i) {
    if (target[i] != lane) continue;
    sum += moved[i];
    count += 1.0;
  }
  rebinned[lane] = count > 0.0 ? sum / count : vec4(0.0, 0.0, 0.0, -1.0);
  barrier();
  vec4 result = rebinned[lane];
  if (result.w < 0.0) {
    vec4 filled = vec4(0.0);
    float filledCount = 0.0;
    for (uint i = 0u; i < GI10_PROBE_CELLS; ++i) {
      if (rebinned[i].w < 0.0) continue;
      filled += rebinned[i];
      filledCount += 1.0;
    }
    result = filledCount > 0.0 ? filled / filledCount : vec4(0.0, 0.0, 0.0, GI10_MISS_DISTANCE);
  }
  Gi10RadianceRef(k.radiance).v[tileIndex * GI10_PROBE_CELLS + lane] = gi10PackCell(result.rgb, result.w);
}
