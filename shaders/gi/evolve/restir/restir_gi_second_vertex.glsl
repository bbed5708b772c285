// The radiance leaving the 2nd vertex x2 towards x1, by RestirGiSettings::secondVertex:
//   emission (with --di off always: x1 then has no light sampling for emissive triangles, so the
//   GI ray is the only way to reach them, with weight 1; with ReSTIR DI none from the emitters
//   it samples, which DI lights at x1; gi_trace_diffuse_rays.comp)
//   + one next-event estimation sample at x2, whose shadow ray gi-trace-diffuse-nee-rays traces
//   + PATH: a path traced on from x2 exactly like the reference tracer's (BRDF sampling, NEE at
//     every vertex with MIS against BRDF hits on emitters, Russian roulette; the vertices are
//     lighting/path_vertex.glsl, as the reference's), so that the chain is unbiased;
//   + CACHE: the clipmap irradiance cache's irradiance / pi x albedo at x2 (added by
//     gi_trace_diffuse_rays.comp, not here).
// The lights come from the scene's light tables (lighting/lights.glsl, loaded into
// `lightTables`), except the sun and the sky, which come from the frame constants because they
// move.
#ifndef BOUNCE_GI_EVOLVE_RESTIR_GI_SECOND_VERTEX_GLSL
#define BOUNCE_GI_EVOLVE_RESTIR_GI_SECOND_VERTEX_GLSL
#include "gi/evolve/restir/restir_gi_common.glsl"
#include "lighting/frame_sun.glsl"
#include "lighting/path_vertex.glsl"

// One NEE sample at x2: a light category (the sun, each KHR directional light, the local
// lights) picked uniformly, then a light sample within it. `localPick` returns the probability
// of the local category, which MIS at the next BRDF hit of an emitter needs.
LightSample sampleSecondVertexLight(FrameConstants f, vec3 x, uvec4 key, out float localPick) {
  uint sun = any(greaterThan(f.sunIrradiance, vec3(0.0))) ? 1u : 0u;
  uint local = lightTables.localLightCount > 0u ? 1u : 0u;
  uint count = sun + lightTables.distantLightCount + local;
  localPick = count > 0u ? float(local) / float(count) : 0.0;
  if (count == 0u) return invalidLightSample();
  vec4 u = pathRandom(key, 1u, PURPOSE_LOCAL_LIGHT);
  vec4 v = pathRandom(key, 1u, PURPOSE_DISTANT_LIGHT);
  uint k = min(uint(v.z * float(count)), count - 1u);
  LightSample l;
  if (k < sun) l = sampleFrameSun(f, v.xy);
  else if (k < sun + lightTables.distantLightCount) l = sampleDistantLight(k - sun, v.xy);
  else l = sampleLocalLight(x, u);
  l.radianceOverPdf *= float(count);
  l.pdf /= float(count);
  return l;
}

// NEE at a later vertex: the reference's (all KHR distant lights + one local light) plus the
// frame's sun, shadow rays traced here.
vec3 laterVertexLighting(FrameConstants f, Surface s, vec3 wo, uvec4 key, uint bounce) {
  LightSample sun = sampleFrameSun(f, pathRandom(key, bounce, PURPOSE_DISTANT_LIGHT + MAX_DISTANT_LIGHTS).xy);
  return directLightingAnd(s, wo, key, bounce, sun);
}

// The path from x2 (scattering event 1; x1 is event 0) on, without x2's emission and NEE.
// Mirrors tracePath of the reference tracer (reference/integrator.glsl) from its second vertex.
vec3 continuedPath(FrameConstants f, Surface s, vec3 wo, uvec4 key, float localPickAtX2,
                   uint maxBounces, bool lambert, uint maxTextureSide) {
  vec3 radiance = vec3(0.0);
  vec3 throughput = vec3(1.0);
  float localPick = localPickAtX2;
  for (uint bounce = 1u; bounce < maxBounces; ++bounce) {
    BrdfSample b = brdfSample(s.brdf, s.shadingNormal, wo, pathRandom(key, bounce, PURPOSE_BRDF).xyz);
    if (!b.valid || dot(b.wi, s.geometricNormal) <= 0.0) break;
    throughput *= b.weight;
    if (bounce + 1u >= ROULETTE_FIRST_BOUNCE) {
      float survive = min(max(throughput.r, max(throughput.g, throughput.b)), 0.95);
      if (pathRandom(key, bounce, PURPOSE_ROULETTE).x >= survive) break;
      throughput /= survive;
    }
    vec3 origin = offsetRayOrigin(s.position, s.geometricNormal);
    TraceHit hit = traceClosest(origin, b.wi, 0.0, NO_HIT, true);
    if (!traceHitFound(hit)) {
      radiance += throughput * skyRadianceToward(f, b.wi);
      break;
    }
    Surface next = loadSurfaceAtCoarseMip(hit, b.wi, lambert, maxTextureSide);
    if (any(greaterThan(next.emission, vec3(0.0)))) {
      float lightPdf = localPick * emissiveHitLightPdf(next.material, s.position, next.position,
                                                       next.geometricNormal);
      radiance += throughput * next.emission * powerHeuristic(b.pdf, lightPdf);
    }
    if (bounce + 1u >= maxBounces) break;
    s = next;
    wo = -b.wi;
    localPick = 1.0;
    radiance += throughput * laterVertexLighting(f, s, wo, key, bounce + 1u);
  }
  return radiance;
}

#endif
