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
#include "di/di_temporal_reuse.glsl"

layout(local_size_x = DI_GROUP_SIZE, local_size_y = DI_GROUP_SIZE) in;

layout(set = 1, binding = DI_TEMPORAL_BINDING_CANDIDATE, rgba32ui) uniform readonly uimage2D candidates;

void main() {
  FrameConstants f = FrameBlock(pc.frame).v;
  DiConstants di = DiBlock(pc.di).v;
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(pixel), f.resolution))) return;
  lightTables = LightTablesBlock(di.lights).v;
  DiSurface s = loadDiSurface(f, pixel);
  storeTemporalReuse(f, di, s, pixel, unpackDiReservoir(imageLoad(candidates, pixel)));
}
