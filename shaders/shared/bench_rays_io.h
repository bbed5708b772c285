// The ray-tracing benchmark (`bounce bench-rays`, pass "bench-rays"): primary rays from the
// camera, then from each primary hit a sun shadow ray (visibility) and a cosine-distributed
// diffuse bounce ray (closest hit), each kind timed on its own.
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

struct BenchRaysConstants {
  GpuCamera camera;
  DeviceAddress surfaces;  // BenchSurface[width * height]
  DeviceAddress results;   // uint[width * height]: 1 = hit (or occluded), 0 = miss, 2 = no ray
  uvec2 resolution;
  uint mode;
  uint frame;
  vec3 toSun;  // unit vector towards the sun
  float sunCosHalfAngle;
};
BOUNCE_CHECK_SIZE(BenchRaysConstants, 112);

BOUNCE_CONST uint BENCH_RAYS_GROUP_SIZE = 8u;

BOUNCE_END_SHARED
#endif
