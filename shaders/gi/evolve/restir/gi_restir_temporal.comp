// gi-restir-temporal: temporal reuse of ReSTIR GI (Ouyang et al. 2021, Alg. 3 and §4.2). The
// candidate reservoir is merged with last frame's reservoir of the same surface: the pixel is
// reprojected with gbuffer.velocity, and last frame's reservoir counts only when its primary
// vertex lies on this pixel's tangent plane (relative plane distance) with a similar normal.
// History M is capped at temporalMaxM, movingTemporalMaxM where the pixel moves (the cap bounds how
// long stale samples persist). The history sample is shifted to this frame's primary vertex by
// reconnection, so its weight carries the Jacobian (restir_gi_common.glsl); shifts with a Jacobian
// above maxJacobian are rejected (they come from grazing or near-contact geometry and would be
// fireflies). The merged reservoir is normalised by the confidence of the reservoirs that could
// have produced its sample (1/Z, Bitterli et al. 2020, Alg. 6, as the spatial passes do:
// couldProduce), not by all of theirs (ReSTIR GI's 1/M): a reservoir whose shift of that sample
// would be refused adds nothing to the weights for it, so counting its M darkened wherever shifts
// are refused (docs/gi/restir-gi.md, "Energy").
// The merged reservoir is this frame's history (the only reservoir fed back). Where the
// candidate is a validated history reservoir (gi-resolve-diffuse-rays), it replaces history
// without a merge (merging would count that history twice).
// Where the fresh candidates around the pixel stay brighter than their running mean (light
// appeared where no history sample points), history M is cut (brighteningScale; off by default).
#version 460
#include "gi/evolve/restir/restir_gi_common.glsl"
#include "common/random.glsl"

layout(local_size_x = RESTIR_GI_GROUP_SIZE, local_size_y = RESTIR_GI_GROUP_SIZE) in;
layout(push_constant, scalar) uniform Push { RestirGiPassConstants pc; };

layout(set = 1, binding = GI_TEMPORAL_BINDING_CANDIDATE + GI_RESERVOIR_SAMPLE, rgba32f) uniform readonly image2D candidateSample;
layout(set = 1, binding = GI_TEMPORAL_BINDING_CANDIDATE + GI_RESERVOIR_RADIANCE, rgba32f) uniform readonly image2D candidateRadiance;
layout(set = 1, binding = GI_TEMPORAL_BINDING_CANDIDATE + GI_RESERVOIR_ORIGIN, rgba32f) uniform readonly image2D candidateOrigin;
layout(set = 1, binding = GI_TEMPORAL_BINDING_CANDIDATE + GI_RESERVOIR_NORMALS, rgba16f) uniform readonly image2D candidateNormals;
layout(set = 1, binding = GI_TEMPORAL_BINDING_PREVIOUS + GI_RESERVOIR_SAMPLE, rgba32f) uniform readonly image2D previousSample;
layout(set = 1, binding = GI_TEMPORAL_BINDING_PREVIOUS + GI_RESERVOIR_RADIANCE, rgba32f) uniform readonly image2D previousRadiance;
layout(set = 1, binding = GI_TEMPORAL_BINDING_PREVIOUS + GI_RESERVOIR_ORIGIN, rgba32f) uniform readonly image2D previousOrigin;
layout(set = 1, binding = GI_TEMPORAL_BINDING_PREVIOUS + GI_RESERVOIR_NORMALS, rgba16f) uniform readonly image2D previousNormals;
layout(set = 1, binding = GI_TEMPORAL_BINDING_CURRENT + GI_RESERVOIR_SAMPLE, rgba32f) uniform writeonly image2D currentSample;
layout(set = 1, binding = GI_TEMPORAL_BINDING_CURRENT + GI_RESERVOIR_RADIANCE, rgba32f) uniform writeonly image2D currentRadiance;
layout(set = 1, binding = GI_TEMPORAL_BINDING_CURRENT + GI_RESERVOIR_ORIGIN, rgba32f) uniform writeonly image2D currentOrigin;
layout(set = 1, binding = GI_TEMPORAL_BINDING_CURRENT + GI_RESERVOIR_NORMALS, rgba16f) uniform writeonly image2D currentNormals;
layout(set = 1, binding = GI_TEMPORAL_BINDING_NORMALS, rgba16f) uniform readonly image2D normals;
layout(set = 1, binding = GI_TEMPORAL_BINDING_DEPTH, r32f) uniform readonly image2D depths;
layout(set = 1, binding = GI_TEMPORAL_BINDING_VELOCITY, rg16f) uniform readonly image2D velocities;
layout(set = 1, binding = GI_TEMPORAL_BINDING_ESTIMATE, rgba16f) uniform writeonly image2D estimateOut;
layout(set = 1, binding = GI_TEMPORAL_BINDING_VALIDITY, rgba16f) uniform readonly image2D validity;
layout(set = 1, binding = GI_TEMPORAL_BINDING_OCCLUSION_VALIDITY, r16f) uniform readonly image2D occlusionValidity;
layout(set = 1, binding = GI_TEMPORAL_BINDING_CANDIDATE_ESTIMATE, rgba16f) uniform readonly image2D candidateEstimate;
layout(set = 1, binding = GI_TEMPORAL_BINDING_PREVIOUS_CANDIDATE_MEAN, rg32f) uniform readonly image2D previousCandidateMean;
layout(set = 1, binding = GI_TEMPORAL_BINDING_CURRENT_CANDIDATE_MEAN, rg32f) uniform writeonly image2D currentCandidateMean;

const uint RANDOM_GI_PERMUTATION = 0x47490006u;

// Last frame's reservoir at q, one frame older; none when its sample has outlived
// maxSampleAge (RestirGiSettings).
Reservoir loadPrevious(RestirGiConstants gi, ivec2 q) {
  Reservoir r = unpackReservoir(imageLoad(previousSample, q), imageLoad(previousRadiance, q),
                                imageLoad(previousOrigin, q), imageLoad(previousNormals, q));
  r.age += 1u;
  if (gi.maxSampleAge > 0u && r.age > gi.maxSampleAge) return emptyReservoir();
  return r;
}

// Whether last frame's reservoir at q holds a sample young enough (as loadPrevious) whose
// primary vertex lies on x1's surface. Reads only the origin and its normal: the sample and its
// radiance are loaded (loadPrevious) for the history actually merged, not for every one tested.
bool previousOnSurface(RestirGiConstants gi, PrimaryVertex x1, ivec2 q) {
  vec4 origin = imageLoad(previousOrigin, q);
  uint kindAge = uint(origin.w + 0.5);
  uint age = (kindAge >> 2u) + 1u;
  if ((kindAge & 3u) == RESTIR_GI_KIND_NONE || (gi.maxSampleAge > 0u && age > gi.maxSampleAge))
    return false;
  return sameSurface(gi, x1, origin.xyz, decodeOctahedral(imageLoad(previousNormals, q).xy));
}

bool insideGi(RestirGiConstants gi, ivec2 q) {
  return all(greaterThanEqual(q, ivec2(0))) && all(lessThan(q, ivec2(gi.giResolution)));
}

// Where this pixel was last frame (gbuffer.velocity), in last frame's GI pixel coordinates:
// GI pixel g sits at its representative pixel's centre, g d + d / 2 + 0.5 (restir_gi_io.h).
vec2 previousGiPosition(RestirGiConstants gi, ivec2 pixel) {
  vec2 previousPixel = vec2(pixel) + 0.5 - imageLoad(velocities, pixel).xy;
  return (previousPixel - 0.5 - float(gi.divisor / 2u)) / float(gi.divisor);
}

// The canonical history reservoir by sub-pixel-aware reprojection (Area ReSTIR, Zhang et al.
// 2024, §5): the reprojected point falls between last frame's GI pixel centres; one of the four
// around it is picked with probability equal to its bilinear weight (renormalised over those on
// this surface), so that over frames the reuse follows the sub-pixel position instead of always
// snapping to one pixel (which makes reprojection drift and blur on moving views). With a
// static view the point is a pixel centre and this is that pixel. Returns q = (-1, -1) when no
// neighbour lies on x1's surface.
ivec2 canonicalHistoryPixel(FrameConstants f, RestirGiConstants gi, ivec2 pixel, ivec2 g,
                            PrimaryVertex x1, out Reservoir history) {
  history = emptyReservoir();
  vec2 p = previousGiPosition(gi, pixel);
  ivec2 base = ivec2(floor(p));
  vec2 t = p - vec2(base);
  float weights[4] = float[4]((1.0 - t.x) * (1.0 - t.y), t.x * (1.0 - t.y), (1.0 - t.x) * t.y, t.x * t.y);
  float total = 0.0;
  for (int i = 0; i < 4; ++i) {
    ivec2 q = base + ivec2(i & 1, i >> 1);
    if (weights[i] <= 1e-4 || !insideGi(gi, q) || !previousOnSurface(gi, x1, q)) weights[i] = 0.0;
    total += weights[i];
  }
  if (total <= 0.0) return ivec2(-1);
  float u = random2(uvec2(g), f.frameIndex, RANDOM_GI_TEMPORAL + 1u).x * total;
  for (int i = 0; i < 4; ++i) {
    if (weights[i] <= 0.0) continue;
    u -= weights[i];
    if (u <= 0.0 || i == 3) {
      ivec2 q = base + ivec2(i & 1, i >> 1);
      history = loadPrevious(gi, q);
      return history.M > 0.0 ? q : ivec2(-1);
    }
  }
  return ivec2(-1);
}

// Extra history reservoir k (1 .. temporalHistorySamples - 1) by permutation sampling (seed
// 000; after Wyman & Panteleev 2021): last frame's GI pixel q displaced by a per-frame
// permutation of a small neighbourhood (an XOR of the coordinates with a frame hash, so that
// every history pixel is used once per frame), accepted when it lies on x1's surface and last
// frame's spatial occlusion validity there says that spatial reuse holds (>= 0.5): under
// occluders, neighbours' samples would blur indirect shadows.
// p: the pixel it was read from.
Reservoir permutedHistory(FrameConstants f, RestirGiConstants gi, ivec2 q, uint k, PrimaryVertex x1,
                          out ivec2 p) {
  uvec3 h = pcg3d(uvec3(f.frameIndex, k, RANDOM_GI_PERMUTATION));
  ivec2 mask = ivec2(1 + h.x % 3u, 1 + h.y % 3u);  // 1..3: neighbours up to 3 GI pixels away
  p = q ^ mask;
  if (!insideGi(gi, p)) return emptyReservoir();
  if ((gi.flags & RESTIR_GI_FLAG_SPATIAL_VALIDATION) != 0u && imageLoad(occlusionValidity, p).x < 0.5)
    return emptyReservoir();
  if (!previousOnSurface(gi, x1, p)) return emptyReservoir();
  return loadPrevious(gi, p);
}

DEFINE_NEIGHBOURHOOD_LUMINANCES(validity)

const int BRIGHTENING_RADIUS = 2;
// The running mean's weight of this frame: 1 / temporalMaxM's default (10), so that the mean
// lags behind a change about as long as the reservoirs' history does and the cut lasts while
// it lags (a faster mean caught up in a few frames and the cut stopped while the history was
// still stale).
const float CANDIDATE_MEAN_BLEND = 0.1;

// The sum of this frame's candidate estimates (luminance) over the 5x5 GI pixels around g,
// without g itself, so that nothing decided from it depends on g's own candidate.
float neighbourhoodCandidates(RestirGiConstants gi, ivec2 g) {
  float sum = 0.0;
  for (int dy = -BRIGHTENING_RADIUS; dy <= BRIGHTENING_RADIUS; ++dy)
    for (int dx = -BRIGHTENING_RADIUS; dx <= BRIGHTENING_RADIUS; ++dx) {
      ivec2 d = ivec2(dx, dy);
      if (d != ivec2(0) && insideGi(gi, g + d))
        sum += brdfLuminance(imageLoad(candidateEstimate, g + d).rgb);
    }
  return sum;
}

// Last frame's GI pixel nearest to where this pixel was (no surface test: the running mean
// below is a smooth neighbourhood quantity), or (-1, -1) off screen.
ivec2 reprojectedGiPixel(RestirGiConstants gi, ivec2 pixel) {
  ivec2 q = ivec2(floor(previousGiPosition(gi, pixel) + 0.5));
  return insideGi(gi, q) ? q : ivec2(-1);
}

// The factor on history M from the neighbourhood's brightening (RestirGiSettings::
// historyBrightening): this frame's neighbourhood candidate sum against its running mean over
// the last frames (gi.candidate-mean, reprojected), which this also updates. Fresh candidates
// only, on both sides: comparing them with the reservoirs' own estimates cut M exactly where
// the neighbours' histories (which share samples with this one through permutation reuse)
// happened to be dark, keeping bright histories and dropping dark ones (too bright).
// Even so, any cut that happens on a static view selects: the mean holds the neighbours' past
// candidates, which this pixel's history shares through permutation reuse, so a cut where they
// were dark drops a dark history. Heavy-tailed candidates (cornell's small light, found only by
// GI rays) cross any threshold now and then: cutting at once made such scenes too bright. So
// the cut needs the threshold crossed in two consecutive frames (y of the mean image), which
// noise rarely does and a real change (the mean takes a few frames to follow) always does.
// Then (threshold / ratio)^2: a neighbourhood 10x brighter keeps 4 % of its history. A
// validated pixel's candidate is a re-traced history sample: the mean is carried over and
// validation decides.
float brighteningScale(RestirGiConstants gi, ivec2 g, ivec2 pixel, bool validated) {
  if (!(gi.historyBrightening > 1.0)) return 1.0;
  float now = neighbourhoodCandidates(gi, g);
  ivec2 q = reprojectedGiPixel(gi, pixel);
  vec2 previous = pc.historyValid != 0u && q.x >= 0 ? imageLoad(previousCandidateMean, q).xy
                                                    : vec2(now, 0.0);
  float mean = previous.x;
  float ratio = now / max(mean, 1e-6 * now + 1e-12);
  bool brighter = !validated && ratio > gi.historyBrightening;
  float updated = validated ? mean : mix(mean, now, CANDIDATE_MEAN_BLEND);
  // A validation frame has no fresh candidates: it carries the flag over rather than break the
  // run of brighter frames.
  float flag = validated ? previous.y : (brighter ? 1.0 : 0.0);
  imageStore(currentCandidateMean, g, vec4(updated, flag, 0.0, 0.0));
  if (!brighter || previous.y < 0.5) return 1.0;
  float s = gi.historyBrightening / ratio;
  return s * s;
}

// The history reservoirs a stream merged: last frame's GI pixel and the confidence each
// entered with, for the 1/Z normalisation (their vertices are read again there, as
// gi-restir-spatial does, rather than held). Slot 0 is the canonical history, slot k the
// permuted one k; a slot that merged nothing has M = 0. Every index is a constant of unrolled
// loops, so that the arrays stay in registers (indexed by a running count they went to memory:
// the pass took twice as long, docs/benchmarks.md).
const uint MAX_HISTORY_SAMPLES = 5u;  // RestirGiSettings::temporalHistorySamples
struct MergedHistory {
  ivec2 pixel[MAX_HISTORY_SAMPLES];
  float M[MAX_HISTORY_SAMPLES];
};

// Z of 1/Z: the candidate's confidence (its domain is x1's hemisphere, which holds every
// sample with a positive target at x1) plus that of every merged history reservoir that could
// have produced the chosen sample (couldProduce: above its surface, its shift to x1 accepted).
float confidenceOfProducers(RestirGiConstants gi, PrimaryVertex x1, float candidateM,
                            Reservoir chosen, MergedHistory h) {
  float z = candidateM;
  [[unroll]] for (uint i = 0u; i < MAX_HISTORY_SAMPLES; ++i) {
    if (!(h.M[i] > 0.0)) continue;
    vec3 origin = imageLoad(previousOrigin, h.pixel[i]).xyz;
    vec3 originNormal = decodeOctahedral(imageLoad(previousNormals, h.pixel[i]).xy);
    if (couldProduce(origin, originNormal, x1, chosen, gi.maxJacobian)) z += h.M[i];
  }
  return z;
}

// Caps a history reservoir's confidence (temporalMaxM x the candidate's M).
Reservoir capped(RestirGiConstants gi, Reservoir r, float candidateM) {
  r.M = min(r.M, gi.temporalMaxM * max(candidateM, 1.0));
  return r;
}

// Motion below this many pixels a frame counts as none: a still view's motion vectors hold
// rounding noise (~1e-4 pixels), which must not move the cap off its whole number.
const float STILL_MOTION = 1.0 / 32.0;

// The history cap at `pixel`: temporalMaxM where its surface stands still on screen,
// movingTemporalMaxM from a motion of movingPixels per frame on (RestirGiSettings says why).
float historyCap(RestirGiConstants gi, ivec2 pixel) {
  float motion = length(imageLoad(velocities, pixel).xy);
  bool finite = !isnan(motion) && !isinf(motion);
  float ramp = max(gi.movingPixels - STILL_MOTION, 1e-6);
  float moving = finite ? clamp((motion - STILL_MOTION) / ramp, 0.0, 1.0) : 1.0;
  return mix(gi.temporalMaxM, gi.movingTemporalMaxM, moving);
}

void main() {
  FrameConstants f = FrameBlock(pc.frame).v;
  RestirGiConstants gi = RestirGiBlock(pc.gi).v;
  ivec2 g = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(g), gi.giResolution))) return;
  ivec2 pixel = giRepresentativePixel(f, gi, g);
  // Shorter while the light settles.
  gi.temporalMaxM = max(historyCap(gi, pixel) * pc.historyScale, 1.0);
  PrimaryVertex x1 = makePrimaryVertex(f, pixel, imageLoad(normals, pixel), imageLoad(depths, pixel).x);
  Reservoir candidate = unpackReservoir(imageLoad(candidateSample, g), imageLoad(candidateRadiance, g),
                                        imageLoad(candidateOrigin, g), imageLoad(candidateNormals, g));
  bool validated = imageLoad(validity, g).y > 0.5;
  float scale = brighteningScale(gi, g, pixel, validated);
  Reservoir result = candidate;
  bool reuse = pc.historyValid != 0u && (gi.flags & RESTIR_GI_FLAG_TEMPORAL) != 0u;
  if (candidate.M > 0.0 && reuse && !validated) {
    // Candidate first (canonical), then the canonical history, then permuted ones until the
    // confidence threshold (temporalMaxM) is reached or temporalHistorySamples were tried.
    ReservoirStream s = beginStream(x1, candidate);
    MergedHistory merged;
    [[unroll]] for (uint k = 0u; k < MAX_HISTORY_SAMPLES; ++k) {
      merged.pixel[k] = ivec2(0);
      merged.M[k] = 0.0;
    }
    Reservoir history;
    ivec2 q = canonicalHistoryPixel(f, gi, pixel, g, x1, history);
    if (q.x >= 0) {
      float u = random2(uvec2(g), f.frameIndex, RANDOM_GI_TEMPORAL).x;
      // The cut scales every history reservoir's weight; how many are merged still follows
      // their unscaled confidence (else a cut would pull in more permuted neighbours, whose
      // reuse is biased and brightens).
      Reservoir h = capped(gi, history, candidate.M);
      float confidence = candidate.M + h.M;
      h.M *= scale;
      merged.pixel[0] = q;
      merged.M[0] = h.M;
      streamReservoir(s, x1, h, reconnectionJacobian(h.origin, x1.position, h), gi.maxJacobian, u);
      [[unroll]] for (uint k = 1u; k < MAX_HISTORY_SAMPLES; ++k) {
        if (k >= gi.temporalHistorySamples || confidence >= gi.temporalMaxM) break;
        ivec2 p;
        Reservoir r = permutedHistory(f, gi, q, k, x1, p);
        if (r.M <= 0.0) continue;
        r = capped(gi, r, candidate.M);
        r.M = min(r.M, gi.temporalMaxM - confidence);
        confidence += r.M;
        r.M *= scale;
        merged.pixel[k] = p;
        merged.M[k] = r.M;
        float uk = random2(uvec2(g), f.frameIndex * 8u + k, RANDOM_GI_TEMPORAL + 2u).x;
        streamReservoir(s, x1, r, reconnectionJacobian(r.origin, x1.position, r), gi.maxJacobian, uk);
      }
    }
    bool normalise = (gi.flags & RESTIR_GI_FLAG_TEMPORAL_PRODUCERS) != 0u;
    result = normalise ? endStreamNormalised(s, x1, confidenceOfProducers(gi, x1, candidate.M, s.chosen, merged))
                       : endStream(s, x1);
  }
  if (validated) {
    // Where the neighbourhood's light changed (a real change, not noise): less confidence, so
    // that the next candidates take over. (Scaling W by the neighbourhood's ratio of re-traced
    // to stored luminance as well darkened by a third with Path at x2: the stored values of
    // freshly selected samples are biased bright, the ratio with them too.)
    vec2 sums = neighbourhoodLuminances(gi, g);  // stored, re-traced
    result.M = max(min(result.M, gi.temporalMaxM) * radianceValidity(gi, sums.x, sums.y), 1.0);
    result.age += 1u;  // a history sample, re-traced: its age as of this frame
  }
  result.origin = x1.position;
  result.originNormal = x1.shadingNormal;
  if (candidate.M <= 0.0) result = emptyReservoir();
  vec4 a, b, c, d;
  packReservoir(result, a, b, c, d);
  imageStore(currentSample, g, finiteOrZero(a));
  imageStore(currentRadiance, g, finiteOrZero(b));
  imageStore(currentOrigin, g, finiteOrZero(c));
  imageStore(currentNormals, g, d);
  imageStore(estimateOut, g, finiteOrZero(vec4(reservoirEstimate(x1, result), 1.0)));
}
