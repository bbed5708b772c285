// The BRDF candidate of di-generate-candidates (RTXDI's one BRDF sample per pixel): a ray along
// a direction drawn from the surface's BRDF; where it first hits an emissive triangle of the
// light table, the hit point is a candidate sample (light, u) like any other. The candidates of
// both strategies are weighted by the balance heuristic (Veach 1997, §9.2; RIS with several
// source densities: Talbot 2005, §3.3): a sample y gets p_hat(y) / (M_L p_L(y) + M_B p_B(y)),
// p_L the light selection's density and p_B the BRDF's, both over the light's u. Light
// sampling finds the diffuse light of a small lamp, BRDF sampling the sharp highlight of a
// large panel in a glossy surface: together neither is noisy where the other is.
//
// p_B is the BRDF's solid-angle density of the direction towards y times |d omega / du|, without
// visibility: where the BRDF ray cannot reach y (occluded), the integrand f(y) is 0 anyway
// after the visibility ray, and the weights only need to sum to 1 where it is not.
#ifndef BOUNCE_DI_DI_BRDF_CANDIDATE_GLSL
#define BOUNCE_DI_DI_BRDF_CANDIDATE_GLSL
#include "di/di_common.glsl"

layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer DiHitMap {
  uint v[];
};

// The light-table index of the emissive triangle `hit` is on, or DI_NO_LIGHT: the three-level
// map of src/lighting/light_table.h (buildEmissiveHitMap).
uint diEmissiveHitLight(DiConstants di, TraceHit hit) {
  DiHitMap map = DiHitMap(di.hitMap);
  uint slot = map.v[hit.instance];
  if (slot == DI_NO_LIGHT) return DI_NO_LIGHT;
  slot = map.v[slot + hit.geometry - sceneInstance(hit.instance).geometryBase];
  if (slot == DI_NO_LIGHT) return DI_NO_LIGHT;
  return map.v[slot + hit.primitive];
}

// The u whose uniformTriangleBarycentrics (lights.glsl) are b: r = sqrt(u.x) = b1 + b2,
// u.y = b2 / r.
vec2 triangleSampleOfBarycentrics(vec2 b) {
  float r = b.x + b.y;
  return vec2(r * r, r > 0.0 ? b.y / r : 0.0);
}

// Whether this pixel draws the BRDF candidate (DiSettings::brdfCandidateMaxRoughness): only
// glossy lobes, where light sampling misses the highlight. Elsewhere M_B = 0 at this pixel.
bool diTracesBrdfCandidate(DiConstants di, DiSurface s) {
  return di.brdfCandidates > 0u && !s.brdf.lambertOnly && s.brdf.alpha <= di.brdfCandidateMaxAlpha;
}

// p_B: the density with which the BRDF candidate produces the sample whose integrand is `l`,
// over the light's u (0 for lights no ray can hit).
float diBrdfCandidatePdf(DiSurface s, DiLight l) {
  if (!(l.solidAngleToU > 0.0)) return 0.0;
  return brdfPdf(s.brdf, s.normal, s.wo, l.direction) * l.solidAngleToU;
}

// The balance-heuristic RIS weight of a candidate whose integrand is `l` and whose light
// selection density, times the light candidates' count, is `lightDensity`.
float diCandidateWeight(DiConstants di, DiSurface s, DiLight l, float lightDensity) {
  float pHat = diTarget(l);
  float density = lightDensity + float(di.brdfCandidates) * diBrdfCandidatePdf(s, l);
  return pHat > 0.0 && density > 0.0 ? pHat / density : 0.0;
}

// The BRDF candidate's sample from `random`: the light the ray hits and u there (quantised as
// the reservoir stores it), or DI_NO_LIGHT.
uint sampleDiBrdfCandidate(DiConstants di, DiSurface s, vec4 random, out vec2 u) {
  u = vec2(0.0);
  BrdfSample b = brdfSample(s.brdf, s.normal, s.wo, random.xyz);
  if (!b.valid || dot(b.wi, s.geometricNormal) <= 0.0) return DI_NO_LIGHT;
  TraceHit hit = traceClosest(offsetRayOrigin(s.position, s.geometricNormal), b.wi, 0.0, 3.0e38, true);
  if (!traceHitFound(hit) || !hit.frontFacing) return DI_NO_LIGHT;
  uint light = diEmissiveHitLight(di, hit);
  if (light == DI_NO_LIGHT) return DI_NO_LIGHT;
  u = unpackUnorm2x16(packUnorm2x16(triangleSampleOfBarycentrics(hit.barycentrics)));
  return light;
}

#endif
