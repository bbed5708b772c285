// Rays and hits exchanged through buffers by the generic trace pass (shaders/rt/trace_rays.comp),
// used by tests (GPU vs CPU) and tools.
#ifndef BOUNCE_SHARED_TRACE_IO_H
#define BOUNCE_SHARED_TRACE_IO_H
#include "shared/compat.h"

BOUNCE_BEGIN_SHARED

struct GpuRay {
  vec3 origin;
  float tMin;
  vec3 direction;  // need not be normalised; t is in units of its length
  float tMax;
};
BOUNCE_CHECK_SIZE(GpuRay, 32);

BOUNCE_CONST uint HIT_NONE = 0xFFFFFFFFu;

struct GpuHit {
  float t;
  uint instance;  // HIT_NONE on a miss
  uint geometry;  // global geometry index
  uint primitive;
  vec2 barycentrics;  // weights of v1 and v2
  uint frontFacing;
  uint occluded;  // answer of the visibility query for the same ray
};
BOUNCE_CHECK_SIZE(GpuHit, 32);

BOUNCE_CONST uint TRACE_ALPHA_TEST = 1u;

struct TraceRaysConstants {
  DeviceAddress rays;  // GpuRay[rayCount]
  DeviceAddress hits;  // GpuHit[rayCount]
  uint rayCount;
  uint flags;
};
BOUNCE_CHECK_SIZE(TraceRaysConstants, 24);

BOUNCE_CONST uint TRACE_RAYS_GROUP_SIZE = 64u;

BOUNCE_END_SHARED
#endif
