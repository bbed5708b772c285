// L1 spherical harmonics of radiance, one vec4 of coefficients per colour channel, in the
// order (Y00, Y1-1, Y10, Y11) = (constant, y, z, x). Shared by the clipmap cache's cells
// (cache-build-sh, the lookup) and ReSTIR GI's resolve.
#ifndef BOUNCE_COMMON_SH_GLSL
#define BOUNCE_COMMON_SH_GLSL

// The L1 basis at unit direction d: 1 / (2 sqrt pi) and sqrt(3 / (4 pi)) times (y, z, x).
vec4 shBasisL1(vec3 d) {
  return vec4(0.282095, 0.488603 * d.y, 0.488603 * d.z, 0.488603 * d.x);
}

// Irradiance / pi for normal n from L1 SH of radiance: the clamped-cosine convolution
// (Ramamoorthi & Hanrahan 2001: A0 = pi, A1 = 2 pi / 3), divided by pi, clamped at zero (L1
// rings negative opposite a bright direction).
float shIrradianceOverPi(vec4 sh, vec3 n) {
  return max(0.0, dot(sh * vec4(1.0, 2.0 / 3.0, 2.0 / 3.0, 2.0 / 3.0), shBasisL1(n)));
}

#endif
