// svgf-atrous-N (Schied et al. 2017 §4.2; Dammertz et al. 2010): one edge-avoiding à-trous
// iteration, a 5x5 B3-spline kernel whose taps lie `step` = 2^N pixels apart (5 iterations:
// steps 1..16, a reach of 2 (1 + 2 + 4 + 8 + 16) = 62 pixels), or with SVGF_FLAG_KERNEL_3X3
// NRD RELAX's 3x3 Gaussian (9 taps instead of 25; 4 iterations reach 15 pixels). Each tap's
// weight is the kernel's times the edge stops (svgf_common.glsl): depth (relative to the
// surface's slope, svgf.slope from svgf-temporal), normal (cos^phiNormal) and luminance, whose
// scale is phiLuminance standard deviations of the centre's luminance, its variance first
// blurred by a 3x3 Gaussian (Schied eq. 5; with SVGF_FLAG_PREFILTER_FIRST_ONLY on iteration 0
// only, as RELAX), or with SVGF_FLAG_SHARED_LUMINANCE_STOP (the default) the geometric mean of
// that and the tap's standard deviation, so that a tap weighs the same from either side
// (SvgfLuminanceStop). The variance in alpha is filtered with the squared weights (Schied eq.
// 2), so later iterations stop at a smaller luminance difference. Iteration 0
// (SvgfSettings::feedbackIteration) writes svgf.illumination, next frame's colour history; the
// last multiplies the albedo back in (SVGF_FLAG_ALBEDO). Pixels without a surface pass through,
// and so do the 8x8 tiles the hybrid denoiser does not read SVGF on (SVGF_FLAG_TILES).
#version 460
#include "denoise/svgf_common.glsl"

layout(local_size_x = SVGF_GROUP_SIZE, local_size_y = SVGF_GROUP_SIZE) in;

layout(set = 1, binding = SVGF_ATROUS_BINDING_INPUT, rgba16f) uniform readonly image2D inputImage;
layout(set = 1, binding = SVGF_ATROUS_BINDING_SURFACE, rg32ui) uniform readonly uimage2D surfaces;
layout(set = 1, binding = SVGF_ATROUS_BINDING_ALBEDO, rgba16f) uniform readonly image2D albedos;
layout(set = 1, binding = SVGF_ATROUS_BINDING_OUTPUT, rgba16f) uniform writeonly image2D outputImage;
layout(set = 1, binding = SVGF_ATROUS_BINDING_TILES, rgba16f) uniform readonly image2D tiles;
layout(set = 1, binding = SVGF_ATROUS_BINDING_SLOPE, r32f) uniform readonly image2D slopes;

// The hybrid denoiser's tile classes (hybrid_classify.comp): a workgroup is one 8x8 tile.
bool tileSkipped() {
  return (pc.flags & SVGF_FLAG_TILES) != 0u && imageLoad(tiles, ivec2(gl_WorkGroupID.xy)).r == 0.0;
}

vec4 surfaceAt(ivec2 q) { return unpackSurface(imageLoad(surfaces, q).xy); }

// The centre's variance blurred by a 3x3 Gaussian (1/4, 1/2, 1/4) over pixels with a surface
// (those without carry SVGF_NO_SURFACE_VARIANCE).
float prefilteredVariance(ivec2 pixel) {
  float sum = 0.0, weightSum = 0.0;
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      ivec2 q = pixel + ivec2(dx, dy);
      if (!inImage(q)) continue;
      float variance = imageLoad(inputImage, q).a;
      if (variance < 0.0) continue;
      float w = (dx == 0 ? 0.5 : 0.25) * (dy == 0 ? 0.5 : 0.25);
      sum += w * variance;
      weightSum += w;
    }
  return sum / weightSum;  // the centre has a surface: weightSum >= 1/4
}

// What every tap is weighed against: the centre pixel's surface, luminance and stop scales.
struct Centre {
  vec4 surface;     // normal xyz, depth w
  float luminance;
  float deviation;  // the standard deviation of its luminance (prefiltered variance)
  float inversePhiL;  // 1 / the luminance stop's scale (the centre's alone)
  float slope;      // its depth change per pixel
};

// The kernel-weighted, edge-stopped sums of the taps (Schied eq. 1-2).
struct TapSums {
  vec3 colour;
  float variance;
  float weight;
};

// Adds the tap `kernelOffset` kernel steps from `pixel`, of kernel weight `kernelWeight`.
void addTap(ivec2 pixel, ivec2 kernelOffset, float kernelWeight, Centre centre,
            inout TapSums sums) {
  ivec2 offset = int(pc.step) * kernelOffset;
  ivec2 q = pixel + offset;
  if (!inImage(q)) return;
  uvec2 packed = imageLoad(surfaces, q).xy;
  if (!hasSurface(surfaceDepthOf(packed))) return;
  vec4 sq = unpackSurface(packed);
  vec4 c = imageLoad(inputImage, q);
  float inversePhiL = (pc.flags & SVGF_FLAG_SHARED_LUMINANCE_STOP) != 0u
                          ? inversesqrt(max(centre.deviation * sqrt(max(c.a, 0.0)), 1e-20)) /
                                pc.phiLuminance
                          : centre.inversePhiL;
  float distance = float(pc.step) * length(vec2(kernelOffset));
  float w = kernelWeight * edgeStopWeight(centre.surface.w, sq.w, centre.slope, distance,
                                          centre.surface.xyz, sq.xyz, centre.luminance,
                                          svgfLuminance(c.rgb), inversePhiL);
  sums.colour += w * c.rgb;
  sums.variance += w * w * c.a;
  sums.weight += w;
}

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (!inImage(pixel)) return;
  vec4 colourVariance = imageLoad(inputImage, pixel);
  vec4 s = surfaceAt(pixel);
  // A skipped tile copies: the feedback iteration's copy is the colour history, and others of
  // neighbouring tiles read finite values.
  if (!hasSurface(s.w) || tileSkipped()) {
    if (pc.lastIteration != 0u && colourVariance.a < 0.0)
      colourVariance.a = 0.0;  // SVGF_NO_SURFACE_VARIANCE
    imageStore(outputImage, pixel, colourVariance);
    return;
  }
  Centre centre;
  centre.surface = s;
  centre.luminance = svgfLuminance(colourVariance.rgb);
  bool prefilter = pc.iteration == 0u || (pc.flags & SVGF_FLAG_PREFILTER_FIRST_ONLY) == 0u;
  centre.deviation = sqrt(max(prefilter ? prefilteredVariance(pixel) : colourVariance.a, 0.0));
  centre.inversePhiL = 1.0 / (pc.phiLuminance * centre.deviation + 1e-10);
  centre.slope = imageLoad(slopes, pixel).r;  // svgf-temporal's depthSlope
  // Two loops of constant bounds rather than one of a variable radius, so that each unrolls.
  TapSums sums;
  if ((pc.flags & SVGF_FLAG_KERNEL_3X3) != 0u) {
    float k0 = gaussian3(0) * gaussian3(0);
    sums = TapSums(k0 * colourVariance.rgb, k0 * k0 * colourVariance.a, k0);
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx)
        if (dx != 0 || dy != 0)
          addTap(pixel, ivec2(dx, dy), gaussian3(dx) * gaussian3(dy), centre, sums);
  } else {
    float k0 = b3(0) * b3(0);
    sums = TapSums(k0 * colourVariance.rgb, k0 * k0 * colourVariance.a, k0);
    for (int dy = -2; dy <= 2; ++dy)
      for (int dx = -2; dx <= 2; ++dx)
        if (dx != 0 || dy != 0) addTap(pixel, ivec2(dx, dy), b3(dx) * b3(dy), centre, sums);
  }
  vec3 colour = sums.colour / sums.weight;
  if (pc.lastIteration != 0u && (pc.flags & SVGF_FLAG_ALBEDO) != 0u)
    colour *= safeAlbedo(imageLoad(albedos, pixel).rgb);
  imageStore(outputImage, pixel, vec4(colour, sums.variance / (sums.weight * sums.weight)));
}
