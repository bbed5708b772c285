// The glTF 2.0 metallic-roughness BRDF, as the specification's Appendix B writes it:
//   dielectric = mix(diffuse, specular, F_dielectric)   with F0 = 0.04 (IOR 1.5)
//   metal      = specular * F_conductor                 with F0 = baseColor
//   f          = mix(dielectric, metal, metallic)
// where diffuse = baseColor / pi (Lambert), specular = D * Vis with the GGX / Trowbridge-Reitz
// distribution D (Walter, Marschner, Li, Torrance 2007, "Microfacet Models for Refraction
// through Rough Surfaces"), alpha = roughness^2, Vis = G2 / (4 |n.l| |n.v|), and both Fresnel
// terms are Schlick's approximation in v.h. The diffuse lobe is weighted by (1 - F_dielectric),
// the energy split of the spec's fresnel_mix. For G2 the appendix writes the separable Smith
// product G1(l) G1(v); we use the height-correlated Smith G2 instead, as the Khronos sample
// renderer does: it is the more accurate of the two (Heitz 2014, "Understanding the
// Masking-Shadowing Function in Microfacet-Based BRDFs") and differs only near grazing angles.
//
// Sampling picks the diffuse lobe (cosine-weighted) or the specular lobe (GGX visible normals,
// Heitz 2018, "Sampling the GGX Distribution of Visible Normals", JCGT 7(4)) and returns the pdf
// of the whole mixture, so that MIS with light sampling sees one density per direction.
//
// Conventions: world-space unit vectors; n the shading normal; wo towards the viewer; wi towards
// the light; f is zero unless both lie above n.
#ifndef BOUNCE_COMMON_BRDF_GLSL
#define BOUNCE_COMMON_BRDF_GLSL
#include "common/sampling.glsl"

// Below this alpha the GGX lobe is narrower than float precision handles gracefully (D peaks
// at 1 / (pi alpha^2)); a mirror is then a very sharp glossy lobe.
const float BRDF_MIN_ALPHA = 1e-3;
const float DIELECTRIC_F0 = 0.04;

struct BrdfMaterial {
  vec3 baseColor;
  float metallic;
  float alpha;       // GGX roughness, roughness^2
  bool lambertOnly;  // --lambert: f = baseColor / pi, no specular lobe
};

BrdfMaterial makeBrdfMaterial(vec3 baseColor, float metallic, float roughness, bool lambertOnly) {
  BrdfMaterial m;
  m.baseColor = baseColor;
  m.metallic = clamp(metallic, 0.0, 1.0);
  float r = clamp(roughness, 0.0, 1.0);
  m.alpha = max(r * r, BRDF_MIN_ALPHA);
  m.lambertOnly = lambertOnly;
  return m;
}

float brdfLuminance(vec3 c) { return dot(c, vec3(0.2126, 0.7152, 0.0722)); }

float schlickWeight(float cosine) {
  float k = clamp(1.0 - cosine, 0.0, 1.0);
  float k2 = k * k;
  return k2 * k2 * k;
}

float ggxDistribution(float nDotH, float alpha) {
  float a2 = alpha * alpha;
  float d = nDotH * nDotH * (a2 - 1.0) + 1.0;
  return a2 / (PI * d * d);
}

// Smith masking of one direction for GGX.
float ggxMasking(float nDotX, float alpha) {
  float a2 = alpha * alpha;
  return 2.0 * nDotX / (nDotX + sqrt(a2 + (1.0 - a2) * nDotX * nDotX));
}

// Height-correlated Smith G2 / (4 n.l n.v), the glTF spec's V_GGX.
float ggxVisibility(float nDotL, float nDotV, float alpha) {
  float a2 = alpha * alpha;
  float ggxV = nDotL * sqrt(nDotV * nDotV * (1.0 - a2) + a2);
  float ggxL = nDotV * sqrt(nDotL * nDotL * (1.0 - a2) + a2);
  float denominator = ggxV + ggxL;
  return denominator > 0.0 ? 0.5 / denominator : 0.0;
}

// Probability of sampling the specular lobe, from rough estimates of the two lobes' albedos
// (their Fresnel weights at n.v), kept within [0.1, 0.9] when both lobes exist so that neither
// is starved (a smooth dielectric still shows its reflections).
float specularLobeProbability(BrdfMaterial m, float nDotV) {
  if (m.lambertOnly) return 0.0;
  float w = schlickWeight(nDotV);
  float dielectricF = DIELECTRIC_F0 + (1.0 - DIELECTRIC_F0) * w;
  float metalF = brdfLuminance(m.baseColor + (1.0 - m.baseColor) * w);
  float specular = (1.0 - m.metallic) * dielectricF + m.metallic * metalF;
  float diffuse = (1.0 - m.metallic) * (1.0 - dielectricF) * brdfLuminance(m.baseColor);
  if (diffuse <= 0.0) return 1.0;
  if (specular <= 0.0) return 0.0;
  return clamp(specular / (specular + diffuse), 0.1, 0.9);
}

vec3 brdfEvaluate(BrdfMaterial m, vec3 n, vec3 wo, vec3 wi) {
  float nDotL = dot(n, wi);
  float nDotV = dot(n, wo);
  if (nDotL <= 0.0 || nDotV <= 0.0) return vec3(0.0);
  vec3 diffuse = m.baseColor * (1.0 / PI);
  if (m.lambertOnly) return diffuse;
  vec3 h = normalize(wo + wi);
  float vDotH = max(dot(wo, h), 0.0);
  float specular = ggxDistribution(max(dot(n, h), 0.0), m.alpha) * ggxVisibility(nDotL, nDotV, m.alpha);
  float w = schlickWeight(vDotH);
  float dielectricF = DIELECTRIC_F0 + (1.0 - DIELECTRIC_F0) * w;
  vec3 metalF = m.baseColor + (1.0 - m.baseColor) * w;
  vec3 dielectric = (1.0 - dielectricF) * diffuse + dielectricF * specular;
  vec3 metal = metalF * specular;
  return mix(dielectric, metal, m.metallic);
}

// Density of the visible-normal sample reflected about h: D_v(h) / (4 v.h) with
// D_v = G1(v) max(v.h, 0) D(h) / n.v (Heitz 2018, eq. 3), i.e. G1(v) D(h) / (4 n.v).
float ggxReflectionPdf(float nDotH, float nDotV, float alpha) {
  return ggxMasking(nDotV, alpha) * ggxDistribution(nDotH, alpha) / (4.0 * nDotV);
}

float brdfPdf(BrdfMaterial m, vec3 n, vec3 wo, vec3 wi) {
  float nDotL = dot(n, wi);
  float nDotV = dot(n, wo);
  if (nDotL <= 0.0 || nDotV <= 0.0) return 0.0;
  float pSpecular = specularLobeProbability(m, nDotV);
  float pdf = (1.0 - pSpecular) * nDotL / PI;
  if (pSpecular > 0.0) {
    vec3 h = normalize(wo + wi);
    pdf += pSpecular * ggxReflectionPdf(max(dot(n, h), 0.0), nDotV, m.alpha);
  }
  return pdf;
}

// A GGX normal visible from vLocal (z = the surface normal), from two uniform numbers:
// stretch the view into the configuration where alpha = 1, sample the projected hemisphere
// (a disc whose far half is squashed by the view's slope), and unstretch (Heitz 2018, §4).
vec3 sampleGgxVisibleNormal(vec3 vLocal, float alpha, vec2 u) {
  vec3 vh = normalize(vec3(alpha * vLocal.x, alpha * vLocal.y, vLocal.z));
  float lengthSq = vh.x * vh.x + vh.y * vh.y;
  vec3 t1 = lengthSq > 0.0 ? vec3(-vh.y, vh.x, 0.0) * inversesqrt(lengthSq) : vec3(1.0, 0.0, 0.0);
  vec3 t2 = cross(vh, t1);
  float r = sqrt(u.x);
  float phi = 2.0 * PI * u.y;
  float p1 = r * cos(phi);
  float p2 = r * sin(phi);
  float s = 0.5 * (1.0 + vh.z);
  p2 = (1.0 - s) * sqrt(max(0.0, 1.0 - p1 * p1)) + s * p2;
  vec3 nh = p1 * t1 + p2 * t2 + sqrt(max(0.0, 1.0 - p1 * p1 - p2 * p2)) * vh;
  return normalize(vec3(alpha * nh.x, alpha * nh.y, max(nh.z, 0.0)));
}

// wo reflected about a GGX normal visible from wo (n.wo > 0): a direction of the specular lobe
// with density ggxReflectionPdf. It may point below the surface (then its weight is zero).
vec3 sampleGgxReflection(vec3 n, vec3 wo, float alpha, vec2 u) {
  vec3 t, b;
  orthonormalBasis(n, t, b);
  vec3 woLocal = vec3(dot(wo, t), dot(wo, b), dot(n, wo));
  vec3 hLocal = sampleGgxVisibleNormal(woLocal, alpha, u);
  vec3 h = normalize(hLocal.x * t + hLocal.y * b + hLocal.z * n);
  return reflect(-wo, h);
}

// The specular lobe's f cos / pdf for a sampleGgxReflection direction, with Fresnel left out
// (F = 1): D Vis n.l / (G1(v) D / (4 n.v)) = G2(l, v) / G1(v) (Heitz 2018, §2). Its mean over the
// lobe is the lobe's directional albedo without Fresnel; Fresnel multiplies it per sample.
float ggxReflectionWeight(float nDotL, float nDotV, float alpha) {
  if (nDotL <= 0.0 || nDotV <= 0.0) return 0.0;
  return 4.0 * ggxVisibility(nDotL, nDotV, alpha) * nDotL * nDotV / ggxMasking(nDotV, alpha);
}

struct BrdfSample {
  vec3 wi;
  vec3 weight;  // f cos / pdf
  float pdf;    // of the whole mixture, solid angle
  bool valid;
};

// u.xy pick the direction, u.z the lobe.
BrdfSample brdfSample(BrdfMaterial m, vec3 n, vec3 wo, vec3 u) {
  BrdfSample s;
  s.valid = false;
  s.weight = vec3(0.0);
  s.pdf = 0.0;
  s.wi = n;
  float nDotV = dot(n, wo);
  if (nDotV <= 0.0) return s;
  if (u.z < specularLobeProbability(m, nDotV)) {
    s.wi = sampleGgxReflection(n, wo, m.alpha, u.xy);
  } else {
    s.wi = sampleCosineHemisphere(n, u.xy);
  }
  float nDotL = dot(n, s.wi);
  if (nDotL <= 0.0) return s;
  s.pdf = brdfPdf(m, n, wo, s.wi);
  if (!(s.pdf > 0.0)) return s;
  s.weight = brdfEvaluate(m, n, wo, s.wi) * nDotL / s.pdf;
  s.valid = true;
  return s;
}

#endif
