// bench-rays, software tracer: one kind of ray per dispatch (see shared/bench_rays_io.h), so
// each kind's traversal cost can be timed alone. Results are written per pixel so no ray is
// optimised away. The rays come from rt/bench_rays_common.glsl, shared with the hardware
// tracer's rt/bench_rays.rgen.
#version 460
#include "rt/bench_rays_common.glsl"
#include "rt/trace.glsl"

layout(local_size_x = BENCH_RAYS_GROUP_SIZE, local_size_y = BENCH_RAYS_GROUP_SIZE) in;
layout(push_constant, scalar) uniform Push { BenchRaysConstants pc; };

// The agreement run only (pc.hits != 0, a uniform branch): the ray and what it hit.
void record(uint index, BenchRay ray, BenchHit hit) {
  if (pc.hits == uint64_t(0)) return;
  BenchRayArray(pc.rays).v[index] = ray;
  BenchHitArray(pc.hits).v[index] = hit;
}

BenchHit benchHit(TraceHit h) {
  return makeBenchHit(traceHitFound(h), h.t, h.instance, h.geometry, h.primitive);
}

void tracePrimary(uvec2 pixel, uint index) {
  BenchRay ray = benchPrimaryRay(pc.camera, pixel, pc.resolution);
  TraceHit hit = traceClosest(ray.origin, ray.direction, ray.tMin, ray.tMax, true);
  BenchSurface s = benchSurface(ray, traceHitFound(hit), hit.t, hit.instance, hit.geometry,
                                hit.primitive, hit.barycentrics);
  SurfaceArray(pc.surfaces).v[index] = s;
  ResultArray(pc.results).v[index] = s.valid;
  record(index, ray, benchHit(hit));
}

void traceSecondary(uvec2 pixel, uint index) {
  BenchSurface s = SurfaceArray(pc.surfaces).v[index];
  uint result = 2u;
  if (s.valid != 0u) {
    BenchRay ray = benchSecondaryRay(s, pc.mode, pixel, pc.frame, pc.toSun, pc.sunCosHalfAngle);
    TraceHit hit = pc.mode == BENCH_RAYS_SHADOW
                       ? traceAnyHit(ray.origin, ray.direction, ray.tMin, ray.tMax, true)
                       : traceClosest(ray.origin, ray.direction, ray.tMin, ray.tMax, true);
    result = traceHitFound(hit) ? 1u : 0u;
    record(index, ray, benchHit(hit));
  } else {
    record(index, noBenchRay(), noBenchHit());
  }
  ResultArray(pc.results).v[index] = result;
}

void main() {
  uvec2 pixel = gl_GlobalInvocationID.xy;
  if (any(greaterThanEqual(pixel, pc.resolution))) return;
  uint index = pixel.y * pc.resolution.x + pixel.x;
  if (pc.mode == BENCH_RAYS_PRIMARY)
    tracePrimary(pixel, index);
  else
    traceSecondary(pixel, index);
}
