// reblur-pre-blur (NRD REBLUR "pre-pass"; research/gi10_lux_denoisers.md §3.2 step 3): a spatial
// reuse of the noisy signal before it enters the temporal history, 8 Poisson taps in a disk of
// blurRadius pixels (NRD: 30), rotated per 8x8 tile and frame, with the geometry weights of
// reblur_common.glsl (plane, normal; no luminance weight, so the mean is kept). It also writes
// reblur.surface (normal, view depth) and reblur.slope (the depth's change per pixel), which every
// later pass reads, and divides the signal by
// the albedo (REBLUR_FLAG_ALBEDO). Pixels without a surface pass the signal through.
#version 460
#extension GL_EXT_samplerless_texture_functions : require
#include "denoise/reblur_common.glsl"

layout(local_size_x = REBLUR_GROUP_SIZE, local_size_y = REBLUR_GROUP_SIZE) in;

layout(set = 1, binding = REBLUR_PRE_BLUR_BINDING_NOISY) uniform texture2D noisyImage;
layout(set = 1, binding = REBLUR_PRE_BLUR_BINDING_DEPTH) uniform texture2D depths;
layout(set = 1, binding = REBLUR_PRE_BLUR_BINDING_NORMALS) uniform texture2D normals;
layout(set = 1, binding = REBLUR_PRE_BLUR_BINDING_ALBEDO) uniform texture2D albedos;
layout(set = 1, binding = REBLUR_PRE_BLUR_BINDING_SURFACE, rg32ui) uniform writeonly uimage2D surfaceOut;
layout(set = 1, binding = REBLUR_PRE_BLUR_BINDING_OUTPUT, rgba16f) uniform writeonly image2D outputImage;
layout(set = 1, binding = REBLUR_PRE_BLUR_BINDING_SLOPE, r32f) uniform writeonly image2D slopeOut;

float depthAt(ivec2 q) {
  float z = texelFetch(depths, q, 0).x;
  return hasSurface(z) ? z : 0.0;
}
DEFINE_REBLUR_DEPTH_SLOPE(depthAt)

vec3 normalAt(ivec2 q) {
  vec4 n = texelFetch(normals, q, 0);
  return (pc.flags & REBLUR_FLAG_OCTAHEDRAL_NORMALS) != 0u ? decodeOctahedralNormal(n.xy) : normalize(n.xyz);
}

vec3 signalAt(ivec2 q) {
  vec3 c = finiteOrZero(texelFetch(noisyImage, q, 0).rgb);
  if ((pc.flags & REBLUR_FLAG_ALBEDO) != 0u) c /= safeAlbedo(texelFetch(albedos, q, 0).rgb);
  return c;
}

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (!inImage(pixel)) return;
  float z = depthAt(pixel);
  if (!hasSurface(z)) {
    imageStore(surfaceOut, pixel, uvec4(0u));
    imageStore(slopeOut, pixel, vec4(0.0));
    imageStore(outputImage, pixel, vec4(finiteOrZero(texelFetch(noisyImage, pixel, 0).rgb), 0.0));
    return;
  }
  vec3 n = normalAt(pixel);
  imageStore(surfaceOut, pixel, uvec4(packSurface(n, z), 0u, 0u));
  float slope = depthSlope(pixel, z);
  imageStore(slopeOut, pixel, vec4(slope));
  // One rotation per 8x8 tile (and frame), not per pixel: a workgroup's taps then read nearby
  // texels together, 2.9x faster on an H200 with the same gates and Cornell FLIP
  // (docs/decisions.md); the temporal history still sees a new rotation every frame.
  mat2 rotation = tapRotation(pixel / int(REBLUR_GROUP_SIZE), 0u);
  vec3 sum = signalAt(pixel);
  float weightSum = 1.0;
  for (uint i = 0u; i < REBLUR_POISSON_TAPS; ++i) {
    vec2 offset = pc.blurRadius * (rotation * kPoisson[i]);
    ivec2 q = pixel + ivec2(round(offset));
    if (!inImage(q) || q == pixel) continue;
    // |rotation kPoisson[i]| = |kPoisson[i]|: a constant, no square root per tap.
    float w = planeWeight(z, slope, pc.blurRadius * length(kPoisson[i]), depthAt(q)) *
              normalWeight(n, normalAt(q));
    if (w <= 0.0) continue;
    sum += w * signalAt(q);
    weightSum += w;
  }
  imageStore(outputImage, pixel, vec4(sum / weightSum, 0.0));
}
