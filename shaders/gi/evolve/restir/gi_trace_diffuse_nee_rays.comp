// gi-trace-diffuse-nee-rays: the visibility of each 2nd vertex's NEE shadow ray (set up by
// gi-trace-diffuse-rays: a point on a local light, or a direction to a distant one). One thread
// per GI pixel with a light sample (GI_RAY_LIST_NEE, ray_list.glsl); the others keep the 0
// gi-trace-diffuse-rays wrote.
#version 460
#include "gi/evolve/restir/restir_gi_common.glsl"
#include "gi/evolve/restir/ray_list.glsl"
#include "common/ray_offset.glsl"
#include "rt/trace.glsl"

layout(local_size_x = GI_RAY_LIST_GROUP_SIZE) in;
layout(push_constant, scalar) uniform Push { RestirGiPassConstants pc; };

layout(set = 1, binding = GI_NEE_BINDING_HIT, rgba32f) uniform readonly image2D hits;
layout(set = 1, binding = GI_NEE_BINDING_HIT_NORMAL, rgba16f) uniform readonly image2D hitNormals;
layout(set = 1, binding = GI_NEE_BINDING_NEE_RAY, rgba32f) uniform readonly image2D neeRays;
layout(set = 1, binding = GI_NEE_BINDING_VISIBILITY, r16f) uniform writeonly image2D visibilityOut;

void traceNeeRay(ivec2 g) {
  vec3 target = imageLoad(neeRays, g).xyz;
  bool toPoint = imageLoad(neeRays, g).w > 0.5;
  vec3 origin = offsetRayOrigin(imageLoad(hits, g).xyz, decodeOctahedral(imageLoad(hitNormals, g).xy));
  bool unoccluded = toPoint ? traceVisibility(origin, target - origin, 0.0, 1.0, true)
                            : traceVisibility(origin, target, 0.0, 3.0e38, true);
  imageStore(visibilityOut, g, vec4(unoccluded ? 1.0 : 0.0));
}

void main() {
  RestirGiConstants gi = RestirGiBlock(pc.gi).v;
  uint count = rayListCount(pc.rayLists, GI_RAY_LIST_NEE);
  for (uint i = gl_GlobalInvocationID.x; i < count; i += RAY_LIST_STRIDE)
    traceNeeRay(rayListPixel(pc.rayLists, GI_RAY_LIST_NEE, gi.giResolution, i));
}
