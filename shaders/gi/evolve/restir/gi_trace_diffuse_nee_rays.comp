// gi-trace-diffuse-nee-rays: the visibility of each 2nd vertex's NEE shadow ray (set up by
// gi-trace-diffuse-rays: a point on a local light, or a direction to a distant one).
#version 460
#include "gi/evolve/restir/restir_gi_common.glsl"
#include "common/ray_offset.glsl"
#include "rt/trace.glsl"

layout(local_size_x = RESTIR_GI_GROUP_SIZE, local_size_y = RESTIR_GI_GROUP_SIZE) in;
layout(push_constant, scalar) uniform Push { RestirGiPassConstants pc; };

layout(set = 1, binding = GI_NEE_BINDING_HIT, rgba32f) uniform readonly image2D hits;
layout(set = 1, binding = GI_NEE_BINDING_HIT_NORMAL, rgba16f) uniform readonly image2D hitNormals;
layout(set = 1, binding = GI_NEE_BINDING_NEE_RAY, rgba32f) uniform readonly image2D neeRays;
layout(set = 1, binding = GI_NEE_BINDING_VISIBILITY, r16f) uniform writeonly image2D visibilityOut;

void main() {
  RestirGiConstants gi = RestirGiBlock(pc.gi).v;
  ivec2 g = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(g), gi.giResolution))) return;
  vec4 hit = imageLoad(hits, g);
  vec4 ray = imageLoad(neeRays, g);
  float visible = 0.0;
  if (uint(hit.w + 0.5) == RESTIR_GI_KIND_SURFACE && any(notEqual(ray.xyz, vec3(0.0)))) {
    vec3 origin = offsetRayOrigin(hit.xyz, decodeOctahedral(imageLoad(hitNormals, g).xy));
    bool unoccluded = ray.w > 0.5 ? traceVisibility(origin, ray.xyz - origin, 0.0, 1.0, true)
                                  : traceVisibility(origin, ray.xyz, 0.0, 3.0e38, true);
    visible = unoccluded ? 1.0 : 0.0;
  }
  imageStore(visibilityOut, g, vec4(visible));
}
