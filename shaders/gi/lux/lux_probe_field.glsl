// Lux's probe field (seed 002, "a 32^3-voxel probe grid"; gi10_lux_denoisers.md §2.3(c)): the
// cells of Evolve's clipmap cache, each a 32^3 cascade's voxel holding L1 SH of the incoming
// radiance (cache-build-sh). The point's own cell (the finest cascade holding it, as every
// cache lookup chooses) gives the radiance arriving from each direction: the target of
// lux-candidates.
#ifndef BOUNCE_GI_LUX_PROBE_FIELD_GLSL
#define BOUNCE_GI_LUX_PROBE_FIELD_GLSL
#include "common/sh.glsl"
#include "gi/evolve/cache/cache_lookup.glsl"

// The SH of the probe serving (position, normal): one lookup with the cache's jitter, marking
// the cell used and allocating a missing one, as cacheLookupIrradiance() does. False where no
// cell with SH serves the point yet (then there is no target: lux-candidates samples the cosine).
struct ProbeSh {
  vec4 r, g, b;
};

bool luxProbeSh(ClipmapCacheView cache, vec3 position, vec3 normal, uint randomSeed,
                out ProbeSh sh) {
  vec2 jitter = uniformFromHash(pcg4d(uvec4(randomSeed, 0x1B873593u, 0xCC9E2D51u, 7u))).xy - 0.5;
  uint cascade;
  uint value = clipmapFindCell(cache, position, normal, jitter, CLIPMAP_TOUCH_DIRECT, true, cascade);
  sh.r = sh.g = sh.b = vec4(0.0);
  if (value == 0u) return false;
  uint cell = value - 1u;
  sh.r = cache.cells.v[cell].shR;
  sh.g = cache.cells.v[cell].shG;
  sh.b = cache.cells.v[cell].shB;
  return clipmapFinite(sh.r.xyz) && clipmapFinite(sh.g.xyz) && clipmapFinite(sh.b.xyz) &&
         clipmapFinite(vec3(sh.r.w, sh.g.w, sh.b.w));
}

// Luminance of the probe's incoming radiance from direction d (L1 SH; may ring negative).
float luxProbeLuminance(ProbeSh sh, vec3 d) {
  vec4 y = shBasisL1(d);
  return clipmapLuminance(vec3(dot(sh.r, y), dot(sh.g, y), dot(sh.b, y)));
}

// Luminance of the probe's mean radiance over the sphere (the SH's constant term).
float luxProbeMeanLuminance(ProbeSh sh) {
  return clipmapLuminance(vec3(sh.r.x, sh.g.x, sh.b.x)) * 0.282095;
}

vec3 luxProbeIrradianceOverPi(ProbeSh sh, vec3 n) {
  return vec3(shIrradianceOverPi(sh.r, n), shIrradianceOverPi(sh.g, n), shIrradianceOverPi(sh.b, n));
}

#endif
