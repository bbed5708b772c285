// Radiance arriving along a cache ray (cache-trace-diffuse-rays, seed 000): at the hit, its
// emission, one next-event-estimation sample of the sun, one of the KHR punctual lights (picked
// uniformly) and every KHR directional light, plus the albedo times the cache's irradiance at
// the hit (a recursive lookup, which makes the bounces infinite); the sky on a miss.
// Emissive triangles count when a ray hits them. The reference estimator of the tests
// (reference_irradiance.comp) uses the same direct-light sample.
#ifndef BOUNCE_GI_EVOLVE_CACHE_RADIANCE_GLSL
#define BOUNCE_GI_EVOLVE_CACHE_RADIANCE_GLSL
#include "gi/evolve/cache_lookup.glsl"
#include "passes/hybrid_frame.glsl"
#include "reference/surface.glsl"
#include "shared/reference_io.h"

layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer CachePunctualLights {
  ReferencePunctualLight v[];
};
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer CacheDirectionalLights {
  ReferenceDistantLight v[];
};

const float CACHE_RAY_FAR = 1e30;

// Reflected direct light at surface s towards wo, with shadow rays; u: four uniform numbers.
vec3 cacheDirectLight(FrameConstants f, Surface s, vec3 wo, vec4 u, bool alphaTest) {
  vec3 n = s.shadingNormal;
  vec3 origin = offsetRayOrigin(s.position, s.geometricNormal);
  vec3 sum = vec3(0.0);
  if (any(greaterThan(f.sunIrradiance, vec3(0.0))) && dot(s.geometricNormal, f.towardSun) > 0.0) {
    vec3 wi = f.sunCosHalfAngle < 1.0 ? sampleCone(f.towardSun, f.sunCosHalfAngle, u.xy)
                                      : f.towardSun;
    float cosine = dot(n, wi);
    if (cosine > 0.0 && traceVisibility(origin, wi, 0.0, CACHE_RAY_FAR, alphaTest))
      sum += brdfEvaluate(s.brdf, n, wo, wi) * cosine * f.sunIrradiance;
  }
  if (f.punctualLightCount > 0u) {
    uint i = min(uint(u.z * float(f.punctualLightCount)), f.punctualLightCount - 1u);
    ReferencePunctualLight p = CachePunctualLights(f.punctualLights).v[i];
    vec3 toLight = p.position - s.position;
    float distanceSq = dot(toLight, toLight);
    if (distanceSq > 0.0) {
      float distance = sqrt(distanceSq);
      vec3 wi = toLight / distance;
      float attenuation = 1.0;
      if (p.type == REFERENCE_LIGHT_SPOT) {
        float a = clamp(dot(p.spotDirection, -wi) * p.angleScale + p.angleOffset, 0.0, 1.0);
        attenuation = a * a;
      }
      float cosine = dot(n, wi);
      if (attenuation > 0.0 && cosine > 0.0 &&
          traceVisibility(origin, wi, 0.0, distance * (1.0 - 1e-4), alphaTest))
        sum += brdfEvaluate(s.brdf, n, wo, wi) * cosine * p.intensity *
               (attenuation * float(f.punctualLightCount) / distanceSq);
    }
  }
  for (uint i = 0u; i < f.directionalLightCount; ++i) {
    ReferenceDistantLight d = CacheDirectionalLights(f.directionalLights).v[i];
    // The table stores the cone-sampling weight E 2 / (1 + cos); undo it for the irradiance.
    vec3 irradiance = d.coneWeight * (0.5 * (1.0 + d.cosHalfAngle));
    float cosine = dot(n, d.towardLight);
    if (cosine > 0.0 && traceVisibility(origin, d.towardLight, 0.0, CACHE_RAY_FAR, alphaTest))
      sum += brdfEvaluate(s.brdf, n, wo, d.towardLight) * cosine * irradiance;
  }
  return sum;
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
  Surface s = loadSurface(hit, dir, (f.flags & FRAME_FLAG_LAMBERT) != 0u);
  vec4 u = uniformFromHash(pcg4d(seed));
  vec2 jitter = uniformFromHash(pcg4d(seed.yzwx ^ uvec4(0x68E31DA4u))).xy - 0.5;
  vec3 albedo = s.brdf.baseColor * (1.0 - s.brdf.metallic);
  vec3 radiance = s.emission + cacheDirectLight(f, s, -dir, u, alphaTest) +
                  albedo * clipmapQuery(cache, s.position, s.shadingNormal, jitter, touch, allocate);
  return clipmapFinite(radiance) ? radiance : vec3(0.0);
}

#endif
