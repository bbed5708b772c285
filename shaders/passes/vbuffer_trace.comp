// vbuffer (ray-cast variant, --vbuffer trace): the same ids as the raster pass, found by one
// camera ray through each pixel centre (shifted by the TAA jitter when on, as the raster pass's
// matrix is) with the tracer's alpha test. Rasterisation and ray
// casting agree on what covers a pixel centre (tests/test_hybrid_frame.cpp checks the GBuffer
// against ray-cast primary hits); this variant exists for GPUs whose raster units are few,
// such as the H100/H200 (GH100 has graphics units in only a small part of the chip), where
// primary rays through our BVH are several times faster than drawing the scene.
#version 460
#include "passes/hybrid_frame.glsl"
#include "rt/trace.glsl"

layout(local_size_x = HYBRID_GROUP_SIZE, local_size_y = HYBRID_GROUP_SIZE) in;
layout(push_constant, scalar) uniform Push { HybridPassConstants pc; };

layout(set = 1, binding = VBUFFER_TRACE_BINDING_IDS, rgba32ui) uniform writeonly uimage2D idsOut;

void main() {
  FrameConstants f = FrameBlock(pc.frame).v;
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(pixel), f.resolution))) return;
  vec3 dir = pixelRayDirection(f, vec2(pixel) + 0.5);
  TraceHit hit = traceClosest(f.camera.position, dir, 0.0, 3.0e38, true);
  uvec4 ids = traceHitFound(hit) ? uvec4(hit.instance, hit.geometry, hit.primitive, 0u)
                                 : uvec4(VBUFFER_NO_HIT, 0u, 0u, 0u);
  imageStore(idsOut, pixel, ids);
}
