// The candidates' RIS of di-generate-candidates, shared with di-candidates-temporal (which draws
// them and merges the history in one pass): resampleCandidates, and the BRDF candidate's
// specialization constant. What it computes is described in di_generate_candidates.comp.
#ifndef BOUNCE_DI_CANDIDATES_GLSL
#define BOUNCE_DI_CANDIDATES_GLSL
#include "di/di_brdf_candidate.glsl"
#include "di/light_grid.glsl"

layout(constant_id = DI_SPEC_BRDF_CANDIDATE) const uint SPEC_BRDF_CANDIDATE = DI_SPEC_ANY;

// This pixel's initial reservoir (M = 1) and the target of the light it kept.
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

#endif
