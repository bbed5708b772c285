// reblur-history-fix (NRD REBLUR "history fix" and fast-history clamping;
// research/gi10_lux_denoisers.md §3.2 steps 5 and 8):
//   - A history shorter than historyFixFrames (NRD 3) is rebuilt from a sparse 5x5 kernel of
//     its neighbours on the same surface, stride historyFixStride pixels (NRD 14) for a history
//     of 1 frame, shrinking linearly to 0 at historyFixFrames; neighbours with a longer history
//     weigh more (weight 1 + their length), so a disoccluded pixel borrows converged light.
//   - Anti-lag: the slow history is clamped to the fast history's 3x3 neighbourhood, mean +-
//     sigmaScale (NRD 2) standard deviations; where it had to move, its length is cut by
//     1 + antilagSensitivity x (the distance moved in those standard deviations), so a lighting
//     change is followed at the fast history's pace rather than the slow one's.
//   - Anti-firefly (NRD's REBLUR anti-firefly, radius 4, 2 sigma; before the anti-lag clamp):
//     the luminance is clamped to its same-surface neighbours' mean +- antiFireflySigma
//     standard deviations, read in a 9x9 window less the 3x3 centre (a firefly's own blur
//     footprint would vouch for it).
// The result (rgb, a the history length) goes to reblur-blur; the fast history's neighbourhood
// statistics go to reblur.fast-moments, for reblur-stabilize's clamp to the same neighbourhood.
#version 460
#extension GL_EXT_samplerless_texture_functions : require
#include "denoise/reblur_common.glsl"

layout(local_size_x = REBLUR_GROUP_SIZE, local_size_y = REBLUR_GROUP_SIZE) in;

layout(set = 1, binding = REBLUR_HISTORY_FIX_BINDING_INPUT) uniform texture2D inputImage;
layout(set = 1, binding = REBLUR_HISTORY_FIX_BINDING_FAST) uniform texture2D fastImage;
layout(set = 1, binding = REBLUR_HISTORY_FIX_BINDING_SURFACE) uniform utexture2D surfaces;
layout(set = 1, binding = REBLUR_HISTORY_FIX_BINDING_OUTPUT, rgba16f) uniform writeonly image2D outputImage;
layout(set = 1, binding = REBLUR_HISTORY_FIX_BINDING_SLOPE) uniform texture2D slopes;
layout(set = 1, binding = REBLUR_HISTORY_FIX_BINDING_FAST_MOMENTS, rgba32ui) uniform writeonly uimage2D fastMomentsOut;

DEFINE_REBLUR_NEIGHBOURHOOD(fastImage, surfaces)

vec3 fixHistory(ivec2 pixel, vec4 centre, float z, float slope, vec3 n) {
  float stride = pc.historyFixStride * (1.0 - (centre.a - 1.0) / pc.historyFixFrames);
  if (stride < 1.0) return centre.rgb;
  vec3 sum = centre.rgb * (1.0 + centre.a);
  float weightSum = 1.0 + centre.a;
  for (int dy = -2; dy <= 2; ++dy)
    for (int dx = -2; dx <= 2; ++dx) {
      if (dx == 0 && dy == 0) continue;
      vec2 offset = stride * vec2(dx, dy);
      ivec2 q = pixel + ivec2(round(offset));
      if (!inImage(q)) continue;
      float w = geometryWeight(z, slope, stride * length(vec2(dx, dy)), n, texelFetch(surfaces, q, 0).xy);
      if (w <= 0.0) continue;
      vec4 c = texelFetch(inputImage, q, 0);
      w *= 1.0 + c.a;
      sum += w * c.rgb;
      weightSum += w;
    }
  return sum / weightSum;
}

const int ANTI_FIREFLY_RADIUS = 4;

vec3 withoutFirefly(ivec2 pixel, vec3 colour, float z, float slope, vec3 n) {
  if (!(pc.antiFireflySigma > 0.0)) return colour;
  float m1 = 0.0, m2 = 0.0, count = 0.0;
  for (int dy = -ANTI_FIREFLY_RADIUS; dy <= ANTI_FIREFLY_RADIUS; ++dy)
    for (int dx = -ANTI_FIREFLY_RADIUS; dx <= ANTI_FIREFLY_RADIUS; ++dx) {
      if (abs(dx) <= 1 && abs(dy) <= 1) continue;
      ivec2 q = pixel + ivec2(dx, dy);
      if (!inImage(q)) continue;
      if (geometryWeight(z, slope, length(vec2(dx, dy)), n, texelFetch(surfaces, q, 0).xy) <= 0.0) continue;
      float l = reblurLuminance(texelFetch(inputImage, q, 0).rgb);
      m1 += l;
      m2 += l * l;
      count += 1.0;
    }
  if (count < 1.0) return colour;
  m1 /= count;
  float sigma = sqrt(max(m2 / count - m1 * m1, 0.0)) * pc.antiFireflySigma;
  float luminance = reblurLuminance(colour);
  float clamped = clamp(luminance, max(m1 - sigma, 0.0), m1 + sigma);
  return luminance > 0.0 ? colour * (clamped / luminance) : colour;
}

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (!inImage(pixel)) return;
  vec4 centre = texelFetch(inputImage, pixel, 0);
  vec4 s = unpackSurface(texelFetch(surfaces, pixel, 0).xy);
  if (!hasSurface(s.w)) {
    imageStore(outputImage, pixel, centre);
    imageStore(fastMomentsOut, pixel, uvec4(0u));
    return;
  }
  float slope = texelFetch(slopes, pixel, 0).r;
  float frames = centre.a;
  vec3 colour = frames < pc.historyFixFrames ? fixHistory(pixel, centre, s.w, slope, s.xyz) : centre.rgb;
  colour = withoutFirefly(pixel, colour, s.w, slope, s.xyz);
  vec3 mean, sigma;
  neighbourhood(pixel, s.w, slope, s.xyz, mean, sigma);
  imageStore(fastMomentsOut, pixel, packMoments(mean, sigma));
  vec3 clamped = clamp(colour, mean - pc.sigmaScale * sigma, mean + pc.sigmaScale * sigma);
  // How far the clamp moved the history, in the neighbourhood's standard deviations of luminance.
  float moved = abs(reblurLuminance(colour - clamped)) / max(reblurLuminance(sigma), 1e-6);
  frames = max(1.0, frames / (1.0 + pc.antilagSensitivity * moved));
  imageStore(outputImage, pixel, vec4(clamped, frames));
}
