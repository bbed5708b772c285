// Radiance arriving along a cache ray (cache-trace-diffuse-rays, seed 000): at the hit, light
// reflected once from the frame's sun and from the scene's lights by next-event estimation (one
// sample of the sun, one local light, emissive triangle or KHR punctual, picked by power, and
// every KHR directional light; src/lighting/gpu_light_tables.h), plus the reflectance
// (indirectHitReflectance: a metal's by its specular lobe) times the cache's irradiance at the hit (a recursive lookup, which makes the bounces infinite), plus the
// surface's emission; the sky on a miss.
// Emitters are split between NEE and the cache's rays (src/lighting/gpu_light_tables.h): large ones
// are not in the light tables (area pdf 0) and count when a ray hits them, small ones count by
// NEE only, at every consumer that adds the cache's irradiance at a point (ReSTIR GI's 2nd
// vertex, gi-cache-lookup, the cache's own rays here), and never when hit. The sun and the KHR
// lights are never hit: NEE alone. The reference estimator of the tests
// (reference_irradiance.comp) uses the same direct-light sample and split.
// The caller loads the light tables into `lightTables` (lighting/light_tables.glsl) first.
#ifndef BOUNCE_GI_EVOLVE_CACHE_RADIANCE_GLSL
#define BOUNCE_GI_EVOLVE_CACHE_RADIANCE_GLSL
#include "gi/evolve/cache/cache_lookup.glsl"
#include "passes/hybrid_frame.glsl"
#include "lighting/lights.glsl"
#include "lighting/regularize.glsl"
#include "lighting/specular_albedo.glsl"
#include "lighting/surface.glsl"

const float CACHE_RAY_FAR = 1e30;
// Whether a cache ray that hit the emitter surface s counts its emission: large emitters only,
// the ones the light tables leave out (src/lighting/gpu_light_tables.h).
bool cacheRayCountsEmission(Surface s) {
  return FloatArray(lightTables.materialLightAreaPdf).v[s.material] == 0.0;
}

// Light sample l's reflection at surface s towards wo when its shadow ray is unoccluded. One
// traceVisibility call for both kinds of light: every call is inlined whole (the BVH traversal
// with its alpha test), and a CPU driver compiles each copy (docs/startup.md).
vec3 cacheLightContribution(Surface s, vec3 wo, LightSample l, vec3 origin, bool alphaTest) {
  if (!l.valid) return vec3(0.0);
  float cosine = dot(s.shadingNormal, l.direction);
  if (cosine <= 0.0 || dot(s.geometricNormal, l.direction) <= 0.0) return vec3(0.0);
  // The lobe regularized as at ReSTIR GI's hits (lighting/regularize.glsl): a cache ray is a
  // diffuse ray, and the sun's peak on a near-mirror it hits is a caustic it samples rarely.
  BrdfMaterial lobe = regularizedMaterial(s.brdf, DIFFUSE_RAY_HIT_MIN_ALPHA);
  vec3 contribution = brdfEvaluate(lobe, s.shadingNormal, wo, l.direction) * cosine * l.radianceOverPdf;
  if (!any(greaterThan(contribution, vec3(0.0)))) return vec3(0.0);
  vec3 shadowDirection = l.distant ? l.direction : l.shadowTarget - origin;
  float shadowEnd = l.distant ? CACHE_RAY_FAR : 1.0;
  bool visible = traceVisibility(origin, shadowDirection, 0.0, shadowEnd, alphaTest);
  return visible ? contribution : vec3(0.0);
}

// The frame's sun as a light sample: a direction in its cone from u.
LightSample cacheSunSample(FrameConstants f, vec2 u) {
  LightSample sun = invalidLightSample();
  sun.distant = true;
  sun.direction = f.sunCosHalfAngle < 1.0 ? sampleCone(f.towardSun, f.sunCosHalfAngle, u)
                                          : f.towardSun;
  sun.radianceOverPdf = f.sunIrradiance;
  sun.valid = true;
  return sun;
}

// Reflected direct light at surface s towards wo, with shadow rays; u: uniform numbers. The
// lights in order: the sun (when it shines), one local light, each KHR directional light; one
// loop with a single cacheLightContribution call, so that its shadow ray is compiled once.
vec3 cacheDirectLight(FrameConstants f, Surface s, vec3 wo, vec4 u, bool alphaTest) {
  vec3 origin = offsetRayOrigin(s.position, s.geometricNormal);
  vec3 sum = vec3(0.0);
  vec4 w = uniformFromHash(pcg4d(floatBitsToUint(u) ^ uvec4(0x2545F491u)));
  const uint SUN = 0u, LOCAL = 1u, FIRST_DISTANT = 2u;
  uint first = any(greaterThan(f.sunIrradiance, vec3(0.0))) ? SUN : LOCAL;
  for (uint light = first; light < FIRST_DISTANT + lightTables.distantLightCount; ++light) {
    LightSample l;
    if (light == SUN) {
      l = cacheSunSample(f, u.xy);
    } else if (light == LOCAL) {
      l = sampleLocalLight(s.position, vec4(u.zw, w.xy));
    } else {
      uint k = light - FIRST_DISTANT;
      vec2 r = k == 0u ? w.zw : uniformFromHash(pcg4d(floatBitsToUint(w) ^ uvec4(k))).xy;
      l = sampleDistantLight(k, r);
    }
    sum += cacheLightContribution(s, wo, l, origin, alphaTest);
  }
  return sum;
}

// Irradiance / pi at (position, normal) straight from the small emitters: one local-light
// sample, counted when it is an emissive triangle (pdf > 0; the KHR punctual lights are
// composite's), zero when occluded: what a consumer without NEE of its own adds to the cache's
// irradiance (gi-cache-lookup).
vec3 emitterIrradianceOverPi(vec3 position, vec3 normal, vec4 u, bool alphaTest) {
  LightSample l = sampleLocalLight(position, u);
  float cosine = dot(normal, l.direction);
  if (!l.valid || !(l.pdf > 0.0) || cosine <= 0.0) return vec3(0.0);
  vec3 origin = offsetRayOrigin(position, normal);
  if (!traceVisibility(origin, l.shadowTarget - origin, 0.0, 1.0, alphaTest)) return vec3(0.0);
  return l.radianceOverPdf * (cosine / PI);
}

// Radiance along the ray (origin, dir) from the cache's point of view. touch/allocate as in
// clipmapQuery (cache_lookup.glsl). hitDistance: -1 on a miss.
vec3 cacheRayRadiance(FrameConstants f, ClipmapCacheView cache, vec3 origin, vec3 dir,
                      bool alphaTest, uint touch, bool allocate, uvec4 seed,
                      out float hitDistance) {
  TraceHit hit = traceClosest(origin, dir, 0.0, CACHE_RAY_FAR, alphaTest);
  if (!traceHitFound(hit)) {
    hitDistance = -1.0;
    return skyRadianceToward(f, dir);
  }
  hitDistance = hit.t;
  Surface s = loadSurfaceAtCoarseMip(hit, dir, (f.flags & FRAME_FLAG_LAMBERT) != 0u, cache.constants.v.materialTextureSide);
  vec4 u = uniformFromHash(pcg4d(seed));
  vec2 jitter = uniformFromHash(pcg4d(seed.yzwx ^ uvec4(0x68E31DA4u))).xy - 0.5;
  vec3 albedo = indirectHitReflectance(f.specularAlbedo, s.brdf, s.shadingNormal, -dir);
  vec3 emission = cacheRayCountsEmission(s) ? s.emission : vec3(0.0);
  vec3 radiance = emission + cacheDirectLight(f, s, -dir, u, alphaTest) +
                  albedo * clipmapQuery(cache, s.position, s.shadingNormal, jitter, touch, allocate);
  return clipmapFinite(radiance) ? radiance : vec3(0.0);
}

#endif
