// reflections-trace (DESIGN.md §4 step 6; seed 000: "one ray from the 1st to the 2nd vertex,
// the clipmap cache sampled at the hit"): one reflection ray per pixel of the traced image
// (render resolution / divisor), from the full-res GBuffer pixel nearest its centre.
//   - direction: a GGX visible normal reflected (common/brdf.glsl, the reference's sampler);
//     below mirrorRoughness the one mirror direction (reflections-trace-mirrors traces the
//     render pixels this one ray does not serve); above maxTracedRoughness no ray at all
//     (composite then takes the diffuse light as specular light);
//   - a miss sees the sky; a hit x2 gives its emission, one light sample of the sun and one of
//     each other kind (KHR directional lights, one local light by power) with shadow rays, and
//     the clipmap cache's irradiance / pi (as gi-trace-diffuse-rays reads it) reflected by x2's
//     split-sum albedo for light from the 3rd vertex on, materials at the GI's coarse mip;
//   - the stored signal is demodulated (shared/specular_io.h): L G2/G1(v) / E[G2/G1(v)];
//   - the same sample, for the reuse passes, as a reservoir of one candidate
//     (shared/reflections_reuse_io.h): x2 or the sky direction, the radiance arriving (not
//     demodulated), W = 1 / its visible-normal GGX pdf, M = 1 (M = 0 where nothing is traced or
//     the pixel is a mirror).
#version 460
#include "common/random.glsl"
#include "gi/evolve/restir/restir_gi_common.glsl"
#include "passes/hybrid_frame.glsl"
#include "shared/specular_io.h"

layout(local_size_x = HYBRID_GROUP_SIZE, local_size_y = HYBRID_GROUP_SIZE) in;
layout(push_constant, scalar) uniform Push { ReflectionPassConstants pc; };

layout(set = 1, binding = REFLECTIONS_TRACE_BINDING_NORMALS, rgba16f) uniform readonly image2D normals;
layout(set = 1, binding = REFLECTIONS_TRACE_BINDING_DEPTH, r32f) uniform readonly image2D depths;
layout(set = 1, binding = REFLECTIONS_TRACE_BINDING_EMISSIVE, rgba16f) uniform readonly image2D emissives;
layout(set = 1, binding = REFLECTIONS_TRACE_BINDING_FLAGS, r32ui) uniform readonly uimage2D flags;
layout(set = 1, binding = REFLECTIONS_TRACE_BINDING_TRACED, rgba16f) uniform writeonly image2D tracedOut;
layout(set = 1, binding = REFLECTIONS_TRACE_BINDING_CANDIDATE + GI_RESERVOIR_SAMPLE, rgba32f) uniform writeonly image2D candidateSample;
layout(set = 1, binding = REFLECTIONS_TRACE_BINDING_CANDIDATE + GI_RESERVOIR_RADIANCE, rgba32f) uniform writeonly image2D candidateRadiance;
layout(set = 1, binding = REFLECTIONS_TRACE_BINDING_CANDIDATE + GI_RESERVOIR_ORIGIN, rgba32f) uniform writeonly image2D candidateOrigin;
layout(set = 1, binding = REFLECTIONS_TRACE_BINDING_CANDIDATE + GI_RESERVOIR_NORMALS, rgba16f) uniform writeonly image2D candidateNormals;

const uint RANDOM_REFLECTION_DIRECTION = 0x52460001u;
const uint RANDOM_REFLECTION_HIT = 0x52460002u;

#include "passes/reflection_hit.glsl"

// The full-res pixel a traced pixel stands for (reflections-upsample uses the same rule).
ivec2 fullResPixel(FrameConstants f, ivec2 tracedPixel) {
  ivec2 p = tracedPixel * int(pc.divisor) + int(pc.divisor / 2u);
  return min(p, ivec2(f.resolution) - 1);
}

// The demodulated reflection signal at a full-res pixel (w: hit distance or
// REFLECTION_NO_SAMPLE) and, in `candidate`, the same sample for reuse: M = 1 for every glossy
// pixel traced (kind NONE, W = 0 for a sample of zero light), M = 0 for mirrors and where
// nothing is traced.
vec4 reflectionSample(FrameConstants f, ivec2 pixel, ivec2 tracedPixel, out Reservoir candidate) {
  candidate = emptyReservoir();
  if ((imageLoad(flags, pixel).x & GBUFFER_FLAG_SURFACE) == 0u) return vec4(0.0, 0.0, 0.0, REFLECTION_NO_SAMPLE);
  float roughness = imageLoad(emissives, pixel).w;
  bool lambert = (f.flags & FRAME_FLAG_LAMBERT) != 0u;
  if (lambert || roughness > pc.maxTracedRoughness) return vec4(0.0, 0.0, 0.0, REFLECTION_NO_SAMPLE);
  vec4 encodedNormals = imageLoad(normals, pixel);
  vec3 n = decodeOctahedral(encodedNormals.xy);
  vec3 ng = decodeOctahedral(encodedNormals.zw);
  vec3 wo = -pixelRayDirection(f, vec2(pixel) + 0.5);
  vec3 position = positionFromDepth(f, vec2(pixel) + 0.5, imageLoad(depths, pixel).x);
  bool mirror = roughness < pc.mirrorRoughness;
  candidate.M = mirror ? 0.0 : 1.0;
  // x1 is the ray's origin, offset off the surface, so that a fresh sample's direction from x1
  // is the traced direction (the reuse passes take the same point: reflections_reuse.glsl).
  candidate.origin = offsetRayOrigin(position, ng);
  candidate.originNormal = n;
  float nDotV = dot(n, wo);
  if (nDotV <= 0.0) return vec4(0.0);
  float alpha = makeBrdfMaterial(vec3(1.0), 0.0, roughness, false).alpha;

  vec3 dir;
  float weight;
  float pdf = 0.0;
  uint seed = f.frameIndex ^ (pc.seed * 0x9E3779B9u);
  if (mirror) {
    // A near-mirror: the lobe is narrower than the pixel's footprint; its one direction.
    dir = reflect(-wo, n);
    weight = 1.0;
  } else {
    dir = sampleGgxReflection(n, wo, alpha, random2(uvec2(tracedPixel), seed, RANDOM_REFLECTION_DIRECTION));
    SpecularAlbedo albedo = specularAlbedo(pc.specularAlbedo, nDotV, alpha);
    float meanWeight = albedo.scale + albedo.bias;
    weight = meanWeight > 0.0 ? ggxReflectionWeight(dot(n, dir), nDotV, alpha) / meanWeight : 0.0;
    pdf = ggxReflectionPdf(max(dot(n, normalize(wo + dir)), 0.0), nDotV, alpha);
  }
  // A direction below the geometric surface would leak through it: a sample of zero light.
  if (weight <= 0.0 || dot(dir, ng) <= 0.0) return vec4(0.0);

  uvec4 key = pcg4d(uvec4(tracedPixel, seed, RANDOM_REFLECTION_HIT));
  float hitDistance;
  vec3 radiance = incomingRadiance(f, candidate.origin, dir, alpha, key, hitDistance, candidate);
  candidate.radiance = radiance;
  candidate.W = pdf > 0.0 ? 1.0 / pdf : 0.0;
  return vec4(radiance * weight, hitDistance);
}

void main() {
  FrameConstants f = FrameBlock(pc.frame).v;
  ivec2 tracedPixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(tracedPixel), pc.tracedResolution))) return;
  lightTables = LightTablesBlock(pc.lights).v;
  Reservoir candidate;
  vec4 value = reflectionSample(f, fullResPixel(f, tracedPixel), tracedPixel, candidate);
  // Nothing non-finite leaves the pass (later passes keep history of it).
  if (any(isnan(value)) || any(isinf(value))) value = vec4(0.0, 0.0, 0.0, REFLECTION_NO_SAMPLE);
  imageStore(tracedOut, tracedPixel, vec4(min(value.rgb, vec3(65000.0)), value.w));
  vec4 a, b, c, d;
  packReservoir(candidate, a, b, c, d);
  if (any(isnan(a)) || any(isinf(a)) || any(isnan(b)) || any(isinf(b))) packReservoir(emptyReservoir(), a, b, c, d);
  imageStore(candidateSample, tracedPixel, a);
  imageStore(candidateRadiance, tracedPixel, b);
  imageStore(candidateOrigin, tracedPixel, finiteOrZero(c));
  imageStore(candidateNormals, tracedPixel, d);
}
