// svgf-variance (Schied et al. 2017 §4.1 "variance estimation"; Falcor SVGFPass "FilterMoments"):
// the luminance variance that steers the à-trous luminance edge stop, in alpha beside the colour.
//   - A history of at least varianceHistoryFrames frames (4, as the paper): the temporal
//     moments, variance = mu2 - mu1^2.
//   - A shorter one (a reset, a disocclusion): too few frames for a temporal estimate, so the
//     moments and the colour are averaged over the 7x7 block of pixels on the same surface
//     (depth and normal edge stops; no luminance stop, which would reject the very noise being
//     measured) and the variance is scaled by 4 / history length, as Falcor does, so that the
//     first à-trous iterations blur a young history more.
// svgf-temporal wrote the first case, and the pixels without a surface (variance
// SVGF_NO_SURFACE_VARIANCE); this pass runs on the 8x8 tiles it listed (svgf.variance-tiles,
// an indirect dispatch) and estimates the second.
#version 460
#include "denoise/svgf_common.glsl"

layout(local_size_x = SVGF_GROUP_SIZE, local_size_y = SVGF_GROUP_SIZE) in;

layout(set = 1, binding = SVGF_VARIANCE_BINDING_ACCUMULATED, rgba16f) uniform readonly image2D accumulated;
layout(set = 1, binding = SVGF_VARIANCE_BINDING_MOMENTS, rgba32f) uniform readonly image2D moments;
layout(set = 1, binding = SVGF_VARIANCE_BINDING_SURFACE, rg32ui) uniform readonly uimage2D surfaces;
layout(set = 1, binding = SVGF_VARIANCE_BINDING_OUTPUT, rgba16f) uniform writeonly image2D outputImage;
layout(set = 1, binding = SVGF_VARIANCE_BINDING_SLOPE, r32f) uniform readonly image2D slopes;

vec4 surfaceAt(ivec2 q) { return unpackSurface(imageLoad(surfaces, q).xy); }

const int SPATIAL_RADIUS = 3;  // 7x7

void main() {
  uint tile = SvgfVarianceTiles(pc.varianceTiles).tiles[gl_WorkGroupID.x];
  ivec2 pixel = ivec2(tile & 0xFFFFu, tile >> 16u) * int(SVGF_GROUP_SIZE) +
                ivec2(gl_LocalInvocationID.xy);
  if (!inImage(pixel)) return;
  vec4 s = surfaceAt(pixel);
  if (!hasSurface(s.w)) return;
  float frames = imageLoad(moments, pixel).z;
  if (frames >= float(pc.varianceHistoryFrames)) return;
  float slope = imageLoad(slopes, pixel).r;  // svgf-temporal's depthSlope
  vec3 colourSum = vec3(0.0);
  vec2 momentSum = vec2(0.0);
  float weightSum = 0.0;
  for (int dy = -SPATIAL_RADIUS; dy <= SPATIAL_RADIUS; ++dy)
    for (int dx = -SPATIAL_RADIUS; dx <= SPATIAL_RADIUS; ++dx) {
      ivec2 q = pixel + ivec2(dx, dy);
      if (!inImage(q)) continue;
      uvec2 packed = imageLoad(surfaces, q).xy;
      if (!hasSurface(surfaceDepthOf(packed))) continue;
      vec4 sq = unpackSurface(packed);
      // The luminance term off: phiL infinite.
      float w = edgeStopWeight(s.w, sq.w, slope, length(vec2(dx, dy)), s.xyz, sq.xyz, 0.0, 0.0, 1.0);
      colourSum += w * imageLoad(accumulated, q).rgb;
      momentSum += w * imageLoad(moments, q).xy;
      weightSum += w;
    }
  // The centre's own weight is 1, so weightSum >= 1.
  momentSum /= weightSum;
  float variance = max(momentSum.y - momentSum.x * momentSum.x, 0.0) * 4.0 / max(frames, 1.0);
  imageStore(outputImage, pixel, vec4(colourSum / weightSum, variance));
}
