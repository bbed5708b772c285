// Pixels beside an occluder, where light from a neighbour's samples may be hidden from this
// pixel: gi-restir-resolve tests the visibility of the samples it reuses there, and
// gi-spatial-denoise does not blur across them (a wall inside a 5 cm gap behind a cabinet
// would otherwise take the light of the wall outside). The including shader declares the
// GBuffer images `depths` (r32f) and `flags` (r32ui).
#ifndef BOUNCE_GI_EVOLVE_BESIDE_OCCLUDER_GLSL
#define BOUNCE_GI_EVOLVE_BESIDE_OCCLUDER_GLSL
#include "gi/evolve/restir_gi_common.glsl"

// Whether a GBuffer point one GI pixel away (8 directions) lies in front of x's tangent plane by
// more than the same-surface tolerance: then something may hide from x what its GI pixel's
// neighbours see (x is behind it: a gap, an overhang, the inside of a corner). In corners the
// test has a price: it zeroes the neighbours' samples x cannot see but never adds those only
// x can see, so corners get darker (cornell's mean -3 %; relMSE still lower on cornell and
// sunroom). Keeping only occluders parallel to x's plane spared the corners but missed the
// gap too: looking into a gap one sees the side of the object in front, across the plane.
bool besideOccluder(FrameConstants f, RestirGiConstants gi, ivec2 pixel, PrimaryVertex x) {
  if ((gi.flags & RESTIR_GI_FLAG_OCCLUDER_VISIBILITY) == 0u) return false;
  int step = int(gi.divisor);
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      ivec2 q = clamp(pixel + ivec2(dx, dy) * step, ivec2(0), ivec2(f.resolution) - 1);
      if ((dx == 0 && dy == 0) || (imageLoad(flags, q).x & GBUFFER_FLAG_SURFACE) == 0u) continue;
      vec3 p = positionFromDepth(f, vec2(q) + 0.5, imageLoad(depths, q).x);
      if (dot(x.geometricNormal, p - x.position) > gi.planeTolerance * x.depth) return true;
    }
  return false;
}

#endif
