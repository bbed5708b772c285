// Hardware ray tracing through VK_KHR_ray_tracing_pipeline, for ray-generation shaders: the
// same two queries as the software tracer (rt/trace.glsl), over the acceleration structures of
// src/rt/hardware_tracer.h. Every geometry uses hit group 0 (closest hit rt/hw_closest_hit.rchit,
// any hit rt/hw_alpha_test.rahit; opaque geometries never run the any-hit shader) and miss
// shader 0 (rt/hw_miss.rmiss). Both queries always alpha-test, as every software call in
// bench-rays does.
#ifndef BOUNCE_RT_HW_TRACE_GLSL
#define BOUNCE_RT_HW_TRACE_GLSL
#extension GL_EXT_ray_tracing : require
#include "rt/hw_payload.glsl"
#include "shared/hardware_trace.h"
#include "shared/scene_layout.h"

layout(set = HW_TRACE_SET, binding = HW_TRACE_BINDING_TLAS) uniform accelerationStructureEXT hwTlas;
layout(location = HW_PAYLOAD_LOCATION) rayPayloadEXT HwHit hwPayload;

bool hwHitFound(HwHit h) { return h.instance != BVH_INVALID; }

// sbtRecordOffset 0 and sbtRecordStride 0: every geometry of every instance uses hit group 0,
// whatever its geometry index.
HwHit hwTraceClosest(vec3 origin, vec3 dir, float tMin, float tMax) {
  traceRayEXT(hwTlas, gl_RayFlagsNoneEXT, 0xFF, 0, 0, 0, origin, tMin, dir, tMax,
              HW_PAYLOAD_LOCATION);
  return hwPayload;
}

// The first accepted hit, not necessarily the closest: the closest-hit shader is skipped, so
// only the miss shader writes the payload (instance, t and primitive stay unknown on a hit).
HwHit hwTraceAnyHit(vec3 origin, vec3 dir, float tMin, float tMax) {
  hwPayload.t = 0.0;
  hwPayload.instance = 0u;
  hwPayload.geometry = 0u;
  hwPayload.primitive = 0u;
  hwPayload.barycentrics = vec2(0.0);
  traceRayEXT(hwTlas, gl_RayFlagsTerminateOnFirstHitEXT | gl_RayFlagsSkipClosestHitShaderEXT, 0xFF,
              0, 0, 0, origin, tMin, dir, tMax, HW_PAYLOAD_LOCATION);
  return hwPayload;
}

#endif
