// reflections-temporal: temporal reuse of the glossy reflection samples (ReSTIR, Bitterli et al.
// 2020, Alg. 3; as ReSTIR GI, Ouyang et al. 2021, §4.2; shared/reflections_reuse_io.h). Each
// traced pixel's fresh candidate (reflections-trace) is merged with last frame's reservoir of the
// same surface: the pixel is reprojected with gbuffer.velocity to the nearest traced pixel of
// last frame, whose reservoir counts only when its x1 lies on this pixel's tangent plane with a
// similar normal and roughness, and when its sample is still there (a ray; historySampleStillThere).
// Under motion its M shrinks by how much of its sample's target the turned lobe keeps
// (motionConfidence), and it counts only where its sample lies at the depth of what the
// neighbours' fresh candidates reflect (sameReflectedDepth). History M is capped at temporalMaxM
// (RTXDI's and ReSTIR GI's ~20: it bounds how long a stale sample persists). The history sample
// is shifted to this frame's x1 by reconnection (its weight carries the Jacobian; the sky's is
// 1) and weighed by the GGX target at this frame's x1 and view. Normalisation 1/M: the history's x1 and lobe are this
// pixel's (the tests above), so both reservoirs could have produced either sample. The output is
// next frame's history. Pixels without reuse (mirrors, below reuseMinRoughness) pass their
// candidate through.
#version 460
#include "passes/reflections_reuse.glsl"
#include "passes/reflection_parallax.glsl"
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

// A reservoir's sample's parallax seen from this pixel's x1 (passes/reflection_parallax.glsl).
float sampleParallax(FrameConstants f, ReflectionReceiver p, Reservoir r) {
  if (r.kind == RESTIR_GI_KIND_SKY) return 1.0;
  return rayParallax(distance(p.x.position, f.camera.position), distance(r.samplePosition, p.x.position));
}

// The mean parallax of the 8 neighbouring traced pixels' fresh candidates, each seen from its
// own x1 (negative where fewer than 3 have one): what the neighbourhood reflects, and at what
// depth, decided without this pixel's own candidate, so that whether its history is kept does
// not depend on the sample it is then merged with (a test on the candidate itself keeps or drops
// the history by the candidate's value: a biased mean).
float neighbourCandidatesParallax(FrameConstants f, ivec2 g) {
  float sum = 0.0, n = 0.0;
  for (int k = 0; k < 9; ++k) {
    ivec2 d = ivec2(k % 3 - 1, k / 3 - 1);
    ivec2 q = g + d;
    if (d == ivec2(0) || any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, ivec2(pc.tracedResolution)))) continue;
    float parallax = candidateParallax(f.camera.position, imageLoad(candidateSample, q), imageLoad(candidateOrigin, q));
    if (parallax < 0.0) continue;
    sum += parallax;
    n += 1.0;
  }
  return n >= 3.0 ? sum / n : -1.0;
}

// Under motion, whether the history reservoir reflects what this pixel's neighbourhood reflects
// now: its sample's parallax within motionParallaxTolerance of the neighbours' candidates'.
// Nearest-pixel reprojection by the surface's motion lands, next to the edge of a reflected
// object, on a reservoir whose sample is another object at another depth; reconnected here it passes the visibility check (the path is
// real) but is a sample this pixel's narrow lobe would almost never draw, and 1/M weighs it as if
// it could: under a camera move that leaves the object's light in the wrong pixels for up to
// temporalMaxM frames (docs/reflections.md, "Motion"). A still view is never tested.
bool sameReflectedDepth(FrameConstants f, ivec2 g, ivec2 pixel, ReflectionReceiver p, Reservoir history) {
  if (pc.motionParallaxTolerance <= 0.0 || length(imageLoad(velocities, pixel).xy) <= REFLECTION_STILL_PIXELS) return true;
  float expected = neighbourCandidatesParallax(f, g);
  if (expected < 0.0 || history.kind == RESTIR_GI_KIND_NONE) return true;
  return abs(sampleParallax(f, p, history) - expected) <= pc.motionParallaxTolerance;
}

// The candidate merged with last frame's reservoir of the same surface and lobe, if any.
Reservoir temporalReuse(FrameConstants f, ivec2 g, ivec2 pixel, ReflectionReceiver p, Reservoir candidate) {
  ReservoirStream s = beginStreamWithTarget(candidate, reflectionTarget(p, candidate));
  ivec2 q = previousTracedPixel(pixel);
  if (q.x >= 0) {
    Reservoir history = unpackReservoir(imageLoad(previousSample, q), imageLoad(previousRadiance, q),
                                        imageLoad(previousOrigin, q), imageLoad(previousNormals, q));
    vec2 lobe = imageLoad(previousLobe, q).xy;
    if (reflectionReusable(p, history, lobe.x) && sameReflectedDepth(f, g, pixel, p, history) &&
        historySampleStillThere(p, history)) {
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
