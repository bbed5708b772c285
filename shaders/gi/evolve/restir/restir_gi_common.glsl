// What every ReSTIR GI pass shares (shared/restir_gi_io.h): the constants, the primary vertex
// of a GI pixel, the reservoir encoding, the target function and the reconnection Jacobian.
// The reflection reuse passes (passes/reflections_reuse.glsl) share the reservoir encoding, the
// reconnection Jacobian, the streaming (with their own target) and the surface tests.
#ifndef BOUNCE_GI_EVOLVE_RESTIR_GI_COMMON_GLSL
#define BOUNCE_GI_EVOLVE_RESTIR_GI_COMMON_GLSL
#include "common/brdf.glsl"
#include "passes/hybrid_frame.glsl"
#include "shared/restir_gi_io.h"

layout(buffer_reference, scalar, buffer_reference_align = 8) readonly buffer RestirGiBlock {
  RestirGiConstants v;
};

// Purposes of the chain's random numbers (common/random.glsl).
const uint RANDOM_GI_DIRECTION = 0x47490001u;
const uint RANDOM_GI_PATH = 0x47490002u;
const uint RANDOM_GI_TEMPORAL = 0x47490003u;

// The full-res pixel whose GBuffer GI pixel g traces from (restir_gi_io.h).
ivec2 giRepresentativePixel(FrameConstants f, RestirGiConstants gi, ivec2 g) {
  ivec2 p = g * int(gi.divisor) + int(gi.divisor / 2u);
  return min(p, ivec2(f.resolution) - 1);
}

// The primary vertex x1 at a full-res pixel.
struct PrimaryVertex {
  vec3 position;
  vec3 shadingNormal;
  vec3 geometricNormal;
  float depth;  // view depth; 0 = sky
};

PrimaryVertex makePrimaryVertex(FrameConstants f, ivec2 pixel, vec4 encodedNormals, float depth) {
  PrimaryVertex v;
  v.depth = depth;
  v.position = positionFromDepth(f, vec2(pixel) + 0.5, depth);
  v.shadingNormal = decodeOctahedral(encodedNormals.xy);
  v.geometricNormal = decodeOctahedral(encodedNormals.zw);
  return v;
}

struct Reservoir {
  vec3 samplePosition;  // x2
  float W;              // unbiased contribution weight (1/sr at x1)
  vec3 radiance;        // at x2 towards x1
  float M;              // confidence
  vec3 origin;          // x1
  uint kind;            // RESTIR_GI_KIND_*
  uint age;             // frames since the sample was traced as a fresh candidate
  vec3 originNormal;    // shading normal at x1
  vec3 sampleNormal;    // geometric normal at x2 (surface samples)
};

Reservoir emptyReservoir() {
  Reservoir r;
  r.samplePosition = vec3(0.0);
  r.W = 0.0;
  r.radiance = vec3(0.0);
  r.M = 0.0;
  r.origin = vec3(0.0);
  r.kind = RESTIR_GI_KIND_NONE;
  r.age = 0u;
  r.originNormal = vec3(0.0, 0.0, 1.0);
  r.sampleNormal = vec3(0.0, 0.0, 1.0);
  return r;
}

// The kind from the origin image's w, which holds kind | age << 2 (exact in a float up to 2^24).
uint reservoirKind(float originW) { return uint(originW + 0.5) & 3u; }

Reservoir unpackReservoir(vec4 sampleW, vec4 radianceM, vec4 originKind, vec4 normals) {
  Reservoir r;
  r.samplePosition = sampleW.xyz;
  r.W = sampleW.w;
  r.radiance = radianceM.rgb;
  r.M = radianceM.w;
  r.origin = originKind.xyz;
  r.kind = reservoirKind(originKind.w);
  r.age = uint(originKind.w + 0.5) >> 2u;
  r.originNormal = decodeOctahedral(normals.xy);
  r.sampleNormal = decodeOctahedral(normals.zw);
  // Nothing non-finite survives into history (DESIGN.md §1).
  bool finite = isFiniteValue(r.W) && isFiniteValue(r.M) && all(not(isnan(r.radiance))) &&
                all(not(isinf(r.radiance))) && all(not(isnan(r.samplePosition)));
  if (!finite || r.M <= 0.0) r = emptyReservoir();
  return r;
}

void packReservoir(Reservoir r, out vec4 sampleW, out vec4 radianceM, out vec4 originKind,
                   out vec4 normals) {
  sampleW = vec4(r.samplePosition, r.W);
  radianceM = vec4(r.radiance, r.M);
  originKind = vec4(r.origin, float(r.kind | (min(r.age, 1u << 20u) << 2u)));
  normals = vec4(encodeOctahedral(r.originNormal), encodeOctahedral(r.sampleNormal));
}

// Direction and cosine of sample x2 seen from x1, zero below the geometric surface (the
// reference path tracer drops such directions too: they would leak through the surface).
float sampleCosine(PrimaryVertex x1, vec3 samplePosition, out vec3 direction) {
  direction = normalize(samplePosition - x1.position);
  if (dot(direction, x1.geometricNormal) <= 0.0) return 0.0;
  return max(dot(direction, x1.shadingNormal), 0.0);
}

// p_hat of ReSTIR GI (Ouyang et al. 2021, §4): luminance of the radiance towards x1 times the
// cosine at x1 (the diffuse BRDF's albedo / pi is the same for every sample of a pixel).
float targetFunction(PrimaryVertex x1, Reservoir r) {
  if (r.kind == RESTIR_GI_KIND_NONE) return 0.0;
  vec3 direction;
  float c = sampleCosine(x1, r.samplePosition, direction);
  return max(brdfLuminance(r.radiance), 0.0) * c;
}

// The Jacobian of the reconnection shift that moves sample x2 from primary vertex `from` to
// `to` (Ouyang et al. 2021, Eq. 11): the solid angle x2's neighbourhood subtends changes with
// the cosine at x2 and the squared distance. Sky samples keep their direction: 1. Returns 0
// when x2 does not face `to`.
float reconnectionJacobian(vec3 from, vec3 to, Reservoir r) {
  if (r.kind != RESTIR_GI_KIND_SURFACE) return 1.0;
  vec3 toFrom = from - r.samplePosition;
  vec3 toTo = to - r.samplePosition;
  float distFromSq = dot(toFrom, toFrom);
  float distToSq = dot(toTo, toTo);
  if (!(distFromSq > 0.0) || !(distToSq > 0.0)) return 0.0;
  float cosFrom = abs(dot(r.sampleNormal, toFrom)) * inversesqrt(distFromSq);
  float cosTo = dot(r.sampleNormal, toTo) * inversesqrt(distToSq);
  if (cosTo <= 0.0 || cosFrom <= 1e-6) return 0.0;
  return (cosTo / cosFrom) * (distFromSq / distToSq);
}

// The reservoir's estimate of gi.diffuse at x1 (irradiance / pi per unit albedo).
vec3 reservoirEstimate(PrimaryVertex x1, Reservoir r) {
  if (r.kind == RESTIR_GI_KIND_NONE || !(r.W > 0.0)) return vec3(0.0);
  vec3 direction;
  float c = sampleCosine(x1, r.samplePosition, direction);
  return r.radiance * (c / PI) * r.W;
}

// Reuse between primary vertices: `origin` (with shading normal `originNormal`) counts as the
// same surface as x1 when it lies within planeTolerance x view depth of x1's tangent plane and
// the normals agree to normalTolerance (RestirGiSettings).
bool sameSurfaceWithin(PrimaryVertex x1, vec3 origin, vec3 originNormal, float planeTolerance,
                       float normalTolerance) {
  float planeDistance = abs(dot(x1.geometricNormal, origin - x1.position)) / max(x1.depth, 1e-6);
  return planeDistance <= planeTolerance && dot(x1.shadingNormal, originNormal) >= normalTolerance;
}

bool sameSurface(RestirGiConstants gi, PrimaryVertex x1, vec3 origin, vec3 originNormal) {
  return sameSurfaceWithin(x1, origin, originNormal, gi.planeTolerance, gi.normalTolerance);
}

// Last frame's GI pixel under full-res pixel `pixel` (gbuffer.velocity), or (-1, -1) when it
// left the screen.
ivec2 reprojectedGiPixel(RestirGiConstants gi, ivec2 pixel, vec2 velocity) {
  vec2 previousPixel = vec2(pixel) + 0.5 - velocity;
  ivec2 q = ivec2(floor(previousPixel / float(gi.divisor)));
  if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, ivec2(gi.giResolution)))) return ivec2(-1);
  return q;
}

const float GOLDEN_ANGLE = 2.39996323;  // pi (3 - sqrt 5)

// Sample i of n on a golden-angle spiral whose radius grows exponentially from minRadius to
// maxRadius (seed 000, "diffuse-restir-spatial"): dense near the pixel, a few far samples.
vec2 goldenSpiralOffset(uint i, uint n, float rotation, float minRadius, float maxRadius) {
  float t = n > 1u ? float(i) / float(n - 1u) : 1.0;
  float radius = minRadius * pow(max(maxRadius, minRadius) / minRadius, t);
  float angle = rotation + float(i) * GOLDEN_ANGLE;
  return radius * vec2(cos(angle), sin(angle));
}

// Reservoir streaming (Ouyang et al. 2021, Alg. 2 and 4): a reservoir r, whose sample is shifted
// to x1 with Jacobian J, enters with weight w = p_hat_x1(r) W M J; the chosen sample keeps its
// target value for the final W = weightSum / (M p_hat).
struct ReservoirStream {
  Reservoir chosen;
  float chosenTarget;
  float weightSum;
  float M;
};

// The stream's arithmetic for any target function: `target` is p_hat at the receiving vertex
// of the reservoir's sample (after the shift). The reflection reuse passes
// (passes/reflections_reuse.glsl) stream with the GGX target through these.
ReservoirStream beginStreamWithTarget(Reservoir canonical, float target) {
  ReservoirStream s;
  s.chosen = canonical;
  s.chosenTarget = target;
  s.weightSum = target * canonical.W * canonical.M;
  s.M = canonical.M;
  return s;
}

void streamReservoirWithTarget(inout ReservoirStream s, Reservoir r, float target, float jacobian,
                               float maxJacobian, float u) {
  float w = jacobian <= maxJacobian ? target * r.W * r.M * jacobian : 0.0;
  s.M += r.M;
  if (!(w > 0.0)) return;
  s.weightSum += w;
  if (u * s.weightSum < w) {
    s.chosen = r;
    s.chosenTarget = target;
  }
}

ReservoirStream beginStream(PrimaryVertex x1, Reservoir canonical) {
  return beginStreamWithTarget(canonical, targetFunction(x1, canonical));
}

// Adds r (already M-capped by the caller); u: a uniform random number.
void streamReservoir(inout ReservoirStream s, PrimaryVertex x1, Reservoir r, float jacobian,
                     float maxJacobian, float u) {
  streamReservoirWithTarget(s, r, targetFunction(x1, r), jacobian, maxJacobian, u);
}

// The stream's reservoir, re-homed at x1, its W normalised by the confidence of the
// reservoirs that could have produced the chosen sample (`z`, at most s.M; s.M itself is
// ReSTIR's biased 1/M normalisation).
Reservoir endStreamNormalised(ReservoirStream s, PrimaryVertex x1, float z) {
  Reservoir r = s.chosen;
  r.M = s.M;
  r.W = s.chosenTarget > 0.0 && z > 0.0 ? s.weightSum / (z * s.chosenTarget) : 0.0;
  r.origin = x1.position;
  r.originNormal = x1.shadingNormal;
  return r;
}

Reservoir endStream(ReservoirStream s, PrimaryVertex x1) {
  return endStreamNormalised(s, x1, s.M);
}

// Whether a reservoir whose primary vertex is (origin, originNormal) could have produced
// the chosen sample and passed it on to x1: the sample lies above that surface and the reconnection
// shift to x1 is one the streams accept (Jacobian at most maxJacobian). The domain test of
// ReSTIR's 1/Z normalisation (Bitterli et al. 2020, Alg. 6; Ouyang et al. 2021, Alg. 4, here
// without visibility): dividing by the confidence of every reservoir, also those whose shift
// could never reach the chosen sample, darkens wherever shifts are rejected (grazing and
// near-contact geometry).
bool couldProduce(vec3 origin, vec3 originNormal, PrimaryVertex x1, Reservoir chosen,
                  float maxJacobian) {
  if (dot(chosen.samplePosition - origin, originNormal) <= 0.0) return false;
  float jacobian = reconnectionJacobian(origin, x1.position, chosen);
  return jacobian > 0.0 && jacobian <= maxJacobian;
}

// Validation (seed 000, "resolve-diffuse-rays": radiance changed -> lower M): how much of the
// history still holds where the validation rays of a neighbourhood found their radiance
// changed, from the sums of the stored and the re-traced luminances over the validated pixels
// of RADIANCE_VALIDATION_RADIUS GI pixels around (gi.reservoir-validity z, w): 1 - the relative
// change of the sums when it exceeds validationRadiance, else 1. Per pixel the two are single
// noisy estimates, and the stored one was *selected* for being bright, so lowering each
// reservoir's M by its own comparison kept the reservoirs whose sample happened to re-trace
// alike and discarded the others: too bright, with fireflies. Summed over a
// neighbourhood, noise cancels and a real change (a light switched, the sun moved) stands out;
// every reservoir of the neighbourhood then loses the same share of its M.
const int RADIANCE_VALIDATION_RADIUS = 2;

// Defines vec2 neighbourhoodLuminances(RestirGiConstants gi, ivec2 g): the stored and re-traced
// luminances summed over the neighbourhood of GI pixel g, read from the pass's binding of
// gi.reservoir-validity, `image` (a macro: a storage image cannot be a function parameter).
#define DEFINE_NEIGHBOURHOOD_LUMINANCES(image)                                            \
  vec2 neighbourhoodLuminances(RestirGiConstants gi, ivec2 g) {                           \
    vec2 sums = vec2(0.0);                                                                \
    for (int dy = -RADIANCE_VALIDATION_RADIUS; dy <= RADIANCE_VALIDATION_RADIUS; ++dy)    \
      for (int dx = -RADIANCE_VALIDATION_RADIUS; dx <= RADIANCE_VALIDATION_RADIUS; ++dx) { \
        ivec2 q = g + ivec2(dx, dy);                                                      \
        if (all(greaterThanEqual(q, ivec2(0))) && all(lessThan(q, ivec2(gi.giResolution)))) \
          sums += imageLoad(image, q).zw;                                                 \
      }                                                                                   \
    return sums;                                                                          \
  }

float radianceValidity(RestirGiConstants gi, float storedSum, float retracedSum) {
  float larger = max(storedSum, retracedSum);
  if (!(larger > 0.0)) return 1.0;
  float change = abs(retracedSum - storedSum) / larger;
  return change > gi.validationRadiance ? 1.0 - change : 1.0;
}

vec4 finiteOrZero(vec4 v) {
  return any(isnan(v)) || any(isinf(v)) ? vec4(0.0) : v;
}

#endif
