// The split-sum directional-albedo table of the glTF BRDF (src/lighting/specular_albedo.h):
// what a surface reflects of uniform incident light, per lobe, as a function of n.v and
// perceptual roughness (Karis 2013, "Real Shading in Unreal Engine 4", the split sum's second
// factor). Computed once on the GPU from shaders/common/brdf.glsl itself
// (shaders/lighting/specular_albedo_table.comp), so it cannot drift from the reference's BRDF.
//
// Entry (i, j) at index j * SPECULAR_ALBEDO_SIZE + i holds, for n.v = i / (SIZE - 1) and
// roughness = j / (SIZE - 1) (the grid includes both ends, where the albedo changes fastest:
// rough metals lose 3 % between roughness 0.98 and 1; n.v = 0 is taken at
// SPECULAR_ALBEDO_MIN_COSINE), interpolated bilinearly:
//   x  scale: mean over the GGX lobe of (1 - w) G2 / G1(v)       w = (1 - v.h)^5, Schlick's weight
//   y  bias:  mean over the GGX lobe of w G2 / G1(v)
//       so the specular lobe with Schlick Fresnel F0 + (1 - F0) w reflects F0 scale + bias
//   z  diffuse Fresnel: (1 / pi) integral of w(v.h) cos over the hemisphere, so the diffuse
//      lobe (1 - F(v.h)) c / pi reflects c (1 - F0 - (1 - F0) z); independent of roughness
//   w  unused (0)
#ifndef BOUNCE_SHARED_SPECULAR_ALBEDO_IO_H
#define BOUNCE_SHARED_SPECULAR_ALBEDO_IO_H
#include "shared/compat.h"

BOUNCE_BEGIN_SHARED

BOUNCE_CONST uint SPECULAR_ALBEDO_SIZE = 32u;
BOUNCE_CONST float SPECULAR_ALBEDO_MIN_COSINE = 1e-3f;
// Samples per entry and per integral: a 32 x 32 jittered stratified grid (error ~0.1%).
BOUNCE_CONST uint SPECULAR_ALBEDO_STRATA = 32u;
BOUNCE_CONST uint SPECULAR_ALBEDO_GROUP_SIZE = 8u;

// Push constants of specular_albedo_table.comp.
struct SpecularAlbedoTableConstants {
  DeviceAddress table;  // vec4[SPECULAR_ALBEDO_SIZE^2], written
};
BOUNCE_CHECK_SIZE(SpecularAlbedoTableConstants, 8);

BOUNCE_END_SHARED
#endif
