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

// Light from the 3rd vertex on, leaving x2 towards x1 (seed 000, "Clipmap for 3rd+ vertices"):
// both lobes of x2 reflect through their split-sum reflectances, the diffuse one the cache's
// irradiance / pi, the specular one `specular` (the same irradiance, as composite reflects the
// diffuse light on rough surfaces, or for a mirror what its mirror direction brings). The
// diffuse lobe alone (what the GI's cache bounce uses) would make every metal seen in a
// reflection black but for its direct highlights: on `spheres` the metal rows came out 6 % and
// 10 % darker than the reference that way.
vec3 hitReflectedLight(Surface s, vec3 wo, vec3 irradianceOverPi, vec3 specular, out vec3 specularWeight) {
  SpecularAlbedo albedo = specularAlbedo(pc.specularAlbedo, max(dot(s.shadingNormal, wo), 0.0), s.brdf.alpha);
  specularWeight = specularReflectance(albedo, s.brdf);
  return diffuseReflectance(albedo, s.brdf) * irradianceOverPi + specularWeight * specular;
}

// Radiance arriving at x1 along `dir`; `hitDistance` is set to the hit's distance (or the miss
// distance), `hitSample` to the hit x2 as a reservoir sample (position, kind, normal facing x1).
// `alpha`: the reflecting lobe's, which sets the hit's regularization. Where x2 is itself a
// mirror (roughness below mirrorRoughness), its specular lobe is followed by one more ray
// along its mirror direction instead of being lit by the cache's irradiance, a cosine-weighted
// average that showed a mirror ball's mirror image of its neighbours far too bright
// (docs/reflections.md, "Mirrors at render resolution"); the cache still lights x2's diffuse
// lobe and x3.
vec3 incomingRadiance(FrameConstants f, vec3 origin, vec3 dir, float alpha, uvec4 key,
                      out float hitDistance, inout Reservoir hitSample) {
  bool lambert = (f.flags & FRAME_FLAG_LAMBERT) != 0u;
  float mirrorAlpha = pc.mirrorRoughness * pc.mirrorRoughness;
  vec3 sum = vec3(0.0), throughput = vec3(1.0);
  hitDistance = REFLECTION_MISS_DISTANCE;
  // One traceClosest call in a loop: a CPU driver compiles each inlined copy (docs/startup.md).
  for (uint bounce = 0u; bounce < 2u; ++bounce) {
    TraceHit hit = traceClosest(origin, dir, 0.0, NO_HIT, true);
    if (!traceHitFound(hit)) {
      if (bounce == 0u) {
        // A sample at infinity: its direction, stored as a far point (restir_gi_io.h).
        hitSample.kind = RESTIR_GI_KIND_SKY;
        hitSample.samplePosition = hitSample.origin + dir * RESTIR_GI_SKY_DISTANCE;
      }
      sum += throughput * skyRadianceToward(f, dir);
      break;
    }
    Surface s = loadSurfaceAtCoarseMip(hit, dir, lambert, pc.materialTextureSide);
    vec3 emission = s.emission;
    if (bounce == 0u) {
      hitDistance = distance(origin, s.position);
      hitSample.kind = RESTIR_GI_KIND_SURFACE;
      hitSample.samplePosition = s.position;
      hitSample.sampleNormal = s.geometricNormal;  // on the side of the incoming ray: facing x1
      // ReSTIR DI lights x1 from the emitters the light tables sample, specular lobe included
      // (FRAME_FLAG_DI_LIGHTS): their emission seen in a reflection would count twice.
      if ((f.flags & FRAME_FLAG_DI_LIGHTS) != 0u && lightTablesSampleMaterial(s.material)) emission = vec3(0.0);
    }
    sum += throughput * (emission + hitDirectLight(f, s, -dir, key, pc.hitRegularization * alpha));
    vec3 irradianceOverPi = pc.cache != 0ul ? cacheLookupIrradiance(clipmapCacheView(pc.cache), s.position, s.geometricNormal, key.x ^ RANDOM_REFLECTION_CACHE) : vec3(0.0);
    vec3 nextDir = reflect(dir, s.shadingNormal);
    bool followMirror = bounce == 0u && !lambert && s.brdf.alpha < mirrorAlpha && dot(nextDir, s.geometricNormal) > 0.0;
    vec3 specularWeight;
    sum += throughput * hitReflectedLight(s, -dir, irradianceOverPi, followMirror ? vec3(0.0) : irradianceOverPi, specularWeight);
    if (!followMirror) break;
    throughput *= specularWeight;
    origin = offsetRayOrigin(s.position, s.geometricNormal);
    dir = nextDir;
  }
  return sum;
}

#endif
