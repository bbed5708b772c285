// trace-rays: traces a buffer of rays (closest hit and visibility) into a buffer of hits.
// Used to check the GPU traversal against the CPU reference, and by tools.
#version 460
#include "rt/trace.glsl"
#include "shared/trace_io.h"

layout(local_size_x = TRACE_RAYS_GROUP_SIZE) in;
layout(push_constant, scalar) uniform Push { TraceRaysConstants pc; };
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer RayArray { GpuRay v[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) writeonly buffer HitArray { GpuHit v[]; };

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= pc.rayCount) return;
  GpuRay ray = RayArray(pc.rays).v[i];
  bool alphaTest = (pc.flags & TRACE_ALPHA_TEST) != 0u;
  TraceHit h = traceClosest(ray.origin, ray.direction, ray.tMin, ray.tMax, alphaTest);
  GpuHit out_;
  out_.t = h.t;
  out_.instance = traceHitFound(h) ? h.instance : HIT_NONE;
  out_.geometry = h.geometry;
  out_.primitive = h.primitive;
  out_.barycentrics = h.barycentrics;
  out_.frontFacing = h.frontFacing ? 1u : 0u;
  out_.occluded = traceVisibility(ray.origin, ray.direction, ray.tMin, ray.tMax, alphaTest) ? 0u : 1u;
  HitArray(pc.hits).v[i] = out_;
}
