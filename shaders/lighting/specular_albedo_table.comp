// Fills the split-sum directional-albedo table (shared/specular_albedo_io.h), one entry per
// thread, by jittered stratified Monte Carlo over the same sampling and BRDF terms the reference
// path tracer uses (common/brdf.glsl): GGX visible normals for the specular lobe, cosine-weighted
// directions for the diffuse Fresnel term. Run once when the frame is created. The jitter
// matters: GGX's long tail puts the normals that reflect below the horizon (weight 0) in the
// last ~1 % of the radial stratum, which stratum midpoints never reach (at roughness 0.33 they
// overestimated the albedo by 1 %).
#version 460
#include "common/random.glsl"
#include "lighting/specular_albedo.glsl"

layout(local_size_x = SPECULAR_ALBEDO_GROUP_SIZE, local_size_y = SPECULAR_ALBEDO_GROUP_SIZE) in;
layout(push_constant, scalar) uniform Push { SpecularAlbedoTableConstants pc; };

layout(buffer_reference, scalar, buffer_reference_align = 4) writeonly buffer TableOut {
  vec4 v[];
};

void main() {
  uvec2 entry = gl_GlobalInvocationID.xy;
  if (any(greaterThanEqual(entry, uvec2(SPECULAR_ALBEDO_SIZE)))) return;
  vec2 grid = vec2(entry) / float(SPECULAR_ALBEDO_SIZE - 1u);
  float nDotV = max(grid.x, SPECULAR_ALBEDO_MIN_COSINE);
  float roughness = grid.y;
  float alpha = makeBrdfMaterial(vec3(1.0), 1.0, roughness, false).alpha;
  const vec3 n = vec3(0.0, 0.0, 1.0);
  vec3 wo = vec3(sqrt(1.0 - nDotV * nDotV), 0.0, nDotV);

  float scale = 0.0, bias = 0.0, diffuseFresnel = 0.0;
  const uint strata = SPECULAR_ALBEDO_STRATA;
  for (uint i = 0u; i < strata; ++i)
    for (uint j = 0u; j < strata; ++j) {
      vec4 jitter = uniformFromHash(pcg4d(uvec4(entry, i, j)));
      vec2 u = (vec2(i, j) + jitter.xy) / float(strata);
      vec3 wi = sampleGgxReflection(n, wo, alpha, u);
      float weight = ggxReflectionWeight(wi.z, nDotV, alpha);
      float w = schlickWeight(dot(wo, normalize(wo + wi)));
      scale += (1.0 - w) * weight;
      bias += w * weight;
      // Cosine-weighted directions: (1 / pi) integral of w cos = E[w].
      vec3 l = sampleCosineHemisphere(n, (vec2(i, j) + jitter.zw) / float(strata));
      diffuseFresnel += schlickWeight(dot(wo, normalize(wo + l)));
    }
  float count = float(strata * strata);
  TableOut(pc.table).v[entry.y * SPECULAR_ALBEDO_SIZE + entry.x] =
      vec4(scale / count, bias / count, diffuseFresnel / count, 0.0);
}
