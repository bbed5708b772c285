// cache-debug -> image `cache` (debug view, as seed 000's picture of the cache): every surface
// pixel shaded with the irradiance / pi of the cell it falls in (L1 SH evaluated for the
// pixel's normal), without the random jitter (so the cells show as flat patches, bent by the
// periodic wobble), times the frame's exposure; a pure read (marks and allocates nothing).
// Colours: the cell's irradiance (black means the cell sees no light); magenta: no cell with SH
// serves the point in any cascade (not allocated yet, allocated this frame and not yet traced,
// or the pool is exhausted); the sky is black.
#version 460
#include "gi/evolve/cache/cache_lookup.glsl"
#include "gi/evolve/gbuffer_point.glsl"

layout(local_size_x = HYBRID_GROUP_SIZE, local_size_y = HYBRID_GROUP_SIZE) in;
layout(push_constant, scalar) uniform Push { ClipmapPassConstants pc; };

void main() {
  FrameConstants f = FrameBlock(pc.frame).v;
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(pixel), f.resolution))) return;
  vec3 position, normal;
  vec3 color = vec3(0.0);
  if (gbufferPoint(f, pixel, position, normal)) {
    ClipmapCacheView cache = clipmapCacheView(pc.cache);
    vec3 irradianceOverPi;
    uint cascadeUsed;
    bool found = clipmapQueryCell(cache, position, normal, vec2(0.0), 0u, false,
                                  irradianceOverPi, cascadeUsed);
    color = found ? irradianceOverPi * f.exposure : vec3(1.0, 0.0, 1.0);
  }
  imageStore(outputImage, pixel, vec4(color, 1.0));
}
