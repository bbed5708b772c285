// gi10-cache-debug: the `gi10.cache-view` debug view. Each pixel looks up the hash-grid cell of
// its surface point and shows its radiance (rgb), with
// alpha = its sample count / maxSampleCount; a missing cell shows magenta at alpha 0, so the
// cells' extent, their running means and the holes are all visible. One thread per pixel.
#version 460
#include "gi/gi10/hash_grid_cache.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(push_constant, scalar) uniform Push { Gi10PassConstants pc; };
layout(set = 1, binding = 0, r32f) uniform readonly image2D depths;
layout(set = 1, binding = 1, rgba16f) uniform writeonly image2D outputImage;
layout(set = 1, binding = 2, rgba16f) uniform readonly image2D normals;

void main() {
  FrameConstants f = FrameBlock(pc.frame).v;
  Gi10Constants k = Gi10ConstantsRef(pc.gi10).v;
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(pixel), f.resolution))) return;
  float depth = imageLoad(depths, pixel).x;
  if (!(depth > 0.0)) {
    imageStore(outputImage, pixel, vec4(0.0));
    return;
  }
  vec3 x = positionFromDepth(f, vec2(pixel) + 0.5, depth);
  Gi10CellKey key = gi10CellKey(k, f, x, decodeOctahedral(imageLoad(normals, pixel).zw));
  Gi10CacheRef cache = Gi10CacheRef(k.cache);
  vec4 result = vec4(1.0, 0.0, 1.0, 0.0);
  for (uint i = 0u; i < GI10_BUCKET_SLOTS; ++i) {
    uint slot = key.bucket * GI10_BUCKET_SLOTS + i;
    if (cache.v[slot].checksum != key.checksum) continue;
    result = vec4(cache.v[slot].radiance, float(cache.v[slot].sampleCount) / float(k.maxSampleCount));
    break;
  }
  imageStore(outputImage, pixel, result);
}
