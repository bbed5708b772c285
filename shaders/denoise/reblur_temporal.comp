// reblur-temporal (NRD REBLUR "temporal accumulation"; research/gi10_lux_denoisers.md §3.2
// step 4): the pre-blurred signal accumulated over a reprojected slow history (up to
// maxAccumulatedFrames, NRD 30) and a fast one (maxFastAccumulatedFrames, NRD 6).
//   - Reprojection: last frame's position is pixel + 0.5 - motion; the four last-frame pixels
//     around it are read bilinearly (NRD uses Catmull-Rom; bilinear keeps it to 4 taps), each
//     only where last frame's surface agrees with this one (reblur_common.glsl sameSurface).
//     Where none agrees the histories restart (a disocclusion).
//   - Blend: running mean with weight 1 / n, n the history length plus this frame, capped at the
//     maximum (so a young history is a plain mean and an old one an EMA of ~2 n - 1 frames).
//     The slow history is last frame's output of this pass, reblur.accumulated, the fast one
//     last frame's reblur.fast. (NRD feeds the post-blurred signal back; here that compounded
//     the blurs' small bias frame after frame: docs/denoise.md.)
//   - Nothing non-finite enters history.
#version 460
#extension GL_EXT_samplerless_texture_functions : require
#include "denoise/reblur_common.glsl"

layout(local_size_x = REBLUR_GROUP_SIZE, local_size_y = REBLUR_GROUP_SIZE) in;

layout(set = 1, binding = REBLUR_TEMPORAL_BINDING_INPUT) uniform texture2D inputImage;
layout(set = 1, binding = REBLUR_TEMPORAL_BINDING_SURFACE) uniform utexture2D surfaces;
layout(set = 1, binding = REBLUR_TEMPORAL_BINDING_MOTION) uniform texture2D motions;
layout(set = 1, binding = REBLUR_TEMPORAL_BINDING_PREVIOUS_SURFACE) uniform utexture2D previousSurface;
layout(set = 1, binding = REBLUR_TEMPORAL_BINDING_PREVIOUS_HISTORY) uniform texture2D previousHistory;
layout(set = 1, binding = REBLUR_TEMPORAL_BINDING_PREVIOUS_FAST) uniform texture2D previousFast;
layout(set = 1, binding = REBLUR_TEMPORAL_BINDING_FAST, rgba16f) uniform writeonly image2D fastOut;
layout(set = 1, binding = REBLUR_TEMPORAL_BINDING_ACCUMULATED, rgba16f) uniform writeonly image2D accumulatedOut;
layout(set = 1, binding = REBLUR_TEMPORAL_BINDING_SLOPE) uniform texture2D slopes;
layout(set = 1, binding = REBLUR_TEMPORAL_BINDING_FOOTPRINT, r8ui) uniform writeonly uimage2D footprintOut;

DEFINE_REBLUR_REPROJECT(previousSurface)

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (!inImage(pixel)) return;
  vec3 signal = finiteOrZero(texelFetch(inputImage, pixel, 0).rgb);
  vec4 s = unpackSurface(texelFetch(surfaces, pixel, 0).xy);
  if (!hasSurface(s.w)) {
    imageStore(fastOut, pixel, vec4(signal, 0.0));
    imageStore(accumulatedOut, pixel, vec4(signal, 0.0));
    imageStore(footprintOut, pixel, uvec4(0u));
    return;
  }
  vec4 slow = vec4(0.0), fast = vec4(0.0);
  float frames = 0.0;  // the history's length, 0: none
  uint agreeing = 0u;  // the footprint's pixels on this surface
  vec2 previous = vec2(pixel) + 0.5 - texelFetch(motions, pixel, 0).xy;
  if (pc.historyValid != 0u && isFiniteValue(previous.x) && isFiniteValue(previous.y)) {
    ivec2 p0;
    vec4 w;
    float sum = reprojectWeights(previous, s.w, texelFetch(slopes, pixel, 0).r, s.xyz, p0, w, agreeing);
    if (sum <= 1e-3) agreeing = 0u;
    if (sum > 1e-3) {
      for (int i = 0; i < 4; ++i) {
        if (w[i] <= 0.0) continue;
        ivec2 q = p0 + ivec2(i & 1, i >> 1);
        slow += w[i] * finiteOrZero4(texelFetch(previousHistory, q, 0));
        fast += w[i] * finiteOrZero4(texelFetch(previousFast, q, 0));
      }
      slow /= sum;
      fast /= sum;
      frames = slow.a;
    }
  }
  float slowFrames = min(frames + 1.0, pc.maxAccumulatedFrames);
  float fastFrames = min(frames + 1.0, pc.maxFastAccumulatedFrames);
  vec3 slowColour = mix(slow.rgb, signal, 1.0 / slowFrames);
  vec3 fastColour = mix(fast.rgb, signal, 1.0 / fastFrames);
  imageStore(fastOut, pixel, vec4(fastColour, fastFrames));
  imageStore(accumulatedOut, pixel, vec4(slowColour, slowFrames));
  imageStore(footprintOut, pixel, uvec4(agreeing));
}
