// composite: the frame's radiance before exposure (DESIGN.md §4 step 7), with the glTF
// metallic-roughness BRDF of the reference (common/brdf.glsl) for every light:
//   direct sun (full BRDF) x denoised sun visibility
//   + every other light: ReSTIR DI's di.radiance (KHR point, spot and directional lights and
//     emissive triangles, shadowed; FRAME_FLAG_DI_LIGHTS), or with --di off the KHR lights
//     unshadowed (full BRDF)
//   + indirect light split by lobe with the split-sum directional albedo
//     (lighting/specular_albedo.glsl; docs/reflections.md):
//       diffuse GI (irradiance / pi) x diffuseReflectance (albedo, non-metal part, less Fresnel)
//       + specular light x specularReflectance, where the specular light is the reflection
//         signal (demodulated: shared/specular_io.h), or the diffuse GI for surfaces rougher
//         than CompositeConstants::reflectionMaxRoughness (and for all without reflections)
//   + a placeholder ambient (unoccluded sky light, off by default) added to the diffuse GI
//   + emission; the sky where no surface is seen.
// Under uniform incident light both weights are exact, so a white furnace shows the BRDF's
// directional albedo at every roughness and metalness.
#version 460
#extension GL_EXT_samplerless_texture_functions : require
#include "common/brdf.glsl"
#include "lighting/regularize.glsl"
#include "lighting/specular_albedo.glsl"
#include "passes/hybrid_frame.glsl"
#include "shared/lighting_io.h"
#include "shared/specular_io.h"

layout(local_size_x = HYBRID_GROUP_SIZE, local_size_y = HYBRID_GROUP_SIZE) in;
layout(push_constant, scalar) uniform Push { CompositeConstants pc; };

layout(set = 1, binding = COMPOSITE_BINDING_BASE_COLOR) uniform texture2D baseColors;
layout(set = 1, binding = COMPOSITE_BINDING_NORMALS) uniform texture2D normals;
layout(set = 1, binding = COMPOSITE_BINDING_DEPTH) uniform texture2D depths;
layout(set = 1, binding = COMPOSITE_BINDING_EMISSIVE) uniform texture2D emissives;
layout(set = 1, binding = COMPOSITE_BINDING_FLAGS) uniform utexture2D flags;
layout(set = 1, binding = COMPOSITE_BINDING_SHADOWS) uniform texture2D shadows;
layout(set = 1, binding = COMPOSITE_BINDING_SKY) uniform texture2D sky;
layout(set = 1, binding = COMPOSITE_BINDING_GI_DIFFUSE) uniform texture2D giDiffuse;
layout(set = 1, binding = COMPOSITE_BINDING_REFLECTIONS) uniform texture2D reflections;
layout(set = 1, binding = COMPOSITE_BINDING_DIRECT) uniform texture2D directLight;
layout(set = 1, binding = COMPOSITE_BINDING_OUTPUT, rgba16f) uniform writeonly image2D hdrOut;

layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer PunctualLights {
  GpuPunctualLight v[];
};
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer DirectionalLights {
  GpuDistantLight v[];
};

// glTF KHR_lights_punctual: intensity / distance^2 with the spot's smooth angular falloff.
vec3 punctualLight(GpuPunctualLight p, BrdfMaterial m, vec3 position, vec3 n, vec3 wo) {
  vec3 toLight = p.position - position;
  float distanceSq = dot(toLight, toLight);
  if (!(distanceSq > 0.0)) return vec3(0.0);
  vec3 wi = toLight * inversesqrt(distanceSq);
  float attenuation = 1.0;
  if (p.type == PUNCTUAL_LIGHT_SPOT) {
    float a = clamp(dot(p.spotDirection, -wi) * p.angleScale + p.angleOffset, 0.0, 1.0);
    attenuation = a * a;
  }
  return brdfEvaluate(m, n, wo, wi) * max(dot(n, wi), 0.0) * p.intensity * (attenuation / distanceSq);
}

vec3 localLights(FrameConstants f, BrdfMaterial m, vec3 position, vec3 n, vec3 wo) {
  vec3 sum = vec3(0.0);
  for (uint i = 0u; i < f.punctualLightCount; ++i)
    sum += punctualLight(PunctualLights(f.punctualLights).v[i], m, position, n, wo);
  for (uint i = 0u; i < f.directionalLightCount; ++i) {
    GpuDistantLight d = DirectionalLights(f.directionalLights).v[i];
    // The table stores the cone-sampling weight E 2 / (1 + cos); undo it for the irradiance.
    vec3 irradiance = d.coneWeight * (0.5 * (1.0 + d.cosHalfAngle));
    sum += brdfEvaluate(m, n, wo, d.towardLight) * max(dot(n, d.towardLight), 0.0) * irradiance;
  }
  return sum;
}

// Unoccluded sky irradiance / pi around n from eight cosine-distributed directions on a
// Fibonacci spiral: a placeholder for diffuse GI, which knows about occlusion.
vec3 skyAmbient(FrameConstants f, vec3 n) {
  const uint count = 8u;
  const float goldenAngle = 2.39996323;
  vec3 t, b;
  orthonormalBasis(n, t, b);
  vec3 sum = vec3(0.0);
  for (uint i = 0u; i < count; ++i) {
    float u = (float(i) + 0.5) / float(count);
    float r = sqrt(u);
    float phi = float(i) * goldenAngle;
    vec3 dir = r * cos(phi) * t + r * sin(phi) * b + sqrt(1.0 - u) * n;
    sum += skyRadianceToward(f, normalize(dir));
  }
  return sum / float(count);
}

// Light that arrives from all around, reflected by both lobes (see the top of the file).
vec3 indirectLight(FrameConstants f, ivec2 pixel, BrdfMaterial m, vec3 n, vec3 wo, float roughness) {
  vec3 diffuseLight = texelFetch(giDiffuse, pixel, 0).rgb + f.skyAmbientStrength * skyAmbient(f, n);
  // reflections.w = 0: no traced sample reached this pixel (reflections-upsample).
  vec4 reflection = roughness <= pc.reflectionMaxRoughness ? texelFetch(reflections, pixel, 0) : vec4(0.0);
  vec3 specularLight = reflection.w > 0.0 ? reflection.rgb : diffuseLight;
  SpecularAlbedo albedo = specularAlbedo(pc.specularAlbedo, max(dot(n, wo), 0.0), m.alpha);
  return diffuseReflectance(albedo, m) * diffuseLight + specularReflectance(albedo, m) * specularLight;
}

vec3 surfaceRadiance(FrameConstants f, ivec2 pixel) {
  vec4 baseMetallic = texelFetch(baseColors, pixel, 0);
  vec4 emissiveRoughness = texelFetch(emissives, pixel, 0);
  vec3 n = decodeOctahedral(texelFetch(normals, pixel, 0).xy);
  vec3 dir = pixelRayDirection(f, vec2(pixel) + 0.5);
  vec3 wo = -dir;
  vec3 position = positionFromDepth(f, vec2(pixel) + 0.5, texelFetch(depths, pixel, 0).x);
  bool lambert = (f.flags & FRAME_FLAG_LAMBERT) != 0u;
  BrdfMaterial m = makeBrdfMaterial(baseMetallic.rgb, lambert ? 0.0 : baseMetallic.w,
                                    emissiveRoughness.w, lambert);

  float sunVisibility = texelFetch(shadows, pixel, 0).x;
  // The sun at its centre direction, its disc folded into the lobe (lighting/regularize.glsl):
  // a near-mirror then shows the disc's radiance, not a point glint of D(0) x E.
  BrdfMaterial sunLobe = m;
  sunLobe.alpha = sunDiscAlpha(m.alpha, f.sunCosHalfAngle);
  vec3 sun = brdfEvaluate(sunLobe, n, wo, f.towardSun) * max(dot(n, f.towardSun), 0.0) * f.sunIrradiance;
  bool restirDi = (f.flags & FRAME_FLAG_DI_LIGHTS) != 0u;
  vec3 lights = restirDi ? texelFetch(directLight, pixel, 0).rgb : localLights(f, m, position, n, wo);
  return sun * sunVisibility + lights +
         indirectLight(f, pixel, m, n, wo, emissiveRoughness.w) + emissiveRoughness.rgb;
}

void main() {
  FrameConstants f = FrameBlock(pc.frame).v;
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(pixel), f.resolution))) return;
  bool surface = (texelFetch(flags, pixel, 0).x & GBUFFER_FLAG_SURFACE) != 0u;
  vec3 radiance = surface ? surfaceRadiance(f, pixel) : texelFetch(sky, pixel, 0).rgb;
  // A non-finite value would poison every later temporal pass that reads the frame.
  if (any(isnan(radiance)) || any(isinf(radiance))) radiance = vec3(0.0);
  imageStore(hdrOut, pixel, vec4(min(radiance, vec3(65000.0)), 1.0));
}
