// A denoiser's per-pixel surface in 8 bytes (RG32UI): x the view depth's bits (0: none, written
// as uvec2(0)), y the
// unit normal, octahedral, as two snorm16. svgf.surface and reblur.surface keep it; their
// filters read it at every tap, where RGBA32F's 16 bytes cost a third of SVGF's à-trous
// (docs/decisions.md). Unpacked as vec4(normal, depth). src/denoise/svgf.cpp's packSvgfSurface
// is the same on the CPU.
#ifndef BOUNCE_DENOISE_PACKED_SURFACE_GLSL
#define BOUNCE_DENOISE_PACKED_SURFACE_GLSL

// Octahedral decoding (Cigolle et al. 2014), as Bounce's gbuffer.normals are written.
vec3 decodeOctahedralNormal(vec2 e) {
  vec3 n = vec3(e, 1.0 - abs(e.x) - abs(e.y));
  if (n.z < 0.0) n.xy = (1.0 - abs(n.yx)) * vec2(n.x >= 0.0 ? 1.0 : -1.0, n.y >= 0.0 ? 1.0 : -1.0);
  return normalize(n);
}

// Octahedral encoding, decodeOctahedralNormal's inverse.
vec2 encodeOctahedralNormal(vec3 n) {
  n /= abs(n.x) + abs(n.y) + abs(n.z);
  if (n.z < 0.0) n.xy = (1.0 - abs(n.yx)) * vec2(n.x >= 0.0 ? 1.0 : -1.0, n.y >= 0.0 ? 1.0 : -1.0);
  return n.xy;
}

uvec2 packSurface(vec3 n, float depth) {
  return uvec2(floatBitsToUint(depth), packSnorm2x16(encodeOctahedralNormal(n)));
}
vec4 unpackSurface(uvec2 packed) {
  return vec4(decodeOctahedralNormal(unpackSnorm2x16(packed.y)), uintBitsToFloat(packed.x));
}
float surfaceDepthOf(uvec2 packed) { return uintBitsToFloat(packed.x); }

#endif
