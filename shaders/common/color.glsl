// Colour helpers for debug views.
#ifndef BOUNCE_COMMON_COLOR_GLSL
#define BOUNCE_COMMON_COLOR_GLSL

// The display value v (sRGB-encoded) as linear, so that writing it to an sRGB PNG shows v.
vec3 displayToLinear(vec3 v) {
  v = clamp(v, 0.0, 1.0);
  return mix(v / 12.92, pow((v + 0.055) / 1.055, vec3(2.4)), greaterThan(v, vec3(0.04045)));
}

// A well-spread colour per integer id (for id debug views).
vec3 idColor(uint id) {
  uint h = id * 0x9E3779B1u;
  h ^= h >> 15;
  h *= 0x85EBCA77u;
  h ^= h >> 13;
  return vec3(float(h & 0xFFu), float((h >> 8) & 0xFFu), float((h >> 16) & 0xFFu)) / 255.0 * 0.8 + 0.2;
}

#endif
