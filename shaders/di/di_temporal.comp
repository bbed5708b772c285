// di-temporal: this frame's candidate reservoir merged with last frame's reservoir at the
// reprojected pixel (Bitterli et al. 2020, Alg. 4 and §4.3), whose confidence is capped at
// DiConstants::temporalMaxM (RTXDI's maxHistoryLength, 20). The history is used where the
// reprojected pixel shows the same surface (diSimilarSurface on last frame's view depth and
// normal, kept in di.reservoir-surface). Each input is weighted p_hat(y) W M at this pixel and
// the result normalised by the sum of M (1/M weights): exact while the reprojected point is this
// pixel's point (a static view: the unbiased tests), biased on motion where the two points'
// targets differ (RTXDI's temporal bias correction "off"). The history is this pass's output of
// last frame as di-shade passed it on (di.reservoir-final): with W = 0 where it held the sample
// di-shade shaded and the final shadow ray was blocked.
#version 460
#include "di/di_common.glsl"

layout(local_size_x = DI_GROUP_SIZE, local_size_y = DI_GROUP_SIZE) in;

layout(set = 1, binding = DI_TEMPORAL_BINDING_CANDIDATE, rgba32ui) uniform readonly uimage2D candidates;
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

void main() {
  FrameConstants f = FrameBlock(pc.frame).v;
  DiConstants di = DiBlock(pc.di).v;
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(pixel), f.resolution))) return;
  lightTables = LightTablesBlock(di.lights).v;
  DiSurface s = loadDiSurface(f, pixel);
  DiReservoir candidate = unpackDiReservoir(imageLoad(candidates, pixel));
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
