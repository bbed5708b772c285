// Where a ray leaving a surface starts, so that it does not hit that surface again: the hit
// point moved along the geometric normal by a few float ulps of its coordinates, an offset that
// scales with the magnitude of the position (Wächter & Binder 2019, "A Fast and Robust Method
// for Avoiding Self-Intersection", Ray Tracing Gems, chapter 6). Near the origin, where ulps are
// tiny, a fixed small distance is used instead.
#ifndef BOUNCE_COMMON_RAY_OFFSET_GLSL
#define BOUNCE_COMMON_RAY_OFFSET_GLSL

// n: unit geometric normal on the side the ray leaves towards.
vec3 offsetRayOrigin(vec3 p, vec3 n) {
  const float nearOrigin = 1.0 / 32.0;
  const float fixedOffset = 1.0 / 65536.0;
  const float ulpScale = 256.0;
  ivec3 ulps = ivec3(ulpScale * n);
  // Moving the bit pattern by k steps moves the float k ulps away from zero; towards the
  // normal therefore means subtracting for negative coordinates.
  vec3 moved = intBitsToFloat(floatBitsToInt(p) + mix(ulps, -ulps, lessThan(p, vec3(0.0))));
  return mix(moved, p + fixedOffset * n, lessThan(abs(p), vec3(nearOrigin)));
}

#endif
