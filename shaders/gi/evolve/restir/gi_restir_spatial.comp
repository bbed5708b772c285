// gi-restir-spatial-0 and gi-restir-spatial-1 (one shader: the two passes differ only by their
// constants, pc.variant picks spatialSamples/spatialRadius[variant]). Spatial reuse of ReSTIR GI
// (Ouyang et al. 2021, Alg. 4; seed 000, "diffuse-restir-spatial"): each GI pixel merges its own
// reservoir (canonical) with neighbours on a golden-angle spiral with exponential radius, pass 0
// 8 samples over a large radius, pass 1 5 samples over a small one, for a large data window.
// Neighbours count when their primary vertex lies on this pixel's surface (sameSurface); their
// sample is shifted to this pixel's x1 by reconnection, its weight carrying the Jacobian (Eq. 11,
// reconnectionJacobian). No visibility is tested here (gi-trace-spatial-validation-rays tests the
// final sample), so the result is biased and NOT fed back into next frame's temporal reuse.
// Pass 0 passes a reservoir through unchanged once its M reaches gi.spatialWideMaxM: the wide
// reuse is for young histories (disocclusions, the frames after a cut); on converged ones its
// far neighbours' unoccluded samples brightened occluded corners (docs/decisions.md).
#version 460
#extension GL_EXT_samplerless_texture_functions : require
#include "gi/evolve/restir/restir_gi_common.glsl"
#include "common/random.glsl"

layout(local_size_x = RESTIR_GI_GROUP_SIZE, local_size_y = RESTIR_GI_GROUP_SIZE) in;
layout(push_constant, scalar) uniform Push { RestirGiPassConstants pc; };

layout(set = 1, binding = GI_SPATIAL_BINDING_INPUT + GI_RESERVOIR_SAMPLE) uniform texture2D inSample;
layout(set = 1, binding = GI_SPATIAL_BINDING_INPUT + GI_RESERVOIR_RADIANCE) uniform texture2D inRadiance;
layout(set = 1, binding = GI_SPATIAL_BINDING_INPUT + GI_RESERVOIR_ORIGIN) uniform texture2D inOrigin;
layout(set = 1, binding = GI_SPATIAL_BINDING_INPUT + GI_RESERVOIR_NORMALS) uniform texture2D inNormals;
layout(set = 1, binding = GI_SPATIAL_BINDING_OUTPUT + GI_RESERVOIR_SAMPLE, rgba32f) uniform writeonly image2D outSample;
layout(set = 1, binding = GI_SPATIAL_BINDING_OUTPUT + GI_RESERVOIR_RADIANCE, rgba32f) uniform writeonly image2D outRadiance;
layout(set = 1, binding = GI_SPATIAL_BINDING_OUTPUT + GI_RESERVOIR_ORIGIN, rgba32f) uniform writeonly image2D outOrigin;
layout(set = 1, binding = GI_SPATIAL_BINDING_OUTPUT + GI_RESERVOIR_NORMALS, rgba16f) uniform writeonly image2D outNormals;
layout(set = 1, binding = GI_SPATIAL_BINDING_NORMALS) uniform texture2D normals;
layout(set = 1, binding = GI_SPATIAL_BINDING_DEPTH) uniform texture2D depths;
layout(set = 1, binding = GI_SPATIAL_BINDING_ESTIMATE, rgba16f) uniform writeonly image2D estimateOut;

const uint RANDOM_GI_SPATIAL = 0x47490010u;

Reservoir loadReservoir(ivec2 q) {
  return unpackReservoir(texelFetch(inSample, q, 0), texelFetch(inRadiance, q, 0), texelFetch(inOrigin, q, 0),
                         texelFetch(inNormals, q, 0));
}

// The neighbour of spatial sample i (of n): a golden-angle spiral with exponential radius around
// g, or (-1, -1) where it leaves the image or falls on g itself.
ivec2 spatialNeighbour(RestirGiConstants gi, ivec2 g, uint i, uint n, float rotation, uint variant) {
  vec2 offset = goldenSpiralOffset(i, n, rotation, gi.spatialMinRadius, gi.spatialRadius[variant]);
  ivec2 q = g + ivec2(round(offset));
  if (q == g || any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, ivec2(gi.giResolution))))
    return ivec2(-1);
  return q;
}

// 1/Z normalisation: the confidence (M) of the reservoirs that could have produced the chosen
// sample, the own one (the chosen sample has a positive target at x1) and those of the merged
// neighbours (bit i of `merged`: spatial sample i) whose surface and shift reach it
// (couldProduce). The neighbours are found again from the spiral rather than kept: an array of
// them cost every pixel registers.
float confidenceOfProducers(RestirGiConstants gi, PrimaryVertex x1, float ownM, Reservoir chosen,
                            ivec2 g, uint merged, uint n, float rotation, uint variant) {
  float z = ownM;
  for (uint i = 0u; i < n; ++i) {
    if ((merged & (1u << i)) == 0u) continue;
    ivec2 q = spatialNeighbour(gi, g, i, n, rotation, variant);
    vec3 origin = texelFetch(inOrigin, q, 0).xyz;
    vec3 originNormal = decodeOctahedral(texelFetch(inNormals, q, 0).xy);
    if (couldProduce(origin, originNormal, x1, chosen, gi.maxJacobian)) z += texelFetch(inRadiance, q, 0).w;
  }
  return z;
}

void main() {
  FrameConstants f = FrameBlock(pc.frame).v;
  RestirGiConstants gi = RestirGiBlock(pc.gi).v;
  ivec2 g = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(g), gi.giResolution))) return;
  ivec2 pixel = giRepresentativePixel(f, gi, g);
  PrimaryVertex x1 = makePrimaryVertex(f, pixel, texelFetch(normals, pixel, 0), texelFetch(depths, pixel, 0).x);
  Reservoir own = loadReservoir(g);
  Reservoir result = own;
  uint variant = min(pc.variant, 1u);
  bool wideSkipped = variant == 0u && gi.spatialWideMaxM > 0.0 && own.M >= gi.spatialWideMaxM;
  if (own.M > 0.0 && !wideSkipped) {
    ReservoirStream s = beginStream(x1, own);
    uint n = min(gi.spatialSamples[variant], RESTIR_GI_MAX_SPATIAL_SAMPLES);
    vec2 u0 = random2(uvec2(g), f.frameIndex, RANDOM_GI_SPATIAL + variant);
    float rotation = 2.0 * PI * u0.x;
    uint merged = 0u;  // bit i: spatial sample i entered the stream
    for (uint i = 0u; i < n; ++i) {
      ivec2 q = spatialNeighbour(gi, g, i, n, rotation, variant);
      if (q.x < 0) continue;
      Reservoir r = loadReservoir(q);
      if (r.M <= 0.0 || !sameSurface(gi, x1, r.origin, r.originNormal)) continue;
      float u = random2(uvec2(g), f.frameIndex * 16u + i, RANDOM_GI_SPATIAL + 2u).x;
      streamReservoir(s, x1, r, reconnectionJacobian(r.origin, x1.position, r), gi.maxJacobian, u);
      merged |= 1u << i;
    }
    bool normalise = (gi.flags & RESTIR_GI_FLAG_PRODUCER_NORMALISATION) != 0u;
    result = normalise ? endStreamNormalised(s, x1, confidenceOfProducers(gi, x1, own.M, s.chosen, g, merged, n, rotation, variant))
                       : endStream(s, x1);
  }
  vec4 a, b, c, d;
  packReservoir(result, a, b, c, d);
  imageStore(outSample, g, finiteOrZero(a));
  imageStore(outRadiance, g, finiteOrZero(b));
  imageStore(outOrigin, g, finiteOrZero(c));
  imageStore(outNormals, g, d);
  imageStore(estimateOut, g, finiteOrZero(vec4(reservoirEstimate(x1, result), 1.0)));
}
