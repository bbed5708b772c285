// Hardware tracer, miss: marks the payload as no hit.
#version 460
#extension GL_EXT_ray_tracing : require
#include "rt/hw_payload.glsl"
#include "shared/scene_layout.h"

layout(location = HW_PAYLOAD_LOCATION) rayPayloadInEXT HwHit payload;

void main() {
  payload.instance = BVH_INVALID;
  payload.t = gl_RayTmaxEXT;
}
