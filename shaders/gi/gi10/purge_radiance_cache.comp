// gi10-purge-radiance-cache (§1.2 #1, §1.4 "lifetime / eviction"): a cell no probe ray has hit
// for decayFrames frames (50) is freed; the live ones are counted. One thread per slot (the
// table is sized from the resolution, so a sweep stays cheap; Capsaicin walks a packed list of
// live tiles instead).
#version 460
#include "gi/gi10/gi10_common.glsl"

layout(local_size_x = GI10_GROUP_SIZE) in;
layout(push_constant, scalar) uniform Push { Gi10PassConstants pc; };

void main() {
  Gi10Constants k = Gi10ConstantsRef(pc.gi10).v;
  Gi10CacheRef cache = Gi10CacheRef(k.cache);
  uint slot = gl_GlobalInvocationID.x;
  if (slot >= (k.bucketMask + 1u) * GI10_BUCKET_SLOTS) return;
  if (cache.v[slot].checksum == 0u) return;
  if (k.frame - cache.v[slot].lastFrame >= k.decayFrames) {
    cache.v[slot].checksum = 0u;
    cache.v[slot].sampleCount = 0u;
    cache.v[slot].radiance = vec3(0.0);
    cache.v[slot].scratch = uvec4(0u);
    return;
  }
  GI10_COUNT(k, liveCells)
}
