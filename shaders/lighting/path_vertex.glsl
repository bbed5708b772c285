// One vertex of a path traced with next-event estimation, shared by the reference path tracer
// (reference/integrator.glsl) and ReSTIR GI's continued path (restir_gi_second_vertex.glsl in
// gi/evolve), so that the two sample light alike: the path's random numbers, and the light
// reflected at a vertex from one sample of every distant light and one local light, with
// multiple importance sampling against BRDF sampling (Veach 1997, ch. 9; power heuristic,
// beta = 2).
//
// Random numbers: each (pixel, sample) has a 128-bit key hashed from (pixel, sample, seed); each
// use hashes the key with (bounce, purpose), so streams never overlap and a sample's numbers do
// not depend on how samples are batched. The one exception is the point in the pixel, which is
// stratified (pixelJitter): edges of bright emitters otherwise dominate the error for hundreds
// of samples.
#ifndef BOUNCE_LIGHTING_PATH_VERTEX_GLSL
#define BOUNCE_LIGHTING_PATH_VERTEX_GLSL
#include "common/random.glsl"
#include "common/ray_offset.glsl"
#include "lighting/lights.glsl"
#include "lighting/surface.glsl"

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

// Reflected radiance from one light sample, zero when occluded; MIS-weighted against BRDF
// sampling where the light can also be hit by BRDF rays (pdf > 0) and `misWithBrdf` says the
// path goes on by BRDF sampling (a vertex that ends the path, as reflections-trace's hit,
// gives its light samples full weight).
vec3 lightContribution(Surface s, vec3 wo, LightSample l, bool misWithBrdf) {
  if (!l.valid || dot(l.direction, s.geometricNormal) <= 0.0) return vec3(0.0);
  vec3 f = brdfEvaluate(s.brdf, s.shadingNormal, wo, l.direction);
  vec3 contribution = f * dot(s.shadingNormal, l.direction) * l.radianceOverPdf;
  if (misWithBrdf && l.pdf > 0.0)
    contribution *= powerHeuristic(l.pdf, brdfPdf(s.brdf, s.shadingNormal, wo, l.direction));
  if (!any(greaterThan(contribution, vec3(0.0)))) return vec3(0.0);
  // One traceVisibility call for both kinds of light: every call is inlined whole (the BVH
  // traversal), and a CPU driver compiles each copy (docs/startup.md).
  vec3 origin = offsetRayOrigin(s.position, s.geometricNormal);
  vec3 shadowDirection = l.distant ? l.direction : l.shadowTarget - origin;
  float shadowEnd = l.distant ? NO_HIT : 1.0;
  bool visible = traceVisibility(origin, shadowDirection, 0.0, shadowEnd, true);
  return visible ? contribution : vec3(0.0);
}

vec3 lightContribution(Surface s, vec3 wo, LightSample l) {
  return lightContribution(s, wo, l, true);
}

// Next-event estimation at a vertex: every distant light once, one local light picked by power,
// then `extra` when it is valid (ReSTIR GI's frame sun). One loop with a single
// lightContribution call, so that its shadow ray is compiled once.
vec3 directLightingAnd(Surface s, vec3 wo, uvec4 key, uint bounce, LightSample extra) {
  vec3 sum = vec3(0.0);
  uint distantCount = lightTables.distantLightCount;
  uint count = distantCount + (extra.valid ? 2u : 1u);
  for (uint k = 0u; k < count; ++k) {
    LightSample l;
    if (k < distantCount)
      l = sampleDistantLight(k, pathRandom(key, bounce, PURPOSE_DISTANT_LIGHT + k).xy);
    else if (k == distantCount)
      l = sampleLocalLight(s.position, pathRandom(key, bounce, PURPOSE_LOCAL_LIGHT));
    else
      l = extra;
    sum += lightContribution(s, wo, l);
  }
  return sum;
}

vec3 directLighting(Surface s, vec3 wo, uvec4 key, uint bounce) {
  return directLightingAnd(s, wo, key, bounce, invalidLightSample());
}

#endif
