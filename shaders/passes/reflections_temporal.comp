// reflections-temporal: temporal reuse of the glossy reflection samples (ReSTIR, Bitterli et al.
// 2020, Alg. 3; as ReSTIR GI, Ouyang et al. 2021, §4.2; shared/reflections_reuse_io.h). Each
// traced pixel's fresh candidate (reflections-trace) is merged with last frame's reservoir of the
// same surface: the pixel is reprojected with gbuffer.velocity to the nearest traced pixel of
// last frame, whose reservoir counts only when its x1 lies on this pixel's tangent plane with a
// similar normal and roughness, and when its sample is still there (a ray; historySampleStillThere).
// Under motion its M shrinks by how much of its sample's target the turned lobe keeps
// (motionConfidence). History M is capped at temporalMaxM (RTXDI's and ReSTIR GI's
// ~20: it bounds how long a stale sample persists). The history sample is shifted to this
// frame's x1 by reconnection (its weight carries the Jacobian; the sky's is 1) and weighed by the
// GGX target at this frame's x1 and view. Normalisation 1/M: the history's x1 and lobe are this
// pixel's (the tests above), so both reservoirs could have produced either sample. The output is
// next frame's history. Pixels without reuse (mirrors, below reuseMinRoughness) pass their
// candidate through.
#version 460
#include "passes/reflections_reuse.glsl"
#include "common/random.glsl"
#include "rt/trace.glsl"

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
layout(set = 1, binding = REFLECTIONS_TEMPORAL_BINDING_PREVIOUS_LOBE, rg32f) uniform readonly image2D previousLobe;
layout(set = 1, binding = REFLECTIONS_TEMPORAL_BINDING_CURRENT_LOBE, rg32f) uniform writeonly image2D currentLobe;

// Last frame's traced pixel nearest to where full-res `pixel` was (gbuffer.velocity), or
// (-1, -1) off screen. Traced pixel g sits at its representative pixel's centre g d + d/2 + 0.5.
ivec2 previousTracedPixel(ivec2 pixel) {
  vec2 previousPixel = vec2(pixel) + 0.5 - imageLoad(velocities, pixel).xy;
  vec2 p = (previousPixel - 0.5 - float(pc.divisor / 2u)) / float(pc.divisor);
  ivec2 q = ivec2(floor(p + 0.5));
  if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, ivec2(pc.tracedResolution)))) return ivec2(-1);
  return q;
}

// Whether the history's sample is still there as seen from this frame's x1: a ray towards x2
// must hit a surface at x2's distance (within REFLECTION_REUSE_VALIDATION_TOLERANCE), and a sky
// sample's direction must stay open. A sample on an object that moved away (nothing there, or
// something farther), or one now hidden behind another surface, is stale: its stored radiance
// would stay in the reservoir for up to temporalMaxM frames, a ghost of the object (ReSTIR GI
// §4.3 validates its samples by tracing again for the same reason; here only the geometry is
// checked, which is what moves). On a static view the ray retraces the sample's own path.
bool historySampleStillThere(ReflectionReceiver p, Reservoir r) {
  if (r.kind == RESTIR_GI_KIND_NONE) return true;
  vec3 direction = reflectionSampleDirection(p.x.position, r);
  if (r.kind == RESTIR_GI_KIND_SKY) return traceVisibility(p.x.position, direction, 0.0, RESTIR_GI_SKY_DISTANCE, true);
  float d = distance(r.samplePosition, p.x.position);
  float slack = REFLECTION_REUSE_VALIDATION_TOLERANCE * d;
  TraceHit hit = traceClosest(p.x.position, direction, 0.0, d + slack, true);
  return traceHitFound(hit) && hit.t >= d - slack;
}

// The history's confidence under motion: M times min(r, 1 / r), r = p_hat_now / p_hat_then the
// ratio of its sample's target at this pixel now to the target it had where it was chosen last
// frame (reflections.reservoir.lobe). r < 1: the lobe turned away from the history's samples (the
// view or the surface moved), poor candidates here that at full confidence would outweigh the
// fresh one for many frames. r > 1: the lobe turned towards a sample that was chosen in the tail
// of the old one, whose W (about 1 / p_hat_then) then weighs it r times more than a sample of
// this lobe would be: a firefly that stays for temporalMaxM frames; M / r takes that back. On a
// static view r is exactly 1 and M stays (1/M normalisation as before: unbiased there).
float motionConfidence(ReflectionReceiver p, Reservoir history, float targetThen) {
  if (!(targetThen > 0.0)) return 1.0;
  float r = reflectionTarget(p, history) / targetThen;
  return r > 1.0 ? 1.0 / r : max(r, 0.0);
}

// The candidate merged with last frame's reservoir of the same surface and lobe, if any.
Reservoir temporalReuse(FrameConstants f, ivec2 g, ivec2 pixel, ReflectionReceiver p, Reservoir candidate) {
  ReservoirStream s = beginStreamWithTarget(candidate, reflectionTarget(p, candidate));
  ivec2 q = previousTracedPixel(pixel);
  if (q.x >= 0) {
    Reservoir history = unpackReservoir(imageLoad(previousSample, q), imageLoad(previousRadiance, q),
                                        imageLoad(previousOrigin, q), imageLoad(previousNormals, q));
    vec2 lobe = imageLoad(previousLobe, q).xy;
    if (reflectionReusable(p, history, lobe.x) && historySampleStillThere(p, history)) {
      history.M = min(history.M, pc.temporalMaxM) * motionConfidence(p, history, lobe.y);
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
  float target = 0.0;
  if (reused) {
    ReflectionReceiver p = makeReflectionReceiver(f, pixel, imageLoad(normals, pixel), imageLoad(depths, pixel).x, roughness);
    if (pc.historyValid != 0u && pc.temporalMaxM > 0.0) result = temporalReuse(f, g, pixel, p, candidate);
    target = reflectionTarget(p, result);
  }
  vec4 a, b, c, d;
  packReservoir(result, a, b, c, d);
  imageStore(currentRadiance, g, finiteOrZero(b));
  imageStore(currentSample, g, finiteOrZero(a));
  imageStore(currentOrigin, g, finiteOrZero(c));
  imageStore(currentNormals, g, d);
  // Roughness -1: no reservoir to reuse here next frame (the roughness test then fails).
  imageStore(currentLobe, g, vec4(reused ? roughness : -1.0, isFiniteValue(target) ? target : 0.0, 0.0, 0.0));
}
