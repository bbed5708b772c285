// Widened GGX lobes for light that reaches a near-mirror from a tiny bright source (the sun, a
// punctual light) and leaves it towards a point whose own sampling cannot aim at that path:
//   - path regularization (Kaplanyan & Dachsbacher 2013, "Path Space Regularization for Holistic
//     and Robust Light Transport"; pbrt-v4's `regularize` option): at a vertex reached by a
//     glossy or diffuse ray, the light samples see the vertex's lobe no narrower than
//     `minAlpha`. Sun -> mirror -> glossy (or diffuse) -> eye is a caustic path: the ray from the
//     glossy point hits the mirror at random points, and only a spot a few millimetres wide
//     reflects the sun towards it, so one sample in thousands carries the whole contribution.
//     Widening the mirror's lobe spreads that spot (the same energy: D integrates to one for any
//     alpha) over more of the mirror, which trades the rare, huge samples for a blur of the
//     caustic. Biased; docs/reflections.md measures it against the unregularized reference;
//   - the sun's disc folded into the lobe (sunDiscAlpha), for a BRDF evaluated at the sun's
//     centre direction only (composite).
#ifndef BOUNCE_LIGHTING_REGULARIZE_GLSL
#define BOUNCE_LIGHTING_REGULARIZE_GLSL
#include "common/brdf.glsl"

// The narrowest lobe (GGX alpha) that light samples see at the hit of a diffuse ray (ReSTIR GI's
// and the cache's rays): pbrt-v4's regularization floor (alpha 0.1, roughness 0.32). A diffuse
// receiver blurs whatever it sees over its whole hemisphere, so the shape of a glint it sees
// matters little; its energy is kept.
const float DIFFUSE_RAY_HIT_MIN_ALPHA = 0.1;

// m with its specular lobe at least minAlpha wide (GGX alpha).
BrdfMaterial regularizedMaterial(BrdfMaterial m, float minAlpha) {
  m.alpha = max(m.alpha, minAlpha);
  return m;
}

// The GGX alpha whose lobe, evaluated at the sun's centre direction, approximates the lobe of
// alpha convolved with the sun's disc of half-angle acos(sunCosHalfAngle): the disc spreads the
// half-vector over half its half-angle, and a GGX lobe of alpha = that spread has the peak of the
// convolution of a mirror with the disc at normal incidence (D(0) = 1 / (pi alpha^2) against the
// disc's uniform density 4 / (pi theta^2) in the half-vector), so that a near-mirror shows the
// sun's disc at the disc's radiance instead of a point glint of D(0) x the sun's irradiance.
// Spreads add in quadrature (as variances of convolved lobes do).
float sunDiscAlpha(float alpha, float sunCosHalfAngle) {
  float spread = 0.5 * acos(clamp(sunCosHalfAngle, -1.0, 1.0));
  return sqrt(alpha * alpha + spread * spread);
}

#endif
