// The shading point of a pixel from the GBuffer, for the passes that look the cache up per
// pixel (gi-cache-lookup, the `cache` debug view).
#ifndef BOUNCE_GI_EVOLVE_GBUFFER_POINT_GLSL
#define BOUNCE_GI_EVOLVE_GBUFFER_POINT_GLSL
#include "passes/hybrid_frame.glsl"

layout(set = 1, binding = CACHE_LOOKUP_BINDING_NORMALS, rgba16f) uniform readonly image2D gbufferNormals;
layout(set = 1, binding = CACHE_LOOKUP_BINDING_DEPTH, r32f) uniform readonly image2D gbufferDepth;
layout(set = 1, binding = CACHE_LOOKUP_BINDING_FLAGS, r32ui) uniform readonly uimage2D gbufferFlags;
layout(set = 1, binding = CACHE_LOOKUP_BINDING_OUTPUT, rgba16f) uniform writeonly image2D outputImage;

// False where the pixel sees the sky.
bool gbufferPoint(FrameConstants f, ivec2 pixel, out vec3 position, out vec3 normal) {
  position = vec3(0.0);
  normal = vec3(0.0, 0.0, 1.0);
  if ((imageLoad(gbufferFlags, pixel).x & GBUFFER_FLAG_SURFACE) == 0u) return false;
  normal = decodeOctahedral(imageLoad(gbufferNormals, pixel).xy);
  position = positionFromDepth(f, vec2(pixel) + 0.5, imageLoad(gbufferDepth, pixel).x);
  return true;
}

#endif
