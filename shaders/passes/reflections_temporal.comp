// reflections-temporal: temporal reuse of the glossy reflection samples (ReSTIR, Bitterli et al.
// 2020, Alg. 3; as ReSTIR GI, Ouyang et al. 2021, §4.2; shared/reflections_reuse_io.h). Each
// traced pixel's fresh candidate (reflections-trace) is merged with last frame's reservoir of the
// same surface: the pixel is reprojected with gbuffer.velocity to the nearest traced pixel of
// last frame, whose reservoir counts only when its x1 lies on this pixel's tangent plane with a
// similar normal and roughness. History M is capped at temporalMaxM (RTXDI's and ReSTIR GI's
// ~20: it bounds how long a stale sample persists). The history sample is shifted to this
// frame's x1 by reconnection (its weight carries the Jacobian; the sky's is 1) and weighed by the
// GGX target at this frame's x1 and view. Normalisation 1/M: the history's x1 and lobe are this
// pixel's (the tests above), so both reservoirs could have produced either sample. The output is
// next frame's history. Pixels without reuse (mirrors, below reuseMinRoughness) pass their
// candidate through.
#version 460
#include "passes/reflections_reuse.glsl"
#include "common/random.glsl"

layout(local_size_x = HYBRID_GROUP_SIZE, local_size_y = HYBRID_GROUP_SIZE) in;
layout(push_constant, scalar) uniform Push { ReflectionReuseConstants pc; };

layout(set = 1, binding = REFLECTIONS_TEMPORAL_BINDING_CANDIDATE + GI_RESERVOIR_SAMPLE, rgba32f) uniform readonly image2D candidateSample;
layout(set = 1, binding = REFLECTIONS_TEMPORAL_BINDING_CANDIDATE + GI_RESERVOIR_RADIANCE, rgba32f) uniform readonly image2D candidateRadiance;
layout(set = 1, binding = REFLECTIONS_TEMPORAL_BINDING_CANDIDATE + GI_RESERVOIR_ORIGIN, rgba32f) uniform readonly image2D candidateOrigin;
layout(set = 1, binding = REFLECTIONS_TEMPORAL_BINDING_CANDIDATE + GI_RESERVOIR_NORMALS, rgba16f) uniform readonly image2D candidateNormals;
layout(set = 1, binding = REFLECTIONS_TEMPORAL_BINDING_PREVIOUS + GI_RESERVOIR_SAMPLE, rgba32f) uniform readonly image2D previousSample;
layout(set = 1, binding = REFLECTIONS_TEMPORAL_BINDING_PREVIOUS + GI_RESERVOIR_RADIANCE, rgba32f) uniform readonly image2D previousRadiance;
layout(set = 1, binding = REFLECTIONS_TEMPORAL_BINDING_PREVIOUS + GI_RESERVOIR_ORIGIN, rgba32f) uniform readonly image2D previousOrigin;
layout(set = 1, binding = REFLECTIONS_TEMPORAL_BINDING_PREVIOUS + GI_RESERVOIR_NORMALS, rgba16f) uniform readonly image2D previousNormals;
layout(set = 1, binding = REFLECTIONS_TEMPORAL_BINDING_CURRENT + GI_RESERVOIR_SAMPLE, rgba32f) uniform writeonly image2D currentSample;
layout(set = 1, binding = REFLECTIONS_TEMPORAL_BINDING_CURRENT + GI_RESERVOIR_RADIANCE, rgba32f) uniform writeonly image2D currentRadiance;
layout(set = 1, binding = REFLECTIONS_TEMPORAL_BINDING_CURRENT + GI_RESERVOIR_ORIGIN, rgba32f) uniform writeonly image2D currentOrigin;
layout(set = 1, binding = REFLECTIONS_TEMPORAL_BINDING_CURRENT + GI_RESERVOIR_NORMALS, rgba16f) uniform writeonly image2D currentNormals;
layout(set = 1, binding = REFLECTIONS_TEMPORAL_BINDING_NORMALS, rgba16f) uniform readonly image2D normals;
layout(set = 1, binding = REFLECTIONS_TEMPORAL_BINDING_DEPTH, r32f) uniform readonly image2D depths;
layout(set = 1, binding = REFLECTIONS_TEMPORAL_BINDING_EMISSIVE, rgba16f) uniform readonly image2D emissives;
layout(set = 1, binding = REFLECTIONS_TEMPORAL_BINDING_VELOCITY, rg16f) uniform readonly image2D velocities;
layout(set = 1, binding = REFLECTIONS_TEMPORAL_BINDING_PREVIOUS_ROUGHNESS, r16f) uniform readonly image2D previousRoughness;
layout(set = 1, binding = REFLECTIONS_TEMPORAL_BINDING_CURRENT_ROUGHNESS, r16f) uniform writeonly image2D currentRoughness;

// Last frame's traced pixel nearest to where full-res `pixel` was (gbuffer.velocity), or
// (-1, -1) off screen. Traced pixel g sits at its representative pixel's centre g d + d/2 + 0.5.
ivec2 previousTracedPixel(ivec2 pixel) {
  vec2 previousPixel = vec2(pixel) + 0.5 - imageLoad(velocities, pixel).xy;
  vec2 p = (previousPixel - 0.5 - float(pc.divisor / 2u)) / float(pc.divisor);
  ivec2 q = ivec2(floor(p + 0.5));
  if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, ivec2(pc.tracedResolution)))) return ivec2(-1);
  return q;
}

// The candidate merged with last frame's reservoir of the same surface and lobe, if any.
Reservoir temporalReuse(FrameConstants f, ivec2 g, ivec2 pixel, ReflectionReceiver p, Reservoir candidate) {
  ReservoirStream s = beginStreamWithTarget(candidate, reflectionTarget(p, candidate));
  ivec2 q = previousTracedPixel(pixel);
  if (q.x >= 0) {
    Reservoir history = unpackReservoir(imageLoad(previousSample, q), imageLoad(previousRadiance, q),
                                        imageLoad(previousOrigin, q), imageLoad(previousNormals, q));
    if (reflectionReusable(p, history, imageLoad(previousRoughness, q).x)) {
      history.M = min(history.M, pc.temporalMaxM);
      streamReflection(s, p, history, random2(uvec2(g), f.frameIndex ^ (pc.seed * 0x9E3779B9u), RANDOM_REFLECTION_TEMPORAL).x);
    }
  }
  return endReflectionStream(s, p, s.M);
}

void main() {
  FrameConstants f = FrameBlock(pc.frame).v;
  ivec2 g = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(g), pc.tracedResolution))) return;
  ivec2 pixel = reflectionRepresentativePixel(f, pc.divisor, g);
  float roughness = imageLoad(emissives, pixel).w;
  Reservoir candidate = unpackReservoir(imageLoad(candidateSample, g), imageLoad(candidateRadiance, g),
                                        imageLoad(candidateOrigin, g), imageLoad(candidateNormals, g));
  Reservoir result = candidate;
  bool reused = reflectionReused(pc, f, candidate, roughness);
  if (reused && pc.historyValid != 0u && pc.temporalMaxM > 0.0) {
    ReflectionReceiver p = makeReflectionReceiver(f, pixel, imageLoad(normals, pixel), imageLoad(depths, pixel).x, roughness);
    result = temporalReuse(f, g, pixel, p, candidate);
  }
  vec4 a, b, c, d;
  packReservoir(result, a, b, c, d);
  imageStore(currentRadiance, g, finiteOrZero(b));
  imageStore(currentSample, g, finiteOrZero(a));
  imageStore(currentOrigin, g, finiteOrZero(c));
  imageStore(currentNormals, g, d);
  // -1: no reservoir to reuse here next frame (the roughness test then fails).
  imageStore(currentRoughness, g, vec4(reused ? roughness : -1.0));
}
