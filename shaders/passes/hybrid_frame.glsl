// What every pass of the hybrid frame shares: the frame constants (shared/hybrid_frame_io.h),
// GBuffer encodings, the camera ray through a pixel and the sky seen in a direction.
#ifndef BOUNCE_PASSES_HYBRID_FRAME_GLSL
#define BOUNCE_PASSES_HYBRID_FRAME_GLSL
#include "common/sky.glsl"
#include "shared/hybrid_frame_io.h"

layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer FrameBlock {
  FrameConstants v;
};

// Octahedral normal encoding (Cigolle et al. 2014, "A Survey of Efficient Representations for
// Independent Unit Vectors", JCGT 3(2)): two numbers in [-1, 1], no singularity.
vec2 signNotZero(vec2 v) { return vec2(v.x >= 0.0 ? 1.0 : -1.0, v.y >= 0.0 ? 1.0 : -1.0); }

vec2 encodeOctahedral(vec3 n) {
  vec2 p = n.xy / (abs(n.x) + abs(n.y) + abs(n.z));
  return n.z <= 0.0 ? (1.0 - abs(p.yx)) * signNotZero(p) : p;
}

vec3 decodeOctahedral(vec2 e) {
  vec3 n = vec3(e, 1.0 - abs(e.x) - abs(e.y));
  if (n.z < 0.0) n.xy = (1.0 - abs(n.yx)) * signNotZero(n.xy);
  return normalize(n);
}

// The primary ray through screen position `pixel` (pixel + 0.5 for a pixel's centre) shifted by
// the frame's sub-pixel jitter (FrameConstants::jitter, 0 without anti-aliasing): the ray the
// vbuffer sees the pixel's surface along, so every pass that rebuilds a position from a pixel
// and a depth finds that surface.
vec3 pixelRayDirection(FrameConstants f, vec2 pixel) {
  return cameraRayDirection(f.camera, pixel + f.jitter, vec2(f.resolution));
}

// The world position seen at `pixel` with view depth `depth`.
vec3 positionFromDepth(FrameConstants f, vec2 pixel, float depth) {
  vec3 dir = pixelRayDirection(f, pixel);
  return f.camera.position + dir * (depth / dot(dir, f.camera.forward));
}

// Sky radiance towards `direction` (unit): the scene's constant sky or the daylight model.
vec3 skyRadianceToward(FrameConstants f, vec3 direction) {
  if (f.skyModel == FRAME_SKY_DAYLIGHT)
    return daylightSky(direction, f.towardSun, f.skyTurbidity) * f.skyScale;
  return f.skyRadiance;
}

bool isFiniteValue(float v) { return !isnan(v) && !isinf(v); }

// Purposes of the hybrid frame's random numbers (common/random.glsl), apart from other users'.
const uint RANDOM_SUN_CONE = 0x48590001u;

#endif
