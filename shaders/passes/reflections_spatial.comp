// reflections-spatial: spatial reuse of the glossy reflection samples (ReSTIR, Bitterli et al.
// 2020, Alg. 4; as ReSTIR GI's spatial pass, Ouyang et al. 2021; shared/reflections_reuse_io.h).
// Each traced pixel merges its own reservoir (reflections-temporal's, canonical) with
// spatialSamples neighbours on a golden-angle spiral whose radius is spatialRadius x the pixel's
// roughness (a narrow lobe's neighbours see other directions; at least
// REFLECTION_REUSE_MIN_RADIUS), kept when their x1 lies on this pixel's surface with a similar
// normal and roughness. Their samples are shifted to this x1 by reconnection (Jacobian: cosine at
// x2 and squared distance ratio, Eq. 11; 1 for the sky) and weighed by the GGX target at this
// pixel, with the generalized balance heuristic as MIS weights (spatialReuse). No visibility test between
// this x1 and a neighbour's x2 (ReSTIR GI's default): the bias docs/reflections.md measures.
// The output is not fed back into next frame's temporal reuse.
#version 460
#include "passes/reflections_reuse.glsl"
#include "common/random.glsl"

layout(local_size_x = HYBRID_GROUP_SIZE, local_size_y = HYBRID_GROUP_SIZE) in;
layout(push_constant, scalar) uniform Push { ReflectionReuseConstants pc; };

layout(set = 1, binding = REFLECTIONS_SPATIAL_BINDING_INPUT + GI_RESERVOIR_SAMPLE, rgba32f) uniform readonly image2D inSample;
layout(set = 1, binding = REFLECTIONS_SPATIAL_BINDING_INPUT + GI_RESERVOIR_RADIANCE, rgba32f) uniform readonly image2D inRadiance;
layout(set = 1, binding = REFLECTIONS_SPATIAL_BINDING_INPUT + GI_RESERVOIR_ORIGIN, rgba32f) uniform readonly image2D inOrigin;
layout(set = 1, binding = REFLECTIONS_SPATIAL_BINDING_INPUT + GI_RESERVOIR_NORMALS, rgba16f) uniform readonly image2D inNormals;
layout(set = 1, binding = REFLECTIONS_SPATIAL_BINDING_OUTPUT + GI_RESERVOIR_SAMPLE, rgba32f) uniform writeonly image2D outSample;
layout(set = 1, binding = REFLECTIONS_SPATIAL_BINDING_OUTPUT + GI_RESERVOIR_RADIANCE, rgba32f) uniform writeonly image2D outRadiance;
layout(set = 1, binding = REFLECTIONS_SPATIAL_BINDING_OUTPUT + GI_RESERVOIR_ORIGIN, rgba32f) uniform writeonly image2D outOrigin;
layout(set = 1, binding = REFLECTIONS_SPATIAL_BINDING_OUTPUT + GI_RESERVOIR_NORMALS, rgba16f) uniform writeonly image2D outNormals;
layout(set = 1, binding = REFLECTIONS_SPATIAL_BINDING_NORMALS, rgba16f) uniform readonly image2D normals;
layout(set = 1, binding = REFLECTIONS_SPATIAL_BINDING_DEPTH, r32f) uniform readonly image2D depths;
layout(set = 1, binding = REFLECTIONS_SPATIAL_BINDING_EMISSIVE, rgba16f) uniform readonly image2D emissives;

Reservoir loadReservoir(ivec2 q) {
  return unpackReservoir(imageLoad(inSample, q), imageLoad(inRadiance, q), imageLoad(inOrigin, q),
                         imageLoad(inNormals, q));
}

// The target at receiver j of candidate r, in the measure of this pixel's directions (the
// reconnection from this pixel's x1 to j's): p_hat_j(T(x)) |dT/dx| (Lin et al. 2022, GRIS,
// §5: the "p_hat from j" of the generalized balance heuristic). 0 where j's lobe cannot
// produce the sample.
float targetFrom(ReflectionReceiver own, ReflectionReceiver j, Reservoir r) {
  float jacobian = reconnectionJacobian(own.x.position, j.x.position, r);
  if (!(jacobian > 0.0) || jacobian > REFLECTION_REUSE_MAX_JACOBIAN) return 0.0;
  return reflectionTarget(j, r) * jacobian;
}

// Spatial resampling with the generalized balance heuristic (Lin et al. 2022, Eq. 14; Bitterli
// et al. 2020, Eq. 22): candidate i (its sample shifted to x1) enters with
//   w_i = m_i p_hat(y_i) W_i J_i,   m_i = M_i p_hat_from_i / sum_j M_j p_hat_from_j
// and W = sum w_i / p_hat(chosen). A glossy target changes strongly between neighbours (their
// normals and views turn the lobe), so the 1/M or 1/Z weights of ReSTIR GI, which assume
// similar targets, let a sample from the tail of a neighbour's lobe (large W there) land in the
// peak of this pixel's lobe: fireflies (measured: spatial reuse with 1/Z doubled the per-pixel
// noise of temporal reuse alone on `spheres`). The balance heuristic bounds each weight by the
// pixel's own share of the target. O(n^2) target evaluations, n <= 9.
Reservoir spatialReuse(FrameConstants f, ivec2 g, ReflectionReceiver p, Reservoir own) {
  uint n = min(pc.spatialSamples, REFLECTION_REUSE_MAX_SPATIAL_SAMPLES);
  uint seed = f.frameIndex ^ (pc.seed * 0x9E3779B9u);
  float rotation = 2.0 * PI * random2(uvec2(g), seed, RANDOM_REFLECTION_SPATIAL).x;
  float radius = max(REFLECTION_REUSE_MIN_RADIUS, pc.spatialRadius * p.roughness);
  // Candidate 0 is the pixel's own reservoir.
  Reservoir candidates[REFLECTION_REUSE_MAX_SPATIAL_SAMPLES + 1];
  ReflectionReceiver receivers[REFLECTION_REUSE_MAX_SPATIAL_SAMPLES + 1];
  candidates[0] = own;
  receivers[0] = p;
  uint count = 1u;
  for (uint i = 0u; i < n; ++i) {
    ivec2 q = g + ivec2(round(goldenSpiralOffset(i, n, rotation, 1.0, radius)));
    if (q == g || any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, ivec2(pc.tracedResolution)))) continue;
    Reservoir r = loadReservoir(q);
    ivec2 pixel = reflectionRepresentativePixel(f, pc.divisor, q);
    float roughness = imageLoad(emissives, pixel).w;
    if (roughness < pc.reuseMinRoughness || !reflectionReusable(p, r, roughness)) continue;
    candidates[count] = r;
    receivers[count] = makeReflectionReceiver(f, pixel, imageLoad(normals, pixel), imageLoad(depths, pixel).x, roughness);
    ++count;
  }
  ReservoirStream s = beginStreamWithTarget(emptyReservoir(), 0.0);
  s.chosen = own;
  s.M = 0.0;
  for (uint i = 0u; i < count; ++i) {
    Reservoir r = candidates[i];
    float target = reflectionTarget(p, r);
    float jacobian = i == 0u ? 1.0 : reconnectionJacobian(r.origin, p.x.position, r);
    float fromI = 0.0, fromAll = 0.0;
    for (uint j = 0u; j < count; ++j) {
      float t = j == 0u ? target : targetFrom(p, receivers[j], r);
      fromAll += candidates[j].M * t;
      if (j == i) fromI = candidates[j].M * t;
    }
    // As a stream of confidence 1 (the weights m_i already sum to 1 over the candidates):
    Reservoir weighted = r;
    weighted.M = 1.0;
    weighted.W = fromAll > 0.0 ? r.W * fromI / fromAll : 0.0;
    streamReservoirWithTarget(s, weighted, target, jacobian, REFLECTION_REUSE_MAX_JACOBIAN,
                              random2(uvec2(g), seed * 16u + i, RANDOM_REFLECTION_SPATIAL + 1u).x);
  }
  Reservoir result = endReflectionStream(s, p, 1.0);
  // Confidence: the candidates' (what later use of M, e.g. a denoiser, reads).
  result.M = 0.0;
  for (uint i = 0u; i < count; ++i) result.M += candidates[i].M;
  return result;
}

void main() {
  FrameConstants f = FrameBlock(pc.frame).v;
  ivec2 g = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(g), pc.tracedResolution))) return;
  ivec2 pixel = reflectionRepresentativePixel(f, pc.divisor, g);
  float roughness = imageLoad(emissives, pixel).w;
  Reservoir own = loadReservoir(g);
  Reservoir result = own;
  if (reflectionReused(pc, f, own, roughness) && pc.spatialSamples > 0u) {
    ReflectionReceiver p = makeReflectionReceiver(f, pixel, imageLoad(normals, pixel), imageLoad(depths, pixel).x, roughness);
    result = spatialReuse(f, g, p, own);
  }
  vec4 a, b, c, d;
  packReservoir(result, a, b, c, d);
  imageStore(outRadiance, g, finiteOrZero(b));
  imageStore(outSample, g, finiteOrZero(a));
  imageStore(outOrigin, g, finiteOrZero(c));
  imageStore(outNormals, g, d);
}
