// lux-probe-integral (test support and a debug view; runs only when LuxSettings::integralSamples
// > 0): a plain Monte Carlo estimate of what Lux's candidates estimate, the integral over x1's
// hemisphere of the radiance the ray finds (emission, one NEE sample with its shadow ray, the
// probe field's irradiance x albedo at the hit: exactly gi-trace-diffuse-rays' and
// gi-trace-diffuse-nee-rays' integrand with the cache 2nd vertex) times cos / pi, from
// integralSamples directions drawn uniformly over the hemisphere (integralUniform: the
// baseline of seed 002's variance gate, at the candidates' count) or from the cosine
// distribution (the brute-force probe-field integral the bias test averages over frames:
// gi10_lux_denoisers.md §4.2 T5). Few directions per dispatch: lavapipe caps an invocation's
// loop iterations (traversal included) at 65,535, so tests average over frames.
#version 460
#include "gi/evolve/restir/restir_gi_second_vertex.glsl"
#include "gi/evolve/cache/cache_radiance.glsl"
#include "lighting/regularize.glsl"
#include "shared/lux_io.h"

layout(local_size_x = RESTIR_GI_GROUP_SIZE, local_size_y = RESTIR_GI_GROUP_SIZE) in;
layout(push_constant, scalar) uniform Push { LuxPassConstants pc; };

layout(set = 1, binding = LUX_INTEGRAL_BINDING_NORMALS, rgba16f) uniform readonly image2D normals;
layout(set = 1, binding = LUX_INTEGRAL_BINDING_DEPTH, r32f) uniform readonly image2D depths;
layout(set = 1, binding = LUX_INTEGRAL_BINDING_FLAGS, r32ui) uniform readonly uimage2D flags;
layout(set = 1, binding = LUX_INTEGRAL_BINDING_OUTPUT, rgba32f) uniform writeonly image2D outputImage;

const uint RANDOM_LUX_INTEGRAL = 0x4C550010u;

// The radiance arriving at x1 from direction `dir` (see the top); `key` seeds the NEE sample
// and the cache lookup's jitter.
vec3 incomingRadiance(FrameConstants f, RestirGiConstants gi, PrimaryVertex x1, vec3 dir, uvec4 key) {
  TraceHit hit = traceClosest(offsetRayOrigin(x1.position, x1.geometricNormal), dir, 0.0, NO_HIT, true);
  if (!traceHitFound(hit)) return skyRadianceToward(f, dir);
  Surface s = loadSurfaceAtCoarseMip(hit, dir, (f.flags & FRAME_FLAG_LAMBERT) != 0u, gi.materialTextureSide);
  vec3 wo = -dir;
  bool diLit = (f.flags & FRAME_FLAG_DI_LIGHTS) != 0u && lightTablesSampleMaterial(s.material);
  vec3 radiance = diLit ? vec3(0.0) : s.emission;
  if (gi.maxPathBounces <= 1u) return radiance;
  float localPick;
  LightSample l = sampleSecondVertexLight(f, s.position, key, localPick);
  if (l.valid && dot(l.direction, s.geometricNormal) > 0.0) {
    BrdfMaterial lobe = regularizedMaterial(s.brdf, DIFFUSE_RAY_HIT_MIN_ALPHA);
    vec3 origin = offsetRayOrigin(s.position, s.geometricNormal);
    bool visible = l.distant ? traceVisibility(origin, l.direction, 0.0, 3.0e38, true)
                             : traceVisibility(origin, l.shadowTarget - origin, 0.0, 1.0, true);
    if (visible)
      radiance += brdfEvaluate(lobe, s.shadingNormal, wo, l.direction) *
                  max(dot(s.shadingNormal, l.direction), 0.0) * l.radianceOverPdf;
  }
  if (gi.maxPathBounces > 2u) {
    vec3 reflectance = indirectHitReflectance(f.specularAlbedo, s.brdf, s.shadingNormal, wo);
    radiance += reflectance * cacheLookupIrradiance(clipmapCacheView(gi.cache), s.position,
                                                    s.geometricNormal, key.x ^ 0x47490005u);
  }
  return radiance;
}

vec3 uniformHemisphereDirection(vec3 n, vec2 u) {
  float sinTheta = sqrt(max(0.0, 1.0 - u.x * u.x));
  vec3 t, b;
  orthonormalBasis(n, t, b);
  return normalize(sinTheta * cos(2.0 * PI * u.y) * t + sinTheta * sin(2.0 * PI * u.y) * b + u.x * n);
}

void main() {
  FrameConstants f = FrameBlock(pc.frame).v;
  RestirGiConstants gi = RestirGiBlock(pc.gi).v;
  ivec2 g = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(g), gi.giResolution))) return;
  lightTables = LightTablesBlock(gi.lights).v;
  ivec2 pixel = giRepresentativePixel(f, gi, g);
  vec3 sum = vec3(0.0);
  if ((imageLoad(flags, pixel).x & GBUFFER_FLAG_SURFACE) != 0u) {
    PrimaryVertex x1 = makePrimaryVertex(f, pixel, imageLoad(normals, pixel), imageLoad(depths, pixel).x);
    for (uint i = 0u; i < pc.integralSamples; ++i) {
      uvec4 key = pcg4d(uvec4(g, f.frameIndex * pc.integralSamples + i, RANDOM_LUX_INTEGRAL));
      vec2 u = uniformFromHash(key).zw;
      vec3 dir = pc.integralUniform != 0u ? uniformHemisphereDirection(x1.shadingNormal, u)
                                          : sampleCosineHemisphere(x1.shadingNormal, u);
      float cosine = dot(dir, x1.shadingNormal);
      if (dot(dir, x1.geometricNormal) <= 0.0 || !(cosine > 0.0)) continue;
      vec3 L = incomingRadiance(f, gi, x1, dir, key);
      // Estimate of irradiance / pi: L cos / pi / pdf; pdf 1 / (2 pi) or cos / pi.
      vec3 e = pc.integralUniform != 0u ? L * (2.0 * cosine) : L;
      if (clipmapFinite(e)) sum += e;
    }
    sum /= float(max(pc.integralSamples, 1u));
  }
  imageStore(outputImage, g, vec4(min(sum, vec3(1.0e30)), 1.0));
}
