// The reservoirs gi-restir-resolve reads for a render-resolution pixel, shared with
// gi-trace-resolve-visibility, which tests their visibility first: both must pick the same
// ones. The including shader declares the reservoir images `reservoirOrigin` and
// `reservoirNormals`.
#ifndef BOUNCE_GI_EVOLVE_RESOLVE_SAMPLES_GLSL
#define BOUNCE_GI_EVOLVE_RESOLVE_SAMPLES_GLSL
#include "gi/evolve/restir/restir_gi_common.glsl"
#include "common/random.glsl"

const uint RANDOM_GI_RESOLVE = 0x47490004u;

bool reservoirOnSurface(RestirGiConstants gi, PrimaryVertex x, ivec2 q) {
  vec4 origin = texelFetch(reservoirOrigin, q, 0);
  vec3 originNormal = decodeOctahedral(texelFetch(reservoirNormals, q, 0).xy);
  return uint(origin.w + 0.5) != RESTIR_GI_KIND_NONE && sameSurface(gi, x, origin.xyz, originNormal);
}

// The GI pixel whose reservoir this pixel starts from: the one under it, else the first of its
// neighbours towards this pixel (horizontal, vertical, diagonal) whose reservoir is on this
// pixel's surface, else the one under it.
ivec2 homeGiPixel(FrameConstants f, RestirGiConstants gi, ivec2 pixel, PrimaryVertex x) {
  ivec2 home = min(pixel / int(gi.divisor), ivec2(gi.giResolution) - 1);
  if (gi.divisor == 1u || reservoirOnSurface(gi, x, home)) return home;
  ivec2 toward = ivec2(sign(vec2(pixel - giRepresentativePixel(f, gi, home))));
  ivec2 steps[3] = ivec2[3](ivec2(toward.x, 0), ivec2(0, toward.y), toward);
  for (int i = 0; i < 3; ++i) {
    ivec2 q = home + steps[i];
    if (steps[i] == ivec2(0) || any(lessThan(q, ivec2(0))) ||
        any(greaterThanEqual(q, ivec2(gi.giResolution))))
      continue;
    if (reservoirOnSurface(gi, x, q)) return q;
  }
  return home;
}

// Reservoirs per pixel: the own one and up to 3 neighbours (one without resolve reuse).
uint resolveSampleCount(RestirGiConstants gi) {
  bool reuse = (gi.flags & RESTIR_GI_FLAG_RESOLVE_REUSE) != 0u;
  return reuse ? clamp(gi.resolveSamples, 1u, RESOLVE_MAX_SAMPLES) : 1u;
}

// The spiral's rotation for this pixel and frame.
float resolveRotation(FrameConstants f, ivec2 pixel) {
  return 2.0 * PI * random2(uvec2(pixel), f.frameIndex, RANDOM_GI_RESOLVE).x;
}

// The GI pixel of sample i: the home pixel first, then a golden-angle spiral between half the
// resolve radius and the radius.
ivec2 resolveSampleGiPixel(RestirGiConstants gi, ivec2 home, uint i, uint samples, float rotation) {
  if (i == 0u) return home;
  vec2 offset = goldenSpiralOffset(i - 1u, samples - 1u, rotation, 0.5 * gi.resolveRadius, gi.resolveRadius);
  return clamp(home + ivec2(round(offset)), ivec2(0), ivec2(gi.giResolution) - 1);
}

#endif
