// gi-resolve-diffuse-rays: the radiance at each 2nd vertex (what the trace found + the NEE
// sample where its shadow ray is unoccluded) becomes a candidate reservoir of one sample drawn
// from the uniform hemisphere, pdf 1 / (2 pi): W = 2 pi, M = 1 (M = 0 where no surface is
// seen). Also writes the candidate's own estimate (for the debug view and the variance test).
// Validation rays (gi-prepare-diffuse-rays, every validationPeriod-th frame; seed 000
// "resolve-diffuse-rays") re-traced a history reservoir's direction: that reservoir becomes the
// candidate instead, and what the ray found is recorded in the *reservoir validity*
// (shared/restir_gi_io.h):
//   hit moved (by more than validationDistance x the old hit distance): the sample points at
//     geometry that is gone: M and W scaled by 0.2 here (it loses most of its weight in every
//     later merge and its estimate fades), validity x = 0.2;
//   otherwise the stored and the re-traced luminance, which gi-restir-temporal compares over a
//     neighbourhood to lower M where the light changed (restir_gi_common.glsl,
//     radianceValidity), and gi-temporal-denoise to shorten its history.
#version 460
#include "gi/evolve/restir/restir_gi_common.glsl"

layout(local_size_x = RESTIR_GI_GROUP_SIZE, local_size_y = RESTIR_GI_GROUP_SIZE) in;
layout(push_constant, scalar) uniform Push { RestirGiPassConstants pc; };

layout(set = 1, binding = GI_CANDIDATES_BINDING_NORMALS, rgba16f) uniform readonly image2D normals;
layout(set = 1, binding = GI_CANDIDATES_BINDING_DEPTH, r32f) uniform readonly image2D depths;
layout(set = 1, binding = GI_CANDIDATES_BINDING_RAYS, rgba32f) uniform readonly image2D rays;
layout(set = 1, binding = GI_CANDIDATES_BINDING_HIT, rgba32f) uniform readonly image2D hits;
layout(set = 1, binding = GI_CANDIDATES_BINDING_HIT_NORMAL, rgba16f) uniform readonly image2D hitNormals;
layout(set = 1, binding = GI_CANDIDATES_BINDING_HIT_RADIANCE, rgba32f) uniform readonly image2D hitRadiance;
layout(set = 1, binding = GI_CANDIDATES_BINDING_NEE_RADIANCE, rgba32f) uniform readonly image2D neeRadiance;
layout(set = 1, binding = GI_CANDIDATES_BINDING_VISIBILITY, r16f) uniform readonly image2D neeVisibility;
layout(set = 1, binding = GI_CANDIDATES_BINDING_SAMPLE, rgba32f) uniform writeonly image2D sampleOut;
layout(set = 1, binding = GI_CANDIDATES_BINDING_RADIANCE, rgba32f) uniform writeonly image2D radianceOut;
layout(set = 1, binding = GI_CANDIDATES_BINDING_ORIGIN, rgba32f) uniform writeonly image2D originOut;
layout(set = 1, binding = GI_CANDIDATES_BINDING_RESERVOIR_NORMALS, rgba16f) uniform writeonly image2D normalsOut;
layout(set = 1, binding = GI_CANDIDATES_BINDING_ESTIMATE, rgba16f) uniform writeonly image2D estimateOut;
layout(set = 1, binding = GI_CANDIDATES_BINDING_PREVIOUS + GI_RESERVOIR_SAMPLE, rgba32f) uniform readonly image2D previousSample;
layout(set = 1, binding = GI_CANDIDATES_BINDING_PREVIOUS + GI_RESERVOIR_RADIANCE, rgba32f) uniform readonly image2D previousRadiance;
layout(set = 1, binding = GI_CANDIDATES_BINDING_PREVIOUS + GI_RESERVOIR_ORIGIN, rgba32f) uniform readonly image2D previousOrigin;
layout(set = 1, binding = GI_CANDIDATES_BINDING_PREVIOUS + GI_RESERVOIR_NORMALS, rgba16f) uniform readonly image2D previousNormals;
layout(set = 1, binding = GI_CANDIDATES_BINDING_VALIDITY, rgba16f) uniform writeonly image2D validityOut;

const float MOVED_VALIDITY = 0.2;
const float VALIDATION_STEP = 2.0;

// The history reservoir a validation ray re-traced, with `fresh` the re-traced sample; x of
// `validity` as in gi.reservoir-validity, z and w the stored and re-traced luminance.
Reservoir validatedHistory(RestirGiConstants gi, float rayW, PrimaryVertex x1, Reservoir fresh,
                           out vec4 validity) {
  int index = int(rayW - GI_RAY_VALIDATION + 0.5);
  ivec2 q = ivec2(index % int(gi.giResolution.x), index / int(gi.giResolution.x));
  Reservoir h = unpackReservoir(imageLoad(previousSample, q), imageLoad(previousRadiance, q),
                                imageLoad(previousOrigin, q), imageLoad(previousNormals, q));
  validity = vec4(1.0, 1.0, 0.0, 0.0);
  if (h.M <= 0.0) return h;
  float oldDistance = length(h.samplePosition - x1.position);
  bool moved = fresh.kind != h.kind ||
               (fresh.kind == RESTIR_GI_KIND_SURFACE &&
                length(fresh.samplePosition - h.samplePosition) > gi.validationDistance * oldDistance);
  if (!moved) {
    // The re-traced radiance replaces the stored one. With the cache at x2 (or NEE alone) both
    // are close estimates of the same point's radiance (their sums agree closely on a static
    // view), so the estimate follows what changed, the cache's convergence
    // included: down at once, up by at most a factor VALIDATION_STEP per validation (W scaled
    // by the rest of the luminance ratio), because a sample that was dark and is now lit
    // carries the large W of a dark sample, and taking its new radiance at once makes a
    // firefly. (Limiting the way down too kept an unlit patch's light for three validations
    // after a sun jump.) With Path at x2
    // the stored value was selected from a heavy-tailed distribution (about twice the re-traced
    // one on average), and taking the re-trace would darken, so W p_hat is kept instead: the
    // estimate and the reservoir's weight in later merges stay.
    float stored = max(brdfLuminance(h.radiance), 0.0);
    float retraced = max(brdfLuminance(fresh.radiance), 0.0);
    validity.zw = vec2(stored, retraced);
    if (stored > 0.0 && retraced > 0.0) {
      float ratio = retraced / stored;
      float estimateRatio = gi.secondVertex == RESTIR_GI_SECOND_VERTEX_PATH
                                ? 1.0
                                : clamp(ratio, 0.0, VALIDATION_STEP);
      h.W *= estimateRatio / ratio;
      h.radiance = fresh.radiance;
    }
    return h;
  }
  validity.x = MOVED_VALIDITY;
  if (fresh.kind == RESTIR_GI_KIND_NONE) return emptyReservoir();
  // W = weightSum / (M p_hat) belongs to the old target value: keep W p_hat, so the estimate
  // changes only through the lowered weight and M.
  float oldTarget = targetFunction(x1, h);
  float newTarget = targetFunction(x1, fresh);
  h.W = newTarget > 0.0 ? h.W * oldTarget / newTarget * MOVED_VALIDITY : 0.0;
  h.M = max(h.M * MOVED_VALIDITY, 1.0);
  h.samplePosition = fresh.samplePosition;
  h.sampleNormal = fresh.sampleNormal;
  h.kind = fresh.kind;
  h.radiance = fresh.radiance;
  return h;
}

void main() {
  FrameConstants f = FrameBlock(pc.frame).v;
  RestirGiConstants gi = RestirGiBlock(pc.gi).v;
  ivec2 g = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(g), gi.giResolution))) return;
  ivec2 pixel = giRepresentativePixel(f, gi, g);
  PrimaryVertex x1 = makePrimaryVertex(f, pixel, imageLoad(normals, pixel), imageLoad(depths, pixel).x);
  Reservoir r = emptyReservoir();
  if (imageLoad(rays, g).w != 0.0) {
    vec4 hit = imageLoad(hits, g);
    r.kind = uint(hit.w + 0.5);
    r.samplePosition = hit.xyz;
    r.sampleNormal = decodeOctahedral(imageLoad(hitNormals, g).xy);
    r.radiance = imageLoad(hitRadiance, g).rgb + imageLoad(neeRadiance, g).rgb * imageLoad(neeVisibility, g).x;
    r.origin = x1.position;
    r.originNormal = x1.shadingNormal;
    r.M = 1.0;
    // One candidate: W = (1 / p_hat) * p_hat / p_source = 2 pi where p_hat > 0.
    r.W = targetFunction(x1, r) > 0.0 ? 2.0 * PI : 0.0;
  }
  float rayW = imageLoad(rays, g).w;
  vec4 validity = vec4(1.0, 0.0, 0.0, 0.0);
  if (rayW >= GI_RAY_VALIDATION) {
    vec4 v;
    Reservoir h = validatedHistory(gi, rayW, x1, r, v);
    if (h.M > 0.0) {
      r = h;
      r.origin = x1.position;
      r.originNormal = x1.shadingNormal;
      validity = v;
    }
  }
  imageStore(validityOut, g, finiteOrZero(min(validity, vec4(60000.0))));
  vec4 a, b, c, d;
  packReservoir(r, a, b, c, d);
  imageStore(sampleOut, g, finiteOrZero(a));
  imageStore(radianceOut, g, finiteOrZero(b));
  imageStore(originOut, g, finiteOrZero(c));
  imageStore(normalsOut, g, d);
  imageStore(estimateOut, g, finiteOrZero(vec4(reservoirEstimate(x1, r), 1.0)));
}
