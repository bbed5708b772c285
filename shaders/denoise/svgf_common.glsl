// What the SVGF passes share (src/denoise/svgf.h, shared/svgf_io.h): the surface each pixel keeps
// in svgf.surface, its depth gradient, and the edge-stopping weights of Schied et al. 2017 §4.2.
// src/denoise/svgf_reference.cpp is the same arithmetic on the CPU.
#ifndef BOUNCE_DENOISE_SVGF_COMMON_GLSL
#define BOUNCE_DENOISE_SVGF_COMMON_GLSL
#include "denoise/packed_surface.glsl"
#include "shared/svgf_io.h"

layout(push_constant, scalar) uniform Push { SvgfConstants pc; };

layout(buffer_reference, scalar, buffer_reference_align = 4) buffer SvgfVarianceTiles {
  SvgfVarianceTilesHeader header;
  uint tiles[];  // x | y << 16
};

bool isFiniteValue(float v) { return !isnan(v) && !isinf(v); }
vec3 finiteOrZero(vec3 v) { return any(isnan(v)) || any(isinf(v)) ? vec3(0.0) : v; }

float svgfLuminance(vec3 c) { return dot(c, vec3(SVGF_LUMINANCE_R, SVGF_LUMINANCE_G, SVGF_LUMINANCE_B)); }

// A depth that means a surface (the caller's contract: 0, negative or non-finite is the sky).
bool hasSurface(float depth) { return depth > 0.0 && isFiniteValue(depth); }

bool inImage(ivec2 p) { return all(greaterThanEqual(p, ivec2(0))) && all(lessThan(p, ivec2(pc.resolution))); }


// The albedo the signal is divided by: never below 1/1000, so black texels do not blow it up
// (their remodulated value is ~0 anyway).
vec3 safeAlbedo(vec3 albedo) { return max(albedo, vec3(1e-3)); }

// The B3-spline weight at offset -2..2 (Schied §4.2).
float b3(int offset) {
  int a = abs(offset);
  return a == 0 ? SVGF_KERNEL_0 : a == 1 ? SVGF_KERNEL_1 : SVGF_KERNEL_2;
}

// RELAX's 3x3 Gaussian weight at offset -1..1 (SvgfKernel::Gaussian3x3).
float gaussian3(int offset) { return offset == 0 ? SVGF_GAUSSIAN_0 : SVGF_GAUSSIAN_1; }

// Per-pixel view-depth change along x and y: of the two one-sided differences the smaller one
// (a difference across a depth edge is not the surface's slope); 0 where no neighbour has a
// surface. `depthAt` returns 0 for no surface.
#define DEFINE_DEPTH_GRADIENT(depthAt)                                      \
  float oneSidedSlope(ivec2 pixel, ivec2 axis, float z) {                   \
    float best = 0.0;                                                       \
    bool found = false;                                                     \
    for (int s = -1; s <= 1; s += 2) {                                      \
      ivec2 q = pixel + s * axis;                                           \
      if (!inImage(q)) continue;                                            \
      float zq = depthAt(q);                                                \
      if (!hasSurface(zq)) continue;                                        \
      float d = abs(zq - z);                                                \
      best = found ? min(best, d) : d;                                      \
      found = true;                                                         \
    }                                                                       \
    return best;                                                            \
  }                                                                         \
  float depthSlope(ivec2 pixel, float z) {                                  \
    return length(vec2(oneSidedSlope(pixel, ivec2(1, 0), z), oneSidedSlope(pixel, ivec2(0, 1), z))); \
  }

// The edge-stopping weight of a tap at `offset` pixels (Schied eq. 3-5, with Falcor's depth term
// |grad z| |offset|, which stays tolerant across a slanted plane in any direction): depth,
// normal and luminance, the last relative to the (prefiltered) standard deviation of the
// centre's luminance.
float edgeStopWeight(float z, float zq, float slope, float distance, vec3 n, vec3 nq, float l,
                     float lq, float inversePhiL) {
  // 1e-3 z: the depth rounding of a plane facing the camera, whose slope is 0.
  float wz = abs(z - zq) / (pc.phiDepth * slope * distance + 1e-3 * z);
  float wl = abs(l - lq) * inversePhiL;
  // exp(-wz - wl) max(0, n.n_q)^phiNormal as one exp2 (a normal at 90 degrees or more: log2 of
  // 1e-30 = -100, so the weight underflows to 0 for any phiNormal >= 1).
  float logNormal = pc.phiNormal * log2(max(dot(n, nq), 1e-30));
  return exp2(logNormal - 1.4426950 * (wz + wl));
}

#endif
