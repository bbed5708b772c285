// gi10-spawn-screen-probes (§1.2 #4, §1.3 "spawn position"): one new probe per spawn tile
// (16x16 pixels on desktop: a quarter of a ray per pixel) at the pixel tile x 16 + Halton(2,3)
// jitter, so that over frames the new probes visit every 8x8 probe tile of the spawn tile.
// Pixels that see the sky spawn nothing.
#version 460
#include "gi/gi10/gi10_common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(push_constant, scalar) uniform Push { Gi10PassConstants pc; };
layout(set = 1, binding = GI10_SPAWN_BINDING_DEPTH, r32f) uniform readonly image2D depths;

float halton(uint index, uint base) {
  float f = 1.0, r = 0.0;
  for (uint i = index; i > 0u; i /= base) {
    f /= float(base);
    r += f * float(i % base);
  }
  return r;
}

void main() {
  FrameConstants f = FrameBlock(pc.frame).v;
  Gi10Constants k = Gi10ConstantsRef(pc.gi10).v;
  uvec2 tile = gl_GlobalInvocationID.xy;
  if (any(greaterThanEqual(tile, k.spawnGrid))) return;
  uint index = (k.frame & 255u) + 1u;
  vec2 jitter = vec2(halton(index, 2u), halton(index, 3u));
  uvec2 offset = min(uvec2(jitter * float(k.spawnTile)), uvec2(k.spawnTile - 1u));
  uvec2 pixel = tile * k.spawnTile + offset;
  // A spawn tile cut by the screen's edge puts its probe inside the screen.
  pixel = min(pixel, f.resolution - 1u);
  bool surface = imageLoad(depths, ivec2(pixel)).x > 0.0;
  Gi10SpawnRef(k.spawn).v[tile.y * k.spawnGrid.x + tile.x] = surface ? pixel : uvec2(GI10_NO_SPAWN);
}
