// di-spatial: the temporal reservoir merged with those of DiConstants::spatialSamples neighbours
// (disocclusionSamples where the temporal reservoir's M is below disocclusionM: a pixel without
// history), uniform in a disc of spatialRadius pixels, that show a similar surface (RTXDI's
// defaults: 1 neighbour, 32 px). Each input is weighted p_hat(y) W M at this pixel. Bias
// correction (Bitterli et al. 2020, Alg. 6): the kept sample y is normalised by Z, the confidence
// of the inputs that could have produced it: those whose own target at their own pixel is
// positive for y (RTXDI's "basic" correction), and with DI_FLAG_UNBIASED also not occluded
// there, by one shadow ray per neighbour (the "ray-traced" correction, unbiased: a neighbour's
// reservoir cannot hold a light that it cannot see, because of the candidates' visibility ray,
// which that configuration turns on, and di-shade's final one on the history).
// This pixel's own reservoir always counts (where y is hidden from it, di-shade's ray gives 0).
// Not fed back (its basic correction's bias would compound): the next frame's history is
// di-temporal's output, through di-shade (di.reservoir-final).
#version 460
#include "di/di_common.glsl"

layout(local_size_x = DI_GROUP_SIZE, local_size_y = DI_GROUP_SIZE) in;

layout(set = 1, binding = DI_SPATIAL_BINDING_INPUT, rgba32ui) uniform readonly uimage2D reservoirs;
layout(set = 1, binding = DI_SPATIAL_BINDING_OUTPUT, rgba32ui) uniform writeonly uimage2D reservoirOut;

layout(constant_id = DI_SPEC_SPATIAL_TRACED_CORRECTION) const uint SPEC_TRACED_CORRECTION = DI_SPEC_ANY;

const uint MAX_DI_SPATIAL_SAMPLES = 8u;

// Whether the bias correction traces a shadow ray per neighbour (DI_FLAG_UNBIASED).
bool tracedCorrection(DiConstants di) {
  if (SPEC_TRACED_CORRECTION != DI_SPEC_ANY) return SPEC_TRACED_CORRECTION != 0u;
  return (di.flags & DI_FLAG_UNBIASED) != 0u;
}

// A pixel uniformly in the disc around `pixel` (never the pixel itself).
ivec2 neighbourPixel(ivec2 pixel, float radius, vec2 u) {
  float r = radius * sqrt(u.x);
  float phi = 2.0 * PI * u.y;
  ivec2 offset = ivec2(round(r * vec2(cos(phi), sin(phi))));
  if (offset == ivec2(0)) offset = ivec2(1, 0);
  return pixel + offset;
}

// The i-th neighbour the stream drew and its reservoir's M (0 where its surface is not similar
// to s's): a pure function of the random key, so that normalisation() finds the same neighbours
// again instead of keeping them in arrays (which went to local memory).
ivec2 drawNeighbour(FrameConstants f, DiConstants di, DiSurface s, ivec2 pixel, inout uvec4 key, out vec4 u, out DiSurface q,
                    out DiReservoir n) {
  u = diRandom(key);
  ivec2 neighbour = neighbourPixel(pixel, di.spatialRadius, u.xy);
  q = loadDiSurface(f, neighbour);
  n = emptyDiReservoir();
  if (q.valid && diSimilarSurface(di, s.depth, s.normal, q.depth, q.normal)) n = unpackDiReservoir(imageLoad(reservoirs, neighbour));
  return neighbour;
}

// Z of the kept sample: the M of every input whose target at its own pixel is positive for it.
// The input the sample came from (`kept`, -1: this pixel's own) needs no evaluation in the basic
// correction: its reservoir holds the sample with W > 0, so its target there was positive.
// `key`: the random key as it was before the first neighbour was drawn.
float normalisation(FrameConstants f, DiConstants di, DiSurface s, DiReservoir r, float ownM, ivec2 pixel, uvec4 key, uint count,
                    int kept) {
  float Z = ownM;
  bool traced = tracedCorrection(di);
  [[dont_unroll]] for (uint i = 0u; i < count; ++i) {
    vec4 u;
    DiSurface q;
    DiReservoir n;
    drawNeighbour(f, di, s, pixel, key, u, q, n);
    if (!(n.M > 0.0)) continue;
    if (!traced && int(i) == kept) {
      Z += n.M;
      continue;
    }
    DiLight l = evaluateDiLight(q, r.light, r.u);
    if (diTarget(l) > 0.0 && (!traced || diVisible(q, l))) Z += n.M;
  }
  return Z;
}

void main() {
  FrameConstants f = FrameBlock(pc.frame).v;
  DiConstants di = DiBlock(pc.di).v;
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(pixel), f.resolution))) return;
  lightTables = LightTablesBlock(di.lights).v;
  DiSurface s = loadDiSurface(f, pixel);
  DiReservoir own = unpackDiReservoir(imageLoad(reservoirs, pixel));
  DiReservoir r = emptyDiReservoir();
  if (s.valid) {
    uvec4 key = diRandomKey(f, di, pixel, RANDOM_DI_SPATIAL);
    float weightSum = 0.0, target = 0.0;
    int kept = -1;
    float ownTarget = diTarget(evaluateDiLight(s, own.light, own.u));
    if (diStream(r, weightSum, own.light, own.u, ownTarget * own.W * own.M, own.M, diRandom(key).x)) {
      target = ownTarget;
      r.visibleAge = own.visibleAge;  // this pixel's own sample: its final visibility holds
    }
    uint count = own.M < di.disocclusionM ? di.disocclusionSamples : di.spatialSamples;
    count = min(count, MAX_DI_SPATIAL_SAMPLES);
    uvec4 neighboursKey = key;
    [[dont_unroll]] for (uint i = 0u; i < count; ++i) {
      vec4 u;
      DiSurface q;
      DiReservoir n;
      drawNeighbour(f, di, s, pixel, key, u, q, n);
      if (!(n.M > 0.0)) continue;
      float t = diTarget(evaluateDiLight(s, n.light, n.u));
      if (diStream(r, weightSum, n.light, n.u, t * n.W * n.M, n.M, u.z)) {
        target = t;
        kept = int(i);
      }
    }
    float Z = r.light == DI_NO_LIGHT ? 0.0 : normalisation(f, di, s, r, own.M, pixel, neighboursKey, count, kept);
    r.W = diContributionWeight(weightSum, target, Z);
  }
  imageStore(reservoirOut, pixel, packDiReservoir(r));
}
