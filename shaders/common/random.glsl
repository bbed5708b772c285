// Deterministic random numbers from a hash of (pixel, frame, purpose) (DESIGN.md §1): no state
// is carried between passes, so any pass can draw the numbers it needs and a fixed seed gives
// the same image. pcg3d is from Jarzynski & Olano 2020, "Hash Functions for GPU Rendering"
// (JCGT 9(3)), chosen there for its quality/speed balance.
#ifndef BOUNCE_COMMON_RANDOM_GLSL
#define BOUNCE_COMMON_RANDOM_GLSL

uvec3 pcg3d(uvec3 v) {
  v = v * 1664525u + 1013904223u;
  v.x += v.y * v.z;
  v.y += v.z * v.x;
  v.z += v.x * v.y;
  v ^= v >> 16u;
  v.x += v.y * v.z;
  v.y += v.z * v.x;
  v.z += v.x * v.y;
  return v;
}

// Purposes keep the streams of different uses independent.
const uint RANDOM_BENCH_DIFFUSE = 1u;
const uint RANDOM_BENCH_SUN = 2u;

// Two uniform numbers in [0, 1) for (pixel, frame, purpose).
vec2 random2(uvec2 pixel, uint frame, uint purpose) {
  uvec3 h = pcg3d(uvec3(pixel.x, pixel.y, frame * 0x9E3779B9u + purpose * 0x85EBCA6Bu));
  return vec2(h.xy >> 8u) * (1.0 / 16777216.0);
}

// The four-dimensional variant from the same paper, for keys with more than three parts.
uvec4 pcg4d(uvec4 v) {
  v = v * 1664525u + 1013904223u;
  v.x += v.y * v.w;
  v.y += v.z * v.x;
  v.z += v.x * v.y;
  v.w += v.y * v.z;
  v ^= v >> 16u;
  v.x += v.y * v.w;
  v.y += v.z * v.x;
  v.z += v.x * v.y;
  v.w += v.y * v.z;
  return v;
}

// Four uniform numbers in [0, 1) from the 24 high bits of each hash word.
vec4 uniformFromHash(uvec4 h) {
  return vec4(h >> 8u) * (1.0 / 16777216.0);
}

#endif
