// Hardware tracer, closest hit: reports the hit in the software tracer's terms (instance,
// global geometry, primitive within the geometry, t, barycentrics of v1 and v2).
#version 460
#extension GL_EXT_ray_tracing : require
#include "rt/hw_payload.glsl"
#include "rt/scene.glsl"

layout(location = HW_PAYLOAD_LOCATION) rayPayloadInEXT HwHit payload;
hitAttributeEXT vec2 barycentrics;

void main() {
  uint instance = gl_InstanceCustomIndexEXT;
  payload.t = gl_HitTEXT;
  payload.instance = instance;
  payload.geometry = sceneInstance(instance).geometryBase + uint(gl_GeometryIndexEXT);
  payload.primitive = uint(gl_PrimitiveID);
  payload.barycentrics = barycentrics;
}
