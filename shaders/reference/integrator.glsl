// The path integrator of the reference tracer: unidirectional path tracing with next-event
// estimation at every vertex and multiple importance sampling (Veach 1997, "Robust Monte Carlo
// Methods for Light Transport Simulation", ch. 9; power heuristic, beta = 2) between BRDF
// sampling and light sampling for emissive triangles. The sun, KHR directional/point/spot
// lights are delta or tiny and reached by light sampling only; the sky is reached by BRDF rays
// only (it is smooth, so BRDF sampling alone converges well). Russian roulette (Arvo & Kirk
// 1990) ends paths after a few bounces in proportion to their throughput. What the path does at
// each vertex (its random numbers, light sampling with MIS) is lighting/path_vertex.glsl, which
// ReSTIR GI's continued path shares.
#ifndef BOUNCE_REFERENCE_INTEGRATOR_GLSL
#define BOUNCE_REFERENCE_INTEGRATOR_GLSL
#include "common/sky.glsl"
#include "lighting/path_vertex.glsl"
#include "reference/settings.glsl"

vec3 skyRadiance(vec3 direction) {
  if (settings.skyModel == REFERENCE_SKY_DAYLIGHT)
    return daylightSky(direction, settings.skyTowardSun, settings.skyTurbidity) * settings.skyScale;
  return settings.skyRadiance;
}

// Radiance arriving at the camera through pixel `pixel` (box filter: a uniform point in the
// pixel) for sample `sampleIndex`.
vec3 tracePath(uvec2 pixel, uint sampleIndex) {
  uvec4 key = pcg4d(uvec4(pixel, sampleIndex, settings.seed));
  // 0xFFFFFFFF: no sample index has it (at most 2^24 samples), so this key is never a sample's.
  vec2 jitter = (settings.flags & REFERENCE_FLAG_PIXEL_CENTRE) != 0u
                    ? vec2(0.5)
                    : pixelJitter(uvec4(pixel, 0xFFFFFFFFu, settings.seed), sampleIndex);
  vec3 origin = settings.camera.position;
  vec3 direction = cameraRayDirection(settings.camera, vec2(pixel) + jitter, vec2(settings.resolution));
  bool lambertOnly = (settings.flags & REFERENCE_FLAG_LAMBERT) != 0u;

  vec3 radiance = vec3(0.0);
  vec3 throughput = vec3(1.0);
  float brdfPdfOfRay = 0.0;  // 0: the camera ray, which no light sampling competes with
  vec3 previousPosition = origin;
  for (uint bounce = 0u;; ++bounce) {
    TraceHit hit = traceClosest(origin, direction, 0.0, NO_HIT, true);
    if (!traceHitFound(hit)) {
      radiance += throughput * skyRadiance(direction);
      break;
    }
    Surface s = loadSurface(hit, direction, lambertOnly);
    if (any(greaterThan(s.emission, vec3(0.0)))) {
      float weight = 1.0;
      if (brdfPdfOfRay > 0.0) {
        float lightPdf = emissiveHitLightPdf(s.material, previousPosition, s.position, s.geometricNormal);
        weight = powerHeuristic(brdfPdfOfRay, lightPdf);
      }
      radiance += throughput * s.emission * weight;
    }
    if (bounce >= settings.maxBounces) break;

    vec3 wo = -direction;
    radiance += throughput * directLighting(s, wo, key, bounce);

    BrdfSample b = brdfSample(s.brdf, s.shadingNormal, wo, pathRandom(key, bounce, PURPOSE_BRDF).xyz);
    // A direction below the geometric surface would leak through it (shading normals differ).
    if (!b.valid || dot(b.wi, s.geometricNormal) <= 0.0) break;
    throughput *= b.weight;
    brdfPdfOfRay = b.pdf;
    previousPosition = s.position;
    origin = offsetRayOrigin(s.position, s.geometricNormal);
    direction = b.wi;

    if (bounce + 1u >= ROULETTE_FIRST_BOUNCE) {
      float survive = min(max(throughput.r, max(throughput.g, throughput.b)), 0.95);
      if (pathRandom(key, bounce, PURPOSE_ROULETTE).x >= survive) break;
      throughput /= survive;
    }
  }
  return radiance;
}

#endif
