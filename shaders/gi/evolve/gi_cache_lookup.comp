// gi-cache-lookup (--gi cache): the cache alone as the frame's diffuse GI. gi.diffuse = the
// mean of four jittered cache lookups (irradiance / pi) at the pixel's surface point; the
// jitter (cache_lookup.glsl) blends neighbouring cells. The cache holds the light straight from
// large emitters only (cache_radiance.glsl), so one NEE sample of the small ones is added (the
// sun and the KHR lights are composite's).
#version 460
#include "gi/evolve/cache/cache_radiance.glsl"
#include "gi/evolve/gbuffer_point.glsl"

layout(local_size_x = HYBRID_GROUP_SIZE, local_size_y = HYBRID_GROUP_SIZE) in;
layout(push_constant, scalar) uniform Push { ClipmapPassConstants pc; };

const uint LOOKUPS_PER_PIXEL = 4u;
const uint RANDOM_CACHE_LOOKUP = 0x43430001u;

void main() {
  FrameConstants f = FrameBlock(pc.frame).v;
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(pixel), f.resolution))) return;
  vec3 position, normal;
  vec3 irradiance = vec3(0.0);
  if (gbufferPoint(f, pixel, position, normal)) {
    ClipmapCacheView cache = clipmapCacheView(pc.cache);
    lightTables = LightTablesBlock(cache.constants.v.lights).v;
    for (uint i = 0u; i < LOOKUPS_PER_PIXEL; ++i) {
      uvec3 h = pcg3d(uvec3(uvec2(pixel), f.frameIndex * LOOKUPS_PER_PIXEL + i) ^ uvec3(0u, 0u, RANDOM_CACHE_LOOKUP));
      irradiance += cacheLookupIrradiance(cache, position, normal, h.x);
    }
    irradiance /= float(LOOKUPS_PER_PIXEL);
    vec4 u = uniformFromHash(pcg4d(uvec4(uvec2(pixel), f.frameIndex, RANDOM_CACHE_LOOKUP + 1u)));
    irradiance += emitterIrradianceOverPi(position, normal, u, true);
  }
  imageStore(outputImage, pixel, vec4(min(irradiance, vec3(65000.0)), 1.0));
}
