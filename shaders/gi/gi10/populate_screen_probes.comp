// gi10-populate-screen-probes (§1.2 #7, #10, #13): one group per spawn tile, one thread per
// cell of its new probe. Each thread traces one ray, uniform within its cell of the probe's
// hemisphere. A miss sees the sky. At a hit: emission (not that of emitters ReSTIR DI already
// lights the pixel with, FRAME_FLAG_DI_LIGHTS), and the hit's outgoing diffuse radiance:
// direct light (the sun, one light of the light tables, the KHR directional lights, each with
// a shadow ray; §1.5 uses a light grid instead) plus the hit's albedo times the light arriving
// there: by temporal radiance feedback (§1.6) last frame's GI where the hit is on screen, else
// the cache's radiance along one cosine ray from the hit (indirectCacheRadiance, a stand-in for
// GI-1.2's multibounce, so that off-screen hits get more than one bounce). That sample goes into the
// hash-grid cell of the hit (hash_grid_cache.glsl); the probe later reads the cell's filtered
// radiance (gi10-resolve-radiance-cache). The leak guard (§1.4): a hit closer than its cell's
// size takes its own sample instead, as does one whose bucket is full.
#version 460
#include "gi/gi10/hash_grid_cache.glsl"
#include "lighting/frame_sun.glsl"
#include "lighting/regularize.glsl"
#include "lighting/specular_albedo.glsl"

layout(local_size_x = GI10_GROUP_SIZE) in;
layout(push_constant, scalar) uniform Push { Gi10PassConstants pc; };
layout(set = 1, binding = GI10_POPULATE_BINDING_NORMALS, rgba16f) uniform readonly image2D normals;
layout(set = 1, binding = GI10_POPULATE_BINDING_DEPTH, r32f) uniform readonly image2D depths;
layout(set = 1, binding = GI10_POPULATE_BINDING_VELOCITY, rg16f) uniform readonly image2D velocities;
layout(set = 1, binding = GI10_POPULATE_BINDING_PREVIOUS_GI, rgba16f) uniform readonly image2D previousGi;

const float FAR = 1e30;
const uint RANDOM_GI10_PROBE_RAY = 0x47313001u;

// Reflected direct light at s towards wo: the sun (when it shines), one local light, each KHR
// directional light, in one loop with one shadow-ray call (a CPU driver compiles each inlined
// copy of the traversal: docs/startup.md).
vec3 directLight(FrameConstants f, Surface s, vec3 wo, uvec4 seed, bool alphaTest) {
  vec3 origin = offsetRayOrigin(s.position, s.geometricNormal);
  BrdfMaterial lobe = regularizedMaterial(s.brdf, DIFFUSE_RAY_HIT_MIN_ALPHA);
  const uint SUN = 0u, LOCAL = 1u, FIRST_DISTANT = 2u;
  vec3 sum = vec3(0.0);
  for (uint light = SUN; light < FIRST_DISTANT + lightTables.distantLightCount; ++light) {
    vec4 u = uniformFromHash(pcg4d(seed + uvec4(0u, 0u, 0u, light)));
    LightSample l;
    if (light == SUN) l = sampleFrameSun(f, u.xy);
    else if (light == LOCAL) l = sampleLocalLight(s.position, u);
    else l = sampleDistantLight(light - FIRST_DISTANT, u.xy);
    if (!l.valid) continue;
    float cosine = dot(s.shadingNormal, l.direction);
    if (cosine <= 0.0 || dot(s.geometricNormal, l.direction) <= 0.0) continue;
    vec3 contribution = brdfEvaluate(lobe, s.shadingNormal, wo, l.direction) * cosine * l.radianceOverPdf;
    if (!any(greaterThan(contribution, vec3(0.0)))) continue;
    vec3 shadowDirection = l.distant ? l.direction : l.shadowTarget - origin;
    if (traceVisibility(origin, shadowDirection, 0.0, l.distant ? FAR : 1.0, alphaTest)) sum += contribution;
  }
  return sum;
}

// §1.6: the hit projected into this frame's view; where the pixel there sees the same surface
// (view depth within 5 %, normals within 60 degrees) last frame's GI at that pixel (through its
// velocity) is the light arriving at the hit. False off screen or where it sees another surface.
bool feedback(FrameConstants f, Gi10Constants k, vec3 p, vec3 n, out vec3 irradianceOverPi) {
  irradianceOverPi = vec3(0.0);
  if ((k.flags & GI10_FLAG_FEEDBACK) == 0u || k.historyValid == 0u) return false;
  vec4 clip = f.viewProjection * vec4(p, 1.0);
  if (!(clip.w > 0.0)) return false;
  vec2 q = (clip.xy / clip.w * 0.5 + 0.5) * vec2(f.resolution);
  if (any(lessThan(q, vec2(0.0))) || any(greaterThanEqual(q, vec2(f.resolution)))) return false;
  ivec2 pixel = ivec2(q);
  float depth = imageLoad(depths, pixel).x;
  float hitDepth = gi10ViewDepth(f, p);
  if (!(depth > 0.0) || abs(depth - hitDepth) > 0.05 * hitDepth) return false;
  if (dot(decodeOctahedral(imageLoad(normals, pixel).zw), n) < 0.5) return false;
  ivec2 previous = ivec2(vec2(pixel) + 0.5 - imageLoad(velocities, pixel).xy);
  if (any(lessThan(previous, ivec2(0))) || any(greaterThanEqual(uvec2(previous), f.resolution))) return false;
  vec4 gi = imageLoad(previousGi, previous);
  if (!(gi.w > 0.0)) return false;
  irradianceOverPi = gi.rgb;
  return true;
}

// Radiance leaving surface s back along a secondary ray, from the cache: the
// cell it lands in (last frame's running mean: direct light and the bounces before), plus the
// emission of large emitters, which the first hit's light sampling does not cover (the light
// tables leave them to rays, src/lighting/gpu_light_tables.h). GI-1.2's "multibounce" traces
// rays from the cells instead; this gives off-screen hits (no feedback) their bounces.
vec3 indirectCacheRadiance(FrameConstants f, Gi10Constants k, Gi10CacheRef cache, Surface s) {
  vec3 emission = lightTablesSampleMaterial(s.material) ? vec3(0.0) : s.emission;
  uint slot = gi10FindCell(cache, gi10CellKey(k, f, s.position, s.geometricNormal));
  return emission + (slot != GI10_NO_CELL ? cache.v[slot].radiance : vec3(0.0));
}

void main() {
  FrameConstants f = FrameBlock(pc.frame).v;
  Gi10Constants k = Gi10ConstantsRef(pc.gi10).v;
  uint spawnIndex = gl_WorkGroupID.y * k.spawnGrid.x + gl_WorkGroupID.x;
  uvec2 spawnPixel = Gi10SpawnRef(k.spawn).v[spawnIndex];
  if (spawnPixel.x == GI10_NO_SPAWN) return;
  uint cellIndex = gl_LocalInvocationIndex;
  uvec2 tile = spawnPixel / GI10_PROBE_SIZE;
  Gi10Probe probe = Gi10ProbesRef(k.probes).v[tile.y * k.probeGrid.x + tile.x];
  lightTables = LightTablesBlock(k.lights).v;
  bool alphaTest = (k.flags & GI10_FLAG_ALPHA_TEST) != 0u;

  uvec4 seed = pcg4d(uvec4(spawnPixel, f.frameIndex, RANDOM_GI10_PROBE_RAY + cellIndex));
  vec2 u = uniformFromHash(seed).xy;
  vec2 square = (vec2(cellIndex % GI10_PROBE_SIZE, cellIndex / GI10_PROBE_SIZE) + u) / float(GI10_PROBE_SIZE);
  vec3 dir = gi10HemisphereDirection(probe.normal, square);
  Gi10Ray ray;
  ray.cell = GI10_NO_CELL;
  ray.radiance = vec3(0.0);
  ray.hitDistance = GI10_MISS_DISTANCE;
  Gi10CacheRef cache = Gi10CacheRef(k.cache);
  bool lambert = (f.flags & FRAME_FLAG_LAMBERT) != 0u;
  // The probe ray, then (when feedback cannot light its hit) one cosine ray from the hit into
  // the cache: one traceClosest call in a loop (a CPU driver compiles each inlined copy).
  vec3 rayOrigin = offsetRayOrigin(probe.position, probe.normal), rayDir = dir;
  vec3 hitPosition = vec3(0.0), hitNormal = vec3(0.0), direct = vec3(0.0), albedo = vec3(0.0), indirect = vec3(0.0);
  bool hitSurface = false;
  for (uint bounce = 0u; bounce < 2u; ++bounce) {
    TraceHit hit = traceClosest(rayOrigin, rayDir, 0.0, FAR, alphaTest);
    if (!traceHitFound(hit)) {
      if (bounce == 0u) ray.radiance = skyRadianceToward(f, rayDir);
      else indirect = skyRadianceToward(f, rayDir);
      break;
    }
    Surface s = loadSurfaceAtCoarseMip(hit, rayDir, lambert, k.materialTextureSide);
    if (bounce == 1u) {
      indirect = indirectCacheRadiance(f, k, cache, s);
      break;
    }
    hitSurface = true;
    hitPosition = s.position;
    hitNormal = s.geometricNormal;
    ray.hitDistance = hit.t;
    bool diLit = (f.flags & FRAME_FLAG_DI_LIGHTS) != 0u && lightTablesSampleMaterial(s.material);
    ray.radiance = diLit ? vec3(0.0) : s.emission;
    direct = directLight(f, s, -rayDir, seed.yzwx, alphaTest);
    albedo = indirectHitReflectance(f.specularAlbedo, s.brdf, s.shadingNormal, -rayDir);
    if (feedback(f, k, s.position, s.geometricNormal, indirect)) {
      GI10_COUNT(k, feedbackHits)
      break;
    }
    rayOrigin = offsetRayOrigin(s.position, s.geometricNormal);
    rayDir = sampleCosineHemisphere(s.geometricNormal, uniformFromHash(seed.zwxy).xy);
  }
  if (hitSurface) {
    vec3 hitSample = direct + albedo * indirect;
    if (any(isnan(hitSample)) || any(isinf(hitSample))) hitSample = vec3(0.0);
    Gi10CellKey key = gi10CellKey(k, f, hitPosition, hitNormal);
    uint slot = gi10FindOrInsertCell(cache, key);
    if (slot != GI10_NO_CELL) {
      gi10AddCellSample(cache, slot, hitSample, k.frame);
      GI10_COUNT(k, cacheInserts)
    } else {
      GI10_COUNT(k, cacheOverflow)
    }
    if (slot == GI10_NO_CELL || ray.hitDistance < key.size) ray.radiance += hitSample;
    else ray.cell = slot;
  }
  uint rayIndex = spawnIndex * GI10_PROBE_CELLS + cellIndex;
  Gi10RaysRef(k.rays).v[rayIndex] = ray;
  GI10_COUNT(k, probeRays)
  if (cellIndex == 0u) GI10_COUNT(k, spawnedProbes)
}
