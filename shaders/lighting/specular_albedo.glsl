// The split-sum directional albedo of the glTF BRDF (shared/specular_albedo_io.h): how much of
// uniform incident light each lobe of a material reflects towards wo. composite weights the
// frame's indirect light with it: diffuse GI by diffuseReflectance, the reflection signal (the
// lobe-weighted mean of incident radiance) by specularReflectance. Under uniform light both are
// exact, so a white furnace of any roughness and metalness shows the BRDF's directional albedo
// (Karis 2013, "Real Shading in Unreal Engine 4": the split-sum approximation).
#ifndef BOUNCE_LIGHTING_SPECULAR_ALBEDO_GLSL
#define BOUNCE_LIGHTING_SPECULAR_ALBEDO_GLSL
#include "common/brdf.glsl"
#include "shared/specular_albedo_io.h"

layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer SpecularAlbedoTable {
  vec4 v[];
};

struct SpecularAlbedo {
  float scale;           // the specular lobe reflects F0 scale + bias
  float bias;
  float diffuseFresnel;  // the diffuse lobe reflects c (1 - F0 - (1 - F0) diffuseFresnel)
};

// Bilinear lookup in the table's grid (its entries sit at both ends of each range).
SpecularAlbedo specularAlbedo(DeviceAddress table, float nDotV, float alpha) {
  const float last = float(SPECULAR_ALBEDO_SIZE - 1u);
  // The table is indexed by perceptual roughness; the material stores alpha = roughness^2.
  vec2 x = clamp(vec2(nDotV, sqrt(alpha)) * last, vec2(0.0), vec2(last));
  uvec2 i0 = uvec2(x);
  uvec2 i1 = min(i0 + 1u, uvec2(SPECULAR_ALBEDO_SIZE - 1u));
  vec2 t = x - vec2(i0);
  SpecularAlbedoTable entries = SpecularAlbedoTable(table);
  vec4 a = mix(entries.v[i0.y * SPECULAR_ALBEDO_SIZE + i0.x], entries.v[i0.y * SPECULAR_ALBEDO_SIZE + i1.x], t.x);
  vec4 b = mix(entries.v[i1.y * SPECULAR_ALBEDO_SIZE + i0.x], entries.v[i1.y * SPECULAR_ALBEDO_SIZE + i1.x], t.x);
  vec4 e = mix(a, b, t.y);
  SpecularAlbedo s;
  s.scale = e.x;
  s.bias = e.y;
  s.diffuseFresnel = e.z;
  return s;
}

// What the specular lobes of brdfEvaluate reflect of uniform light: the dielectric's (F0 = 0.04)
// and the metal's (F0 = base colour), mixed by metalness as the BRDF mixes them.
vec3 specularReflectance(SpecularAlbedo s, BrdfMaterial m) {
  if (m.lambertOnly) return vec3(0.0);
  // Schlick's F0 + (1 - F0) w = F0 (1 - w) + w.
  vec3 metal = m.baseColor * s.scale + s.bias;
  float dielectric = DIELECTRIC_F0 * s.scale + s.bias;
  return mix(vec3(dielectric), metal, m.metallic);
}

// What the diffuse lobe of brdfEvaluate reflects of uniform light: (1 - F_dielectric(v.h)) c / pi
// integrated with the cosine, on the non-metal part.
vec3 diffuseReflectance(SpecularAlbedo s, BrdfMaterial m) {
  if (m.lambertOnly) return m.baseColor;
  float transmitted = 1.0 - DIELECTRIC_F0 - (1.0 - DIELECTRIC_F0) * s.diffuseFresnel;
  return m.baseColor * ((1.0 - m.metallic) * transmitted);
}

// What a surface that a GI or cache ray hits reflects of the cache's irradiance / pi there
// (seed 000's diffuse-only continuation from the 3rd vertex on): the non-metal part its Lambert
// albedo c, the metal part its specular lobe's albedo c scale + bias, seen from wo. A metal
// reflects all it reflects through its specular lobe; with the diffuse albedo c (1 - metallic)
// alone it is black to the GI but for its direct highlights, which left the `spheres` scene's
// spheres 5-20 % dark in gi.diffuse under a uniform sky (docs/reflections.md, "The metals'
// shortfall"). The non-metal part keeps c so that the cache's Lambert reference estimator
// (gi/evolve/reference_irradiance.comp) still holds for dielectrics. table = 0: c (1 - metallic).
vec3 indirectHitReflectance(DeviceAddress table, BrdfMaterial m, vec3 n, vec3 wo) {
  if (m.lambertOnly) return m.baseColor;
  vec3 diffuse = m.baseColor * (1.0 - m.metallic);
  if (table == 0ul || m.metallic <= 0.0) return diffuse;
  SpecularAlbedo s = specularAlbedo(table, max(dot(n, wo), 0.0), m.alpha);
  return diffuse + m.metallic * (m.baseColor * s.scale + s.bias);
}

#endif
