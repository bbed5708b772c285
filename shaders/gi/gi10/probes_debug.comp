// gi10-probes-debug: the `gi10.probes-view` debug view. Each 8x8-pixel tile shows its probe's 64
// cells as an 8x8 image of their radiance (the hemisphere's equal-area square, gi10_common.glsl);
// alpha: 1 for a probe traced this frame, 0.5 for one reprojected, 0 for none (an empty tile,
// shown black). One thread per pixel.
#version 460
#include "gi/gi10/gi10_common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(push_constant, scalar) uniform Push { Gi10PassConstants pc; };
layout(set = 1, binding = 0, rgba16f) uniform writeonly image2D outputImage;

void main() {
  FrameConstants f = FrameBlock(pc.frame).v;
  Gi10Constants k = Gi10ConstantsRef(pc.gi10).v;
  uvec2 pixel = gl_GlobalInvocationID.xy;
  if (any(greaterThanEqual(pixel, f.resolution))) return;
  uvec2 tile = pixel / GI10_PROBE_SIZE;
  uint tileIndex = tile.y * k.probeGrid.x + tile.x;
  uint flags = Gi10ProbesRef(k.probes).v[tileIndex].flags;
  vec4 result = vec4(0.0);
  if ((flags & GI10_PROBE_VALID) != 0u) {
    uvec2 c = pixel % GI10_PROBE_SIZE;
    vec4 cell = gi10UnpackCell(Gi10RadianceRef(k.radiance).v[tileIndex * GI10_PROBE_CELLS + c.y * GI10_PROBE_SIZE + c.x]);
    result = vec4(cell.rgb, (flags & GI10_PROBE_SPAWNED) != 0u ? 1.0 : 0.5);
  }
  imageStore(outputImage, ivec2(pixel), result);
}
