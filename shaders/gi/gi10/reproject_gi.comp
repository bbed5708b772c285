// gi10-reproject-gi (§1.2 #24, §1.7 "ReprojectGI"): temporal accumulation of the interpolated
// irradiance. Last frame's result is fetched through the velocity (bilinear over the taps whose
// view depth agrees within 5 %). The running mean counts at most
// max(lerp(4, 8 min(N, 8), alphaBlend), 1) frames (N: the history length; at most historyCap),
// with alphaBlend = 1 - |delta| / luma_history, delta an exponential mean (1/8) of the luma
// change between the new value and the history (Capsaicin's ReprojectGI; its vignette factor
// is left out): where the light changes the history shortens, so multi-bounce light that
// arrives through feedback is not held back by 64 frames of the past. Pixels whose probes did
// not fit (alpha 0 in gi10.irradiance) keep their history when they have one. Writes gi10.gi
// (rgb, a = history length) and gi10.gi-delta (x = delta).
#version 460
#include "gi/gi10/gi10_common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(push_constant, scalar) uniform Push { Gi10PassConstants pc; };
layout(set = 1, binding = GI10_REPROJECT_GI_BINDING_IRRADIANCE, rgba16f) uniform readonly image2D irradiance;
layout(set = 1, binding = GI10_REPROJECT_GI_BINDING_DEPTH, r32f) uniform readonly image2D depths;
layout(set = 1, binding = GI10_REPROJECT_GI_BINDING_PREVIOUS_DEPTH, r32f) uniform readonly image2D previousDepths;
layout(set = 1, binding = GI10_REPROJECT_GI_BINDING_VELOCITY, rg16f) uniform readonly image2D velocities;
layout(set = 1, binding = GI10_REPROJECT_GI_BINDING_PREVIOUS, rgba16f) uniform readonly image2D previous;
layout(set = 1, binding = GI10_REPROJECT_GI_BINDING_OUTPUT, rgba16f) uniform writeonly image2D outputImage;
layout(set = 1, binding = GI10_REPROJECT_GI_BINDING_PREVIOUS_DELTA, rg16f) uniform readonly image2D previousDelta;
layout(set = 1, binding = GI10_REPROJECT_GI_BINDING_DELTA, rg16f) uniform writeonly image2D deltaOutput;

// Last frame's accumulation at this pixel: rgb, a = history length (0: none); its luma delta.
vec4 history(FrameConstants f, ivec2 pixel, float depth, out float delta) {
  delta = 0.0;
  vec2 p = vec2(pixel) + 0.5 - imageLoad(velocities, pixel).xy - 0.5;
  ivec2 base = ivec2(floor(p));
  vec2 fraction = p - vec2(base);
  vec4 sum = vec4(0.0);
  float weightSum = 0.0;
  for (uint i = 0u; i < 4u; ++i) {
    ivec2 offset = ivec2(i & 1u, i >> 1u);
    ivec2 q = base + offset;
    if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(uvec2(q), f.resolution))) continue;
    float previousDepth = imageLoad(previousDepths, q).x;
    if (!(previousDepth > 0.0) || abs(previousDepth - depth) > 0.05 * depth) continue;
    vec4 h = imageLoad(previous, q);
    if (!(h.w > 0.0)) continue;
    vec2 bilinear = mix(1.0 - fraction, fraction, vec2(offset));
    float w = bilinear.x * bilinear.y + 1e-4;
    sum += w * h;
    delta += w * imageLoad(previousDelta, q).x;
    weightSum += w;
  }
  if (!(weightSum > 0.0)) return vec4(0.0);
  delta /= weightSum;
  return sum / weightSum;
}

void main() {
  FrameConstants f = FrameBlock(pc.frame).v;
  Gi10Constants k = Gi10ConstantsRef(pc.gi10).v;
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(pixel), f.resolution))) return;
  float depth = imageLoad(depths, pixel).x;
  vec4 current = imageLoad(irradiance, pixel);
  if (!(depth > 0.0)) {
    imageStore(outputImage, pixel, vec4(0.0));
    imageStore(deltaOutput, pixel, vec4(0.0));
    return;
  }
  float delta = 0.0;
  vec4 h = k.historyValid != 0u ? history(f, pixel, depth, delta) : vec4(0.0);
  float length = h.w;
  vec3 result = current.rgb;
  if (current.w > 0.0 || !(length > 0.0)) {
    float lumaHistory = gi10Luma(h.rgb);
    delta = length > 0.0 ? mix(delta, abs(gi10Luma(current.rgb) - lumaHistory), 0.125) : 0.0;
    float alphaBlend = lumaHistory > 0.0 ? clamp(1.0 - delta / lumaHistory, 0.0, 1.0) : 1.0;
    float cap = min(max(mix(4.0, 8.0 * min(length, 8.0), alphaBlend), 1.0), k.historyCap);
    length = min(floor(length + 0.5) + 1.0, cap);
    result = mix(h.rgb, current.rgb, 1.0 / length);
  } else {
    result = h.rgb;
  }
  imageStore(deltaOutput, pixel, vec4(isnan(delta) || isinf(delta) ? 0.0 : delta, 0.0, 0.0, 0.0));
  bool finite = !any(isnan(result)) && !any(isinf(result));
  imageStore(outputImage, pixel, finite ? vec4(result, max(length, 1.0)) : vec4(0.0, 0.0, 0.0, 1.0));
}
