// The ray-tracing benchmark (`bounce bench-rays`, pass "bench-rays"): primary rays from the
// camera, then from each primary hit a sun shadow ray (visibility) and a cosine-distributed
// diffuse bounce ray (closest hit), each kind timed on its own. The same constants drive the
// software compute shader (rt/bench_rays.comp) and the hardware ray-generation shader
// (rt/bench_rays.rgen); both generate their rays with rt/bench_rays_common.glsl.
#ifndef BOUNCE_SHARED_BENCH_RAYS_IO_H
#define BOUNCE_SHARED_BENCH_RAYS_IO_H
#include "shared/camera.h"

BOUNCE_BEGIN_SHARED

BOUNCE_CONST uint BENCH_RAYS_PRIMARY = 0u;
BOUNCE_CONST uint BENCH_RAYS_SHADOW = 1u;
BOUNCE_CONST uint BENCH_RAYS_DIFFUSE = 2u;

// A primary hit, the origin of the secondary rays. valid = 0 on a miss.
struct BenchSurface {
  vec3 position;  // offset off the surface along the normal
  uint valid;
  vec3 normal;  // facing the camera
  float pad;
};
BOUNCE_CHECK_SIZE(BenchSurface, 32);

// One ray as traced: the agreement run (`bench-rays --tracer both`) has the software tracer
// write the rays it traced and the hardware tracer trace exactly those. tMax < 0: no ray (the
// pixel's primary ray missed).
struct BenchRay {
  vec3 origin;
  float tMin;
  vec3 direction;
  float tMax;
};
BOUNCE_CHECK_SIZE(BenchRay, 32);

// What a tracer found for one ray. instance = BVH_INVALID (0xFFFFFFFF) on a miss,
// BENCH_RAYS_NO_RAY where there was no ray. Visibility rays (shadow) stop at any hit, so only
// their hit/miss answer is comparable between tracers.
BOUNCE_CONST uint BENCH_RAYS_NO_RAY = 0xFFFFFFFEu;
struct BenchHit {
  float t;
  uint instance;
  uint geometry;  // global geometry index
  uint primitive;
};
BOUNCE_CHECK_SIZE(BenchHit, 16);

struct BenchRaysConstants {
  GpuCamera camera;
  DeviceAddress surfaces;  // BenchSurface[width * height]
  DeviceAddress results;   // uint[width * height]: 1 = hit (or occluded), 0 = miss, 2 = no ray
  // The agreement run (both 0 in timed runs). Software: non-zero `hits` records every traced
  // ray into rays[] and its hit into hits[]. Hardware: non-zero `hits` traces the rays of
  // rays[] (instead of generating them) and records the hits.
  DeviceAddress rays;  // BenchRay[width * height]
  DeviceAddress hits;  // BenchHit[width * height]
  uvec2 resolution;
  uint mode;
  uint frame;
  vec3 toSun;  // unit vector towards the sun
  float sunCosHalfAngle;
};
// 128 bytes: the smallest maxPushConstantsSize Vulkan allows (and lavapipe's).
BOUNCE_CHECK_SIZE(BenchRaysConstants, 128);

BOUNCE_CONST uint BENCH_RAYS_GROUP_SIZE = 8u;

BOUNCE_END_SHARED
#endif
