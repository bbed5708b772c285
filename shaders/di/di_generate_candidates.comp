// di-generate-candidates: each pixel's initial reservoir by resampled importance sampling
// (Talbot 2005; Bitterli et al. 2020, Alg. 3) over DiConstants::lightCandidates light candidates
// drawn by power (the alias table; distant lights uniformly) or, with the light grid, most of
// them from the pixel's grid cell (di/light_grid.glsl): candidate i gets the weight
// p_hat(y_i) m_i(y_i) W_i (with the alias table alone: p_hat(y_i) / (M p(y_i))). Without the
// grid and on glossy pixels, DiConstants::brdfCandidates BRDF-sampled candidates join
// (di_brdf_candidate.glsl: diTracesBrdfCandidate), and
// every candidate gets the balance-heuristic weight p_hat(y_i) / (M_L p_L(y_i) + M_B p_B(y_i)).
// (With the grid the light strategy's density is not known, only each slot's RIS weight, so the
// host turns the BRDF candidate off there: RestirDi's makeConstants.) The kept one y has
// W = (sum of weights) / p_hat(y) and M = 1.
// Its shadow ray (RTXDI's initial visibility) is di-trace-candidate-visibility's.
#version 460
#include "di/di_brdf_candidate.glsl"
#include "di/light_grid.glsl"

layout(local_size_x = DI_GROUP_SIZE, local_size_y = DI_GROUP_SIZE) in;

layout(set = 1, binding = DI_CANDIDATES_BINDING_RESERVOIR, rgba32ui) uniform writeonly uimage2D reservoirOut;

layout(constant_id = DI_SPEC_BRDF_CANDIDATE) const uint SPEC_BRDF_CANDIDATE = DI_SPEC_ANY;

DiReservoir resampleCandidates(FrameConstants f, DiConstants di, DiSurface s, ivec2 pixel, out float target) {
  uvec4 key = diRandomKey(f, di, pixel, RANDOM_DI_CANDIDATES);
  DiReservoir r = emptyDiReservoir();
  float weightSum = 0.0;
  target = 0.0;
  bool brdfCandidate = SPEC_BRDF_CANDIDATE != 0u && diTracesBrdfCandidate(di, s);
  if (!brdfCandidate) {
    // Light candidates only: from the grid's cell where there is a grid, else the alias table.
    DiGridLookup grid = diLightGridLookup(f, di, s.position, diRandom(key).xyz);
    [[dont_unroll]] for (uint i = 0u; i < di.lightCandidates; ++i) {
      vec4 a = diRandom(key);
      vec4 b = diRandom(key);
      vec2 u;
      float sourceWeight;
      uint light = diSampleLightCandidate(grid, i, a, b.xy, u, sourceWeight);
      float pHat = sourceWeight > 0.0 ? diTarget(evaluateDiLight(s, light, u)) : 0.0;
      if (diStream(r, weightSum, light, u, pHat * sourceWeight, 0.0, b.z)) target = pHat;
    }
  } else {
    // Alias-table and BRDF candidates, weighted by the balance heuristic over both strategies.
    float count = float(di.lightCandidates);
    [[dont_unroll]] for (uint i = 0u; i < di.lightCandidates; ++i) {
      vec4 a = diRandom(key);
      vec4 b = diRandom(key);
      vec2 u;
      uint light = sampleDiLight(a, b.xy, u);
      float pdf = diSelectionPdf(light);
      DiLight l = light != DI_NO_LIGHT && pdf > 0.0 ? evaluateDiLight(s, light, u) : noDiLight();
      if (diStream(r, weightSum, light, u, diCandidateWeight(di, s, l, count * pdf), 0.0, b.z))
        target = diTarget(l);
    }
    vec2 u;
    uint light = sampleDiBrdfCandidate(di, s, diRandom(key), u);
    DiLight l = evaluateDiLight(s, light, u);
    if (diStream(r, weightSum, light, u, diCandidateWeight(di, s, l, count * diSelectionPdf(light)), 0.0,
                 diRandom(key).x))
      target = diTarget(l);
  }
  r.M = 1.0;
  r.W = diContributionWeight(weightSum, target, 1.0);
  return r;
}

void main() {
  FrameConstants f = FrameBlock(pc.frame).v;
  DiConstants di = DiBlock(pc.di).v;
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(pixel), f.resolution))) return;
  lightTables = LightTablesBlock(di.lights).v;
  DiSurface s = loadDiSurface(f, pixel);
  DiReservoir r = emptyDiReservoir();
  if (s.valid) {
    float target;
    r = resampleCandidates(f, di, s, pixel, target);
  }
  imageStore(reservoirOut, pixel, packDiReservoir(r));
}
