// What the ReBLUR passes share (src/denoise/reblur.h, shared/reblur_io.h): the surface each pixel
// keeps in reblur.surface, the geometry weights of the blurs, reprojection of a history with
// disocclusion tests, and the neighbourhood statistics of the clamps.
#ifndef BOUNCE_DENOISE_REBLUR_COMMON_GLSL
#define BOUNCE_DENOISE_REBLUR_COMMON_GLSL
#include "denoise/packed_surface.glsl"
#include "shared/reblur_io.h"

layout(push_constant, scalar) uniform Push { ReblurConstants pc; };

bool isFiniteValue(float v) { return !isnan(v) && !isinf(v); }
vec3 finiteOrZero(vec3 v) { return any(isnan(v)) || any(isinf(v)) ? vec3(0.0) : v; }
vec4 finiteOrZero4(vec4 v) { return any(isnan(v)) || any(isinf(v)) ? vec4(0.0) : v; }

float reblurLuminance(vec3 c) { return dot(c, vec3(0.2126, 0.7152, 0.0722)); }

// A depth that means a surface (the caller's contract: 0, negative or non-finite is the sky).
bool hasSurface(float depth) { return depth > 0.0 && isFiniteValue(depth); }

bool inImage(ivec2 p) { return all(greaterThanEqual(p, ivec2(0))) && all(lessThan(p, ivec2(pc.resolution))); }

vec3 safeAlbedo(vec3 albedo) { return max(albedo, vec3(1e-3)); }

// 8 taps of a Poisson-like disk in the unit disk (placed by hand for Bounce: no two closer than
// 0.5, mean radius 0.78), rotated per pixel and frame by an interleaved-gradient-noise angle
// (Jimenez 2014) so that the taps' pattern does not print into the image.
const vec2 kPoisson[8] = vec2[8](vec2(-0.37, 0.25), vec2(0.43, 0.61), vec2(0.09, -0.52),
                                 vec2(0.80, -0.07), vec2(-0.68, -0.53), vec2(-0.22, 0.92),
                                 vec2(0.52, -0.78), vec2(-0.95, 0.12));

mat2 tapRotation(ivec2 pixel, uint salt) {
  vec2 p = vec2(pixel) + 5.588238 * float((pc.frame + salt) & 63u);
  float angle = 6.2831853 * fract(52.9829189 * fract(dot(p, vec2(0.06711056, 0.00583715))));
  float c = cos(angle), s = sin(angle);
  return mat2(c, s, -s, c);
}

// The geometry weight of a tap on surface (nq, zq) for a centre on (n, z) `distance` pixels away
// (NRD's blurs weigh by plane distance and normal, not by luminance, so the mean is kept on
// noisy input): the depth must follow the centre's plane within depthTolerance (relative), the
// plane's depth change over the distance given by its slope per pixel; normals weigh
// max(0, n.n_q)^normalPower.
// The weight is the product of planeWeight and normalWeight.
float planeWeight(float z, float slope, float distance, float zq) {
  if (!hasSurface(zq)) return 0.0;
  float allowed = pc.depthTolerance * z + slope * distance;
  float dz = abs(zq - z) / max(allowed, 1e-6);
  return max(0.0, 1.0 - dz * dz);
}
float normalWeight(vec3 n, vec3 nq) { return pow(max(dot(n, nq), 0.0), pc.normalPower); }

// The geometry weight of a tap whose surface is reblur.surface's packed `q`.
float geometryWeight(float z, float slope, float distance, vec3 n, uvec2 q) {
  return planeWeight(z, slope, distance, surfaceDepthOf(q)) * normalWeight(n, unpackSurface(q).xyz);
}

// The view-depth change per pixel along the surface: the smaller one-sided difference on each
// axis (a difference across a depth edge is not the surface's slope). `depthAt` returns 0 for
// no surface.
#define DEFINE_REBLUR_DEPTH_SLOPE(depthAt)                                   \
  float oneSidedSlope(ivec2 pixel, ivec2 axis, float z) {                   \
    float best = 1e30;                                                      \
    for (int s = -1; s <= 1; s += 2) {                                      \
      ivec2 q = pixel + s * axis;                                           \
      if (!inImage(q)) continue;                                            \
      float zq = depthAt(q);                                                \
      if (hasSurface(zq)) best = min(best, abs(zq - z));                    \
    }                                                                       \
    return best < 1e30 ? best : 0.0;                                        \
  }                                                                         \
  float depthSlope(ivec2 pixel, float z) {                                  \
    return length(vec2(oneSidedSlope(pixel, ivec2(1, 0), z), oneSidedSlope(pixel, ivec2(0, 1), z))); \
  }

// The fast history's neighbourhood statistics as reblur.fast-moments keeps them (6 halves; w
// 1: the pixel has a surface, which reblur-stabilize reads instead of reblur.surface).
uvec4 packMoments(vec3 mean, vec3 sigma) {
  return uvec4(packHalf2x16(mean.rg), packHalf2x16(vec2(mean.b, sigma.r)), packHalf2x16(sigma.gb), 1u);
}
void unpackMoments(uvec4 packed, out vec3 mean, out vec3 sigma) {
  vec2 a = unpackHalf2x16(packed.x), b = unpackHalf2x16(packed.y), c = unpackHalf2x16(packed.z);
  mean = vec3(a, b.x);
  sigma = vec3(b.y, c);
}

// Whether last frame's surface `s` (reblur.surface unpacked: normal, depth) is this pixel's.
bool sameSurface(vec4 s, float z, float slope, vec3 n) {
  return hasSurface(s.w) && abs(s.w - z) <= pc.depthTolerance * z + 2.0 * slope &&
         dot(s.xyz, n) >= pc.normalTolerance;
}

// The bilinear footprint of last frame's position `previous` (in pixels): its top-left pixel p0
// and the weights of the 4 pixels p0 + (i & 1, i >> 1).
vec4 bilinearFootprint(vec2 previous, out ivec2 p0) {
  vec2 base = previous - 0.5;
  p0 = ivec2(floor(base));
  vec2 f = base - vec2(p0);
  return vec4((1.0 - f.x) * (1.0 - f.y), f.x * (1.0 - f.y), (1.0 - f.x) * f.y, f.x * f.y);
}

// Bilinear reprojection of a history image (rgba, its alpha a frame count) to this pixel's
// surface, each of the 4 last-frame pixels only where its surface agrees (bit i of `agreeing`);
// returns weight 0 when none does (a disocclusion). reblur-temporal tests the surfaces and keeps
// the bits in reblur.footprint, which reblur-stabilize reprojects its own history with.
#define DEFINE_REBLUR_REPROJECT(previousSurfaceImage)                                        \
  float reprojectWeights(vec2 previous, float z, float slope, vec3 n, out ivec2 p0, out vec4 w, \
                         out uint agreeing) {                                                \
    w = bilinearFootprint(previous, p0);                                                     \
    float sum = 0.0;                                                                         \
    agreeing = 0u;                                                                           \
    for (int i = 0; i < 4; ++i) {                                                            \
      ivec2 q = p0 + ivec2(i & 1, i >> 1);                                                   \
      if (w[i] <= 0.0 || !inImage(q) || !sameSurface(unpackSurface(texelFetch(previousSurfaceImage, q, 0).xy), z, slope, n)) \
        w[i] = 0.0;                                                                          \
      else                                                                                   \
        agreeing |= 1u << i;                                                                 \
      sum += w[i];                                                                           \
    }                                                                                        \
    return sum;                                                                              \
  }

// Mean and standard deviation (per channel) of an image's rgb over the 3x3 pixels on this
// pixel's surface: the neighbourhood the slow histories are clamped to (NRD's fast-history
// clamping, sigma scale pc.sigmaScale).
#define DEFINE_REBLUR_NEIGHBOURHOOD(image, surfaceImage)                                    \
  void neighbourhood(ivec2 pixel, float z, float slope, vec3 n, out vec3 mean, out vec3 sigma) { \
    vec3 m1 = vec3(0.0), m2 = vec3(0.0);                                                     \
    float count = 0.0;                                                                       \
    for (int dy = -1; dy <= 1; ++dy)                                                         \
      for (int dx = -1; dx <= 1; ++dx) {                                                     \
        ivec2 q = pixel + ivec2(dx, dy);                                                     \
        if (!inImage(q)) continue;                                                           \
        if (geometryWeight(z, slope, length(vec2(dx, dy)), n, texelFetch(surfaceImage, q, 0).xy) <= 0.0) \
          continue;                                                                          \
        vec3 c = texelFetch(image, q, 0).rgb;                                                \
        m1 += c;                                                                             \
        m2 += c * c;                                                                         \
        count += 1.0;                                                                        \
      }                                                                                      \
    mean = m1 / max(count, 1.0);                                                             \
    sigma = sqrt(max(m2 / max(count, 1.0) - mean * mean, vec3(0.0)));                        \
  }

#endif
