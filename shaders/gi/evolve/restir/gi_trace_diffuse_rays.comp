// gi-trace-diffuse-rays: the closest hit of each GI pixel's ray from x1 (alpha test on), as ids
// and barycentrics; gi-shade-diffuse-hits makes x2 of them. The two were one pass: its shading
// code (materials, light sampling, the cache, a continued path) set the register count of the
// whole shader, so the traversal ran at a quarter of the GPU's threads (docs/benchmarks.md).
#version 460
#include "gi/evolve/restir/restir_gi_common.glsl"
#include "common/ray_offset.glsl"
#include "rt/trace.glsl"

layout(local_size_x = RESTIR_GI_GROUP_SIZE, local_size_y = RESTIR_GI_GROUP_SIZE) in;
layout(push_constant, scalar) uniform Push { RestirGiPassConstants pc; };

layout(set = 1, binding = GI_TRACE_BINDING_NORMALS, rgba16f) uniform readonly image2D normals;
layout(set = 1, binding = GI_TRACE_BINDING_DEPTH, r32f) uniform readonly image2D depths;
layout(set = 1, binding = GI_TRACE_BINDING_RAYS, rgba32f) uniform readonly image2D rays;
layout(set = 1, binding = GI_TRACE_BINDING_HIT_IDS, rgba32ui) uniform writeonly uimage2D hitIdsOut;
layout(set = 1, binding = GI_TRACE_BINDING_HIT_BARYCENTRICS, rg32f) uniform writeonly image2D hitBarycentricsOut;

void main() {
  FrameConstants f = FrameBlock(pc.frame).v;
  RestirGiConstants gi = RestirGiBlock(pc.gi).v;
  ivec2 g = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(g), gi.giResolution))) return;
  vec4 ray = imageLoad(rays, g);
  ivec2 pixel = giRepresentativePixel(f, gi, g);
  PrimaryVertex x1 = makePrimaryVertex(f, pixel, imageLoad(normals, pixel), imageLoad(depths, pixel).x);
  // No ray, or a direction below the geometric surface (gi-shade-diffuse-hits tests it too).
  TraceHit hit = noHit(0.0);
  if (ray.w != 0.0 && dot(ray.xyz, x1.geometricNormal) > 0.0)
    hit = traceClosest(offsetRayOrigin(x1.position, x1.geometricNormal), ray.xyz, 0.0, 3.0e38, true);
  bool found = traceHitFound(hit);
  imageStore(hitIdsOut, g, found ? uvec4(hit.instance, hit.geometry, hit.primitive, 0u) : uvec4(GI_HIT_NONE, 0u, 0u, 0u));
  imageStore(hitBarycentricsOut, g, vec4(found ? hit.barycentrics : vec2(0.0), 0.0, 0.0));
}
