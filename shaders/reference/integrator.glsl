// The path integrator of the reference tracer: unidirectional path tracing with next-event
// estimation at every vertex and multiple importance sampling (Veach 1997, "Robust Monte Carlo
// Methods for Light Transport Simulation", ch. 9; power heuristic, beta = 2) between BRDF
// sampling and light sampling for emissive triangles. The sun, KHR directional/point/spot
// lights are delta or tiny and reached by light sampling only; the sky is reached by BRDF rays
// only (it is smooth, so BRDF sampling alone converges well). Russian roulette (Arvo & Kirk
// 1990) ends paths after a few bounces in proportion to their throughput.
//
// Random numbers: each (pixel, sample) has a 128-bit key hashed from (pixel, sample, seed); each
// use hashes the key with (bounce, purpose), so streams never overlap and a sample's numbers do
// not depend on how samples are batched. The one exception is the point in the pixel, which is
// stratified (pixelJitter): edges of bright emitters otherwise dominate the error for hundreds
// of samples.
#ifndef BOUNCE_REFERENCE_INTEGRATOR_GLSL
#define BOUNCE_REFERENCE_INTEGRATOR_GLSL
#include "common/random.glsl"
#include "common/ray_offset.glsl"
#include "common/sky.glsl"
#include "reference/lights.glsl"
#include "reference/settings.glsl"
#include "reference/surface.glsl"

const uint PURPOSE_BRDF = 1u;
const uint PURPOSE_LOCAL_LIGHT = 2u;
const uint PURPOSE_ROULETTE = 3u;
const uint PURPOSE_DISTANT_LIGHT = 4u;  // + light index, up to MAX_DISTANT_LIGHTS

const uint ROULETTE_FIRST_BOUNCE = 3u;
const float NO_HIT = 3.0e38;

vec4 pathRandom(uvec4 key, uint bounce, uint purpose) {
  return uniformFromHash(pcg4d(key ^ uvec4(0u, 0u, 0u, (bounce << 8u) | purpose)));
}

// The sample's point in the pixel: the R2 sequence (Roberts 2018, "The Unreasonable
// Effectiveness of Quasirandom Sequences": n * (1/g, 1/g^2) mod 1 with g the plastic number,
// well stratified in 2D for every prefix) rotated by a per-pixel random offset (Cranley &
// Patterson 1976), which keeps every sample uniformly distributed in the pixel and the pixels
// independent. In 0.32 fixed point, so that the sequence stays exact for any sample count.
vec2 pixelJitter(uvec4 pixelKey, uint sampleIndex) {
  const uvec2 r2Step = uvec2(3242174889u, 2447445413u);  // (1/g, 1/g^2) * 2^32
  uvec2 rotation = pcg4d(pixelKey).xy;
  return vec2((sampleIndex * r2Step + rotation) >> 8u) * (1.0 / 16777216.0);
}

vec3 skyRadiance(vec3 direction) {
  if (settings.skyModel == REFERENCE_SKY_DAYLIGHT)
    return daylightSky(direction, settings.skyTowardSun, settings.skyTurbidity) * settings.skyScale;
  return settings.skyRadiance;
}

// Reflected radiance from one light sample, MIS-weighted against BRDF sampling where the light
// can also be hit by BRDF rays (pdf > 0), and zero when occluded.
vec3 lightContribution(Surface s, vec3 wo, LightSample l) {
  if (!l.valid || dot(l.direction, s.geometricNormal) <= 0.0) return vec3(0.0);
  vec3 f = brdfEvaluate(s.brdf, s.shadingNormal, wo, l.direction);
  vec3 contribution = f * dot(s.shadingNormal, l.direction) * l.radianceOverPdf;
  if (l.pdf > 0.0) contribution *= powerHeuristic(l.pdf, brdfPdf(s.brdf, s.shadingNormal, wo, l.direction));
  if (!any(greaterThan(contribution, vec3(0.0)))) return vec3(0.0);
  vec3 origin = offsetRayOrigin(s.position, s.geometricNormal);
  bool visible = l.distant ? traceVisibility(origin, l.direction, 0.0, NO_HIT, true)
                           : traceVisibility(origin, l.shadowTarget - origin, 0.0, 1.0, true);
  return visible ? contribution : vec3(0.0);
}

vec3 directLighting(Surface s, vec3 wo, uvec4 key, uint bounce) {
  vec3 sum = vec3(0.0);
  for (uint k = 0u; k < lightTables.distantLightCount; ++k)
    sum += lightContribution(s, wo, sampleDistantLight(k, pathRandom(key, bounce, PURPOSE_DISTANT_LIGHT + k).xy));
  vec4 u = pathRandom(key, bounce, PURPOSE_LOCAL_LIGHT);
  sum += lightContribution(s, wo, sampleLocalLight(s.position, u));
  return sum;
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
