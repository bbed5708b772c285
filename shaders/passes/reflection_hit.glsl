// What a reflection ray sees, shared by reflections-trace and reflections-trace-mirrors: the
// radiance arriving at x1 along the ray (sky, emission, direct light and the clipmap cache at
// the hit x2). The including shader declares `pc` (ReflectionPassConstants) and sets
// `lightTables` first.
#ifndef BOUNCE_PASSES_REFLECTION_HIT_GLSL
#define BOUNCE_PASSES_REFLECTION_HIT_GLSL
#include "gi/evolve/cache/cache_lookup.glsl"
#include "gi/evolve/restir/restir_gi_common.glsl"
#include "lighting/frame_sun.glsl"
#include "lighting/light_tables.glsl"
#include "lighting/path_vertex.glsl"
#include "lighting/regularize.glsl"
#include "lighting/specular_albedo.glsl"
#include "passes/hybrid_frame.glsl"
#include "shared/specular_io.h"

const uint RANDOM_REFLECTION_CACHE = 0x52460003u;

// Direct light at the hit x2 towards x1: the sun, every KHR directional light and one local
// light, each one sample with a shadow ray at full weight (the path ends here: no BRDF ray
// competes; light the samples miss, such as the large emitters the tables leave to rays, comes
// from the cache). x2's lobe is regularized to at least minAlpha (lighting/regularize.glsl).
vec3 hitDirectLight(FrameConstants f, Surface s, vec3 wo, uvec4 key, float minAlpha) {
  s.brdf = regularizedMaterial(s.brdf, minAlpha);
  // One loop with a single lightContribution call: each call inlines a BVH traversal, and a CPU
  // driver compiles every copy (docs/startup.md).
  vec3 sum = vec3(0.0);
  uint distantCount = lightTables.distantLightCount;
  for (uint k = 0u; k < distantCount + 2u; ++k) {
    LightSample l;
    if (k < distantCount)
      l = sampleDistantLight(k, pathRandom(key, 1u, PURPOSE_DISTANT_LIGHT + k).xy);
    else if (k == distantCount)
      l = sampleLocalLight(s.position, pathRandom(key, 1u, PURPOSE_LOCAL_LIGHT));
    else
      l = sampleFrameSun(f, pathRandom(key, 1u, PURPOSE_DISTANT_LIGHT + MAX_DISTANT_LIGHTS).xy);
    sum += lightContribution(s, wo, l, false);
  }
  return sum;
}

// Light from the 3rd vertex on, reflected at x2 (seed 000, "Clipmap for 3rd+ vertices"): the
// cache's irradiance / pi, reflected by both lobes of x2 with the split-sum albedo, as composite
// reflects the diffuse light on rough surfaces. The diffuse lobe alone (what the GI's cache
// bounce uses) would make every metal seen in a reflection black but for its direct highlights:
// on `spheres` the metal rows came out 6 % and 10 % darker than the reference that way.
vec3 hitCacheLight(Surface s, vec3 wo, uint seed) {
  if (pc.cache == 0ul) return vec3(0.0);
  SpecularAlbedo albedo = specularAlbedo(pc.specularAlbedo, max(dot(s.shadingNormal, wo), 0.0), s.brdf.alpha);
  vec3 reflectance = diffuseReflectance(albedo, s.brdf) + specularReflectance(albedo, s.brdf);
  return reflectance * cacheLookupIrradiance(clipmapCacheView(pc.cache), s.position, s.geometricNormal, seed);
}

// Radiance arriving at x1 along `dir`; `hitDistance` is set to the hit's distance (or the miss
// distance), `hitSample` to the hit x2 as a reservoir sample (position, kind, normal facing x1).
// `alpha`: the reflecting lobe's, which sets the hit's regularization.
vec3 incomingRadiance(FrameConstants f, vec3 origin, vec3 dir, float alpha, uvec4 key,
                      out float hitDistance, inout Reservoir hitSample) {
  TraceHit hit = traceClosest(origin, dir, 0.0, NO_HIT, true);
  if (!traceHitFound(hit)) {
    hitDistance = REFLECTION_MISS_DISTANCE;
    // A sample at infinity: its direction, stored as a far point (restir_gi_io.h).
    hitSample.kind = RESTIR_GI_KIND_SKY;
    hitSample.samplePosition = hitSample.origin + dir * RESTIR_GI_SKY_DISTANCE;
    return skyRadianceToward(f, dir);
  }
  bool lambert = (f.flags & FRAME_FLAG_LAMBERT) != 0u;
  Surface s = loadSurfaceAtCoarseMip(hit, dir, lambert, pc.materialTextureSide);
  hitDistance = distance(origin, s.position);
  hitSample.kind = RESTIR_GI_KIND_SURFACE;
  hitSample.samplePosition = s.position;
  hitSample.sampleNormal = s.geometricNormal;  // on the side of the incoming ray: facing x1
  // ReSTIR DI lights x1 from the emitters the light tables sample, specular lobe included
  // (FRAME_FLAG_DI_LIGHTS): their emission seen in a reflection would count twice.
  bool diLit = (f.flags & FRAME_FLAG_DI_LIGHTS) != 0u && lightTablesSampleMaterial(s.material);
  return (diLit ? vec3(0.0) : s.emission) + hitDirectLight(f, s, -dir, key, pc.hitRegularization * alpha) + hitCacheLight(s, -dir, key.x ^ RANDOM_REFLECTION_CACHE);
}

#endif
