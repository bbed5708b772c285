// gi10-filter-gi (§1.2 #26, §1.7 "FilterGI"): a separable bilateral blur, run twice (x, then
// y), only where the history is short: radius max(8 - N, 0) / 2 pixels for history length N
// (Capsaicin's blur mask, without its 9x9 dilation and sample budget). Weights: depth
// exp2(-200 |1 - z_c / z|), normal (n . n_c)^4. Elsewhere the pixel passes through.
#version 460
#include "gi/gi10/gi10_common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(push_constant, scalar) uniform Push { Gi10PassConstants pc; };
layout(set = 1, binding = GI10_FILTER_BINDING_INPUT, rgba16f) uniform readonly image2D inputImage;
layout(set = 1, binding = GI10_FILTER_BINDING_HISTORY, rgba16f) uniform readonly image2D historyImage;
layout(set = 1, binding = GI10_FILTER_BINDING_NORMALS, rgba16f) uniform readonly image2D normals;
layout(set = 1, binding = GI10_FILTER_BINDING_DEPTH, r32f) uniform readonly image2D depths;
layout(set = 1, binding = GI10_FILTER_BINDING_OUTPUT, rgba16f) uniform writeonly image2D outputImage;

void main() {
  FrameConstants f = FrameBlock(pc.frame).v;
  Gi10Constants k = Gi10ConstantsRef(pc.gi10).v;
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(pixel), f.resolution))) return;
  vec4 centre = imageLoad(inputImage, pixel);
  float depth = imageLoad(depths, pixel).x;
  float historyLength = imageLoad(historyImage, pixel).w;
  int radius = int(max(8.0 - historyLength, 0.0) * 0.5);
  if ((k.flags & GI10_FLAG_FILTER) == 0u || radius == 0 || !(depth > 0.0)) {
    imageStore(outputImage, pixel, centre);
    return;
  }
  vec3 n = decodeOctahedral(imageLoad(normals, pixel).xy);
  ivec2 axis = pc.axis == 0u ? ivec2(1, 0) : ivec2(0, 1);
  vec3 sum = centre.rgb;
  float weightSum = 1.0;
  for (int i = -radius; i <= radius; ++i) {
    if (i == 0) continue;
    ivec2 q = pixel + i * axis;
    if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(uvec2(q), f.resolution))) continue;
    float z = imageLoad(depths, q).x;
    if (!(z > 0.0)) continue;
    float nDot = max(dot(n, decodeOctahedral(imageLoad(normals, q).xy)), 0.0);
    float w = exp2(-200.0 * abs(1.0 - depth / z)) * nDot * nDot * nDot * nDot;
    sum += w * imageLoad(inputImage, q).rgb;
    weightSum += w;
  }
  imageStore(outputImage, pixel, vec4(sum / weightSum, centre.w));
}
