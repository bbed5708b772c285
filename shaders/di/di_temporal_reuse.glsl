// di-temporal's merge of a pixel's candidate reservoir with last frame's reservoir at the
// reprojected pixel, shared by di-temporal (the candidate read from di.candidate) and
// di-candidates-temporal (the candidate drawn in the same pass). What it computes is described
// in di_temporal.comp. Declares the history images at DI_TEMPORAL_BINDING_*.
#ifndef BOUNCE_DI_TEMPORAL_REUSE_GLSL
#define BOUNCE_DI_TEMPORAL_REUSE_GLSL
#include "di/di_common.glsl"

layout(set = 1, binding = DI_TEMPORAL_BINDING_VELOCITY, rg16f) uniform readonly image2D velocities;
layout(set = 1, binding = DI_TEMPORAL_BINDING_PREVIOUS, rgba32ui) uniform readonly uimage2D previousReservoirs;
layout(set = 1, binding = DI_TEMPORAL_BINDING_PREVIOUS_SURFACE, rgba32f) uniform readonly image2D previousSurfaces;
layout(set = 1, binding = DI_TEMPORAL_BINDING_CURRENT, rgba32ui) uniform writeonly uimage2D reservoirOut;
layout(set = 1, binding = DI_TEMPORAL_BINDING_CURRENT_SURFACE, rgba32f) uniform writeonly image2D surfaceOut;

// Last frame's reservoir at the pixel this one was, or an empty one.
DiReservoir historyReservoir(FrameConstants f, DiConstants di, DiSurface s, ivec2 pixel) {
  if (pc.historyValid == 0u || (di.flags & DI_FLAG_TEMPORAL) == 0u) return emptyDiReservoir();
  vec2 previous = vec2(pixel) + 0.5 - imageLoad(velocities, pixel).xy;
  ivec2 p = ivec2(floor(previous));
  if (any(lessThan(p, ivec2(0))) || any(greaterThanEqual(uvec2(p), f.resolution))) return emptyDiReservoir();
  vec4 surface = imageLoad(previousSurfaces, p);
  if (!diSimilarSurface(di, s.depth, s.normal, surface.z, decodeOctahedral(surface.xy))) return emptyDiReservoir();
  DiReservoir h = unpackDiReservoir(imageLoad(previousReservoirs, p));
  h.M = min(h.M, di.temporalMaxM);
  return h;
}

// The candidate merged with the history; writes this pixel's reservoir and its surface (the
// next frame's history test).
void storeTemporalReuse(FrameConstants f, DiConstants di, DiSurface s, ivec2 pixel, DiReservoir candidate) {
  DiReservoir r = emptyDiReservoir();
  if (s.valid) {
    DiReservoir history = historyReservoir(f, di, s, pixel);
    uvec4 key = diRandomKey(f, di, pixel, RANDOM_DI_TEMPORAL);
    float weightSum = 0.0, target = 0.0;
    float candidateTarget = diTarget(evaluateDiLight(s, candidate.light, candidate.u));
    if (diStream(r, weightSum, candidate.light, candidate.u, candidateTarget * candidate.W * candidate.M,
                 candidate.M, diRandom(key).x))
      target = candidateTarget;
    float historyTarget = history.M > 0.0 ? diTarget(evaluateDiLight(s, history.light, history.u)) : 0.0;
    if (diStream(r, weightSum, history.light, history.u, historyTarget * history.W * history.M, history.M,
                 diRandom(key).x)) {
      target = historyTarget;
      // Its final visibility (di-shade) is a frame older.
      r.visibleAge = min(history.visibleAge + 1u, DI_VISIBILITY_UNKNOWN);
    }
    r.W = diContributionWeight(weightSum, target, r.M);
  }
  imageStore(reservoirOut, pixel, packDiReservoir(r));
  imageStore(surfaceOut, pixel, vec4(encodeOctahedral(s.normal), s.valid ? s.depth : 0.0, 0.0));
}

#endif
