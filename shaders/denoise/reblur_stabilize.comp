// reblur-stabilize (NRD REBLUR "temporal stabilisation" with anti-lag;
// research/gi10_lux_denoisers.md §2.3 (e), §3.2 step 8): a second, longer running mean (up to
// maxStabilizedFrames, NRD 63) of the post-blurred signal over its own reprojected history,
// reblur.stable (reprojected with reblur-temporal's disocclusion tests, reblur.footprint), which
// is first clamped to the fast history's 3x3 neighbourhood, mean +- sigmaScale standard
// deviations (reblur.fast-moments, from reblur-history-fix; NRD's 2; seed 002's "3 sigma" is a
// TAA-style clamp, §2.4).
// Anti-lag: where the clamp moved the stable history, its length is cut by 1 + antilagSensitivity
// x (distance moved in standard deviations of luminance), so it follows a change in a few frames.
// Last, the albedo is multiplied back (REBLUR_FLAG_ALBEDO). Pixels without a surface pass through.
#version 460
#extension GL_EXT_samplerless_texture_functions : require
#include "denoise/reblur_common.glsl"

layout(local_size_x = REBLUR_GROUP_SIZE, local_size_y = REBLUR_GROUP_SIZE) in;

layout(set = 1, binding = REBLUR_STABILIZE_BINDING_INPUT) uniform texture2D inputImage;
layout(set = 1, binding = REBLUR_STABILIZE_BINDING_FAST_MOMENTS) uniform utexture2D fastMoments;
layout(set = 1, binding = REBLUR_STABILIZE_BINDING_MOTION) uniform texture2D motions;
layout(set = 1, binding = REBLUR_STABILIZE_BINDING_FOOTPRINT) uniform utexture2D footprints;
layout(set = 1, binding = REBLUR_STABILIZE_BINDING_PREVIOUS_STABLE) uniform texture2D previousStable;
layout(set = 1, binding = REBLUR_STABILIZE_BINDING_ALBEDO) uniform texture2D albedos;
layout(set = 1, binding = REBLUR_STABILIZE_BINDING_STABLE, rgba16f) uniform writeonly image2D stableOut;
layout(set = 1, binding = REBLUR_STABILIZE_BINDING_OUTPUT, rgba16f) uniform writeonly image2D outputImage;


void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (!inImage(pixel)) return;
  vec4 current = finiteOrZero4(texelFetch(inputImage, pixel, 0));
  uvec4 moments = texelFetch(fastMoments, pixel, 0);
  if (moments.w == 0u) {  // no surface (reblur-history-fix's flag)
    imageStore(stableOut, pixel, vec4(current.rgb, 0.0));
    imageStore(outputImage, pixel, vec4(current.rgb, 0.0));
    return;
  }
  vec4 history = vec4(0.0);
  // The footprint's pixels that reblur-temporal found on this surface: the same disocclusion
  // test, not repeated here.
  uint agreeing = texelFetch(footprints, pixel, 0).r;
  vec2 previous = vec2(pixel) + 0.5 - texelFetch(motions, pixel, 0).xy;
  if (pc.historyValid != 0u && agreeing != 0u) {
    ivec2 p0;
    vec4 w = bilinearFootprint(previous, p0);
    float sum = 0.0;
    for (int i = 0; i < 4; ++i) {
      if ((agreeing & (1u << i)) == 0u) w[i] = 0.0;
      sum += w[i];
    }
    if (sum > 1e-3) {
      for (int i = 0; i < 4; ++i)
        if (w[i] > 0.0) history += w[i] * finiteOrZero4(texelFetch(previousStable, p0 + ivec2(i & 1, i >> 1), 0));
      history /= sum;
    }
  }
  float frames = history.a;
  if (frames > 0.0) {
    vec3 mean, sigma;
    unpackMoments(moments, mean, sigma);
    vec3 clamped = clamp(history.rgb, mean - pc.sigmaScale * sigma, mean + pc.sigmaScale * sigma);
    float moved = abs(reblurLuminance(history.rgb - clamped)) / max(reblurLuminance(sigma), 1e-6);
    frames = frames / (1.0 + pc.antilagSensitivity * moved);
    history.rgb = clamped;
  }
  frames = min(frames + 1.0, pc.maxStabilizedFrames);
  vec3 colour = mix(history.rgb, current.rgb, 1.0 / frames);
  imageStore(stableOut, pixel, vec4(colour, frames));
  if ((pc.flags & REBLUR_FLAG_ALBEDO) != 0u) colour *= safeAlbedo(texelFetch(albedos, pixel, 0).rgb);
  imageStore(outputImage, pixel, vec4(colour, current.a));
}
