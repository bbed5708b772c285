// Test support: irradiance / pi at probe points by path tracing through the same tracer, with
// Lambert surfaces and the same direct-light sample as the cache (cache_radiance.glsl), but no
// cache. Emitters are split like the cache's (large ones counted when hit, small ones by NEE
// only, at the probe itself too): what gi-cache-lookup's output (cache + its NEE sample of the
// small emitters) estimates, with other random numbers. Cosine-distributed first directions make the estimator of irradiance / pi the mean of
// the incoming radiance. maxBounces scattering events after the probe: 1 = light reflected once
// (emission and direct light of the surfaces the probe sees), large = multi-bounce.
// One group of CLIPMAP_GROUP_SIZE threads per probe; each thread writes the sum of its samples.
#version 460
#include "gi/evolve/cache/cache_radiance.glsl"

layout(local_size_x = CLIPMAP_GROUP_SIZE) in;
layout(push_constant, scalar) uniform Push { ReferenceIrradianceConstants pc; };

layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer Probes {
  IrradianceProbe v[];
};
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer Sums {
  vec4 v[];
};

// One path from the probe: the sum of emission and direct light at each vertex, weighted by
// the path's throughput.
vec3 tracePath(FrameConstants f, IrradianceProbe p, uvec4 seed) {
  vec3 origin = offsetRayOrigin(p.position, p.normal);
  vec3 normal = p.normal;
  vec3 throughput = vec3(1.0);
  vec3 radiance = emitterIrradianceOverPi(
      p.position, p.normal, uniformFromHash(pcg4d(seed ^ uvec4(0x51ED270Bu))), true);
  if (!clipmapFinite(radiance)) radiance = vec3(0.0);
  bool alive = true;
  for (uint bounce = 0u; alive && bounce < pc.maxBounces; ++bounce) {
    vec4 u = uniformFromHash(pcg4d(seed + uvec4(0u, 0u, 0u, 0x9E3779B9u * (2u * bounce + 1u))));
    vec4 v = uniformFromHash(pcg4d(seed + uvec4(0u, 0u, 0u, 0x9E3779B9u * (2u * bounce + 2u))));
    vec3 dir = sampleCosineHemisphere(normal, u.xy);
    TraceHit hit = traceClosest(origin, dir, 0.0, CACHE_RAY_FAR, true);
    if (!traceHitFound(hit)) {
      vec3 sky = throughput * skyRadianceToward(f, dir);
      if (clipmapFinite(sky)) radiance += sky;
      alive = false;
    } else {
      Surface surface = loadSurface(hit, dir, true);
      // A non-finite term ends the path but keeps what it gathered so far, so the multi-bounce
      // estimate can never fall below the single-bounce one with the same random numbers.
      vec3 emission = cacheRayCountsEmission(surface) ? surface.emission : vec3(0.0);
      vec3 term = throughput * (emission + cacheDirectLight(f, surface, -dir, v, true));
      if (clipmapFinite(term)) {
        radiance += term;
        throughput *= surface.brdf.baseColor;
        normal = surface.shadingNormal;
        origin = offsetRayOrigin(surface.position, surface.geometricNormal);
      } else {
        alive = false;
      }
    }
  }
  return radiance;
}

void main() {
  uint probe = gl_WorkGroupID.x;
  uint thread = gl_LocalInvocationID.x;
  if (probe >= pc.probeCount) return;
  FrameConstants f = FrameBlock(pc.frame).v;
  lightTables = LightTablesBlock(pc.lights).v;
  IrradianceProbe p = Probes(pc.probes).v[probe];
  vec3 sum = vec3(0.0);
  // Counted, not assumed: lavapipe cuts every loop of an invocation short after 65,535 loop
  // iterations in all (gallivm's loop limiter), traversal steps included, so a thread can only
  // afford a few paths per dispatch; the harness checks that every sample ran.
  float taken = 0.0;
  for (uint s = 0u; s < pc.samplesPerThread; ++s) {
    vec3 radiance = tracePath(f, p, uvec4(probe, thread, s, pc.seed));
    if (clipmapFinite(radiance)) sum += radiance;
    taken += 1.0;
  }
  Sums(pc.sums).v[probe * CLIPMAP_GROUP_SIZE + thread] = vec4(sum, taken);
}
