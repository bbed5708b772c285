// reblur-blur and reblur-post-blur (NRD REBLUR "blur" and "post-blur";
// research/gi10_lux_denoisers.md §3.2 steps 6 and 7): 8 Poisson taps with the geometry weights of
// reblur_common.glsl (plane, normal; no luminance weight) in a disk whose radius shrinks as the
// history grows, blurRadius / (1 + n) pixels for a history of n frames (NRD's convergence
// 1 / (1 + k n), k = 1) but at least minBlurRadius: a young history is blurred wide, a converged
// one barely. As reblur-post-blur (REBLUR_FLAG_POST_BLUR) the radius is twice that (NRD) and the
// taps are rotated differently; its output goes to reblur-stabilize. The history length
// (alpha) passes through. Pixels without a surface pass through, and so do the 8x8 tiles the
// hybrid denoiser does not read ReBLUR on (REBLUR_FLAG_TILES).
#version 460
#extension GL_EXT_samplerless_texture_functions : require
#include "denoise/reblur_common.glsl"

layout(local_size_x = REBLUR_GROUP_SIZE, local_size_y = REBLUR_GROUP_SIZE) in;

layout(set = 1, binding = REBLUR_BLUR_BINDING_INPUT) uniform texture2D inputImage;
layout(set = 1, binding = REBLUR_BLUR_BINDING_SURFACE) uniform utexture2D surfaces;
layout(set = 1, binding = REBLUR_BLUR_BINDING_OUTPUT, rgba16f) uniform writeonly image2D outputImage;
layout(set = 1, binding = REBLUR_BLUR_BINDING_TILES) uniform texture2D tiles;
layout(set = 1, binding = REBLUR_BLUR_BINDING_SLOPE) uniform texture2D slopes;

// The hybrid denoiser's tile classes (hybrid_classify.comp): a workgroup is one 8x8 tile.
bool tileSkipped() {
  return (pc.flags & REBLUR_FLAG_TILES) != 0u && texelFetch(tiles, ivec2(gl_WorkGroupID.xy), 0).g == 0.0;
}

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (!inImage(pixel)) return;
  vec4 centre = texelFetch(inputImage, pixel, 0);
  vec4 s = unpackSurface(texelFetch(surfaces, pixel, 0).xy);
  // A skipped tile copies, so that neighbouring tiles' taps read finite values.
  if (!hasSurface(s.w) || tileSkipped()) {
    imageStore(outputImage, pixel, centre);
    return;
  }
  bool post = (pc.flags & REBLUR_FLAG_POST_BLUR) != 0u;
  float radius = max(pc.blurRadius / (1.0 + max(centre.a, 0.0)), pc.minBlurRadius) * (post ? 2.0 : 1.0);
  float slope = texelFetch(slopes, pixel, 0).r;
  // One rotation per 8x8 tile and frame, as the pre-blur's: a workgroup's taps read nearby
  // texels together (docs/decisions.md, "ReBLUR's blurs rotated per 8x8 tile").
  mat2 rotation = tapRotation(pixel / int(REBLUR_GROUP_SIZE), post ? 17u : 5u);
  vec3 sum = centre.rgb;
  float weightSum = 1.0;
  for (uint i = 0u; i < REBLUR_POISSON_TAPS; ++i) {
    vec2 offset = radius * (rotation * kPoisson[i]);
    ivec2 q = pixel + ivec2(round(offset));
    if (!inImage(q) || q == pixel) continue;
    // |rotation kPoisson[i]| = |kPoisson[i]|: a constant, no square root per tap.
    float w = geometryWeight(s.w, slope, radius * length(kPoisson[i]), s.xyz, texelFetch(surfaces, q, 0).xy);
    if (w <= 0.0) continue;
    sum += w * texelFetch(inputImage, q, 0).rgb;
    weightSum += w;
  }
  imageStore(outputImage, pixel, vec4(sum / weightSum, centre.a));
}
