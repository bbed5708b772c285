// di-trace-candidate-visibility: the shadow ray of each pixel's initial reservoir (RTXDI's
// initial visibility), after di-generate-candidates: an occluded sample keeps M but W = 0, so
// that reuse does not spread a light this pixel cannot see. Its own pass because the traversal
// in the candidates' pass set that pass's registers for its whole candidate loop
// (docs/benchmarks.md). Runs only with DI_FLAG_CANDIDATE_VISIBILITY. Each candidate is a light
// picked at random among many, so neighbouring pixels' rays part: a workgroup's rays are binned
// by direction first, pixels without one last (rt/ray_bins.glsl).
#version 460
#include "di/di_common.glsl"
#include "rt/ray_bins.glsl"

layout(local_size_x = RAY_BIN_GROUP_SIDE, local_size_y = RAY_BIN_GROUP_SIDE) in;

layout(set = 1, binding = DI_CANDIDATES_BINDING_RESERVOIR, rgba32ui) uniform uimage2D reservoirs;

struct ShadowRay {
  DiReservoir reservoir;
  DiSurface surface;
  DiLight light;
  bool traced;  // a sample with weight on a surface
};

ShadowRay shadowRayAt(FrameConstants f, ivec2 pixel) {
  ShadowRay s;
  s.traced = false;
  s.light = noDiLight();
  if (any(greaterThanEqual(uvec2(pixel), f.resolution))) return s;
  s.reservoir = unpackDiReservoir(imageLoad(reservoirs, pixel));
  if (!(s.reservoir.W > 0.0)) return s;
  s.surface = loadDiSurface(f, pixel);
  if (!s.surface.valid) return s;
  s.light = evaluateDiLight(s.surface, s.reservoir.light, s.reservoir.u);
  s.traced = true;
  return s;
}

void main() {
  FrameConstants f = FrameBlock(pc.frame).v;
  DiConstants di = DiBlock(pc.di).v;
  lightTables = LightTablesBlock(di.lights).v;
  ivec2 tile = ivec2(gl_WorkGroupID.xy * RAY_BIN_GROUP_SIDE);
  ShadowRay own = shadowRayAt(f, tile + ivec2(gl_LocalInvocationID.xy));
  vec3 direction = vec3(0.0);
  if (own.traced)
    direction = own.light.distant ? own.light.direction : own.light.shadowTarget - own.surface.position;
  uint traced = binnedInvocation(own.traced, direction);
  ivec2 pixel = tile + ivec2(traced % RAY_BIN_GROUP_SIDE, traced / RAY_BIN_GROUP_SIDE);
  ShadowRay s = shadowRayAt(f, pixel);
  if (!s.traced || diVisible(s.surface, s.light)) return;
  s.reservoir.W = 0.0;
  imageStore(reservoirs, pixel, packDiReservoir(s.reservoir));
}
