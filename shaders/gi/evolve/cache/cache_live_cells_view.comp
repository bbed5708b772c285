// cache-live-cells-view -> image `cache.live-cells` (debug view): one bar per cascade (finest
// at the top), length log2(1 + live cells) / 16 of the width, so 65,535 cells fill it.
#version 460
#include "gi/evolve/cache/cache_common.glsl"
#include "common/color.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(push_constant, scalar) uniform Push { ClipmapPassConstants pc; };
layout(set = 1, binding = CACHE_LIVE_VIEW_BINDING_OUTPUT, rgba16f) uniform writeonly image2D outputImage;

void main() {
  uvec2 pixel = gl_GlobalInvocationID.xy;
  if (pixel.x >= CLIPMAP_LIVE_VIEW_WIDTH || pixel.y >= CLIPMAP_LIVE_VIEW_BAR * CLIPMAP_CASCADES)
    return;
  uint cascade = pixel.y / CLIPMAP_LIVE_VIEW_BAR;
  uint live = ClipmapFrameRef(pc.buffers.frame).v.liveCells[cascade];
  float length = log2(1.0 + float(live)) / 16.0 * float(CLIPMAP_LIVE_VIEW_WIDTH);
  bool gap = pixel.y % CLIPMAP_LIVE_VIEW_BAR == CLIPMAP_LIVE_VIEW_BAR - 1u;
  vec3 color = (float(pixel.x) + 0.5 < length && !gap) ? idColor(cascade) : vec3(0.05);
  imageStore(outputImage, ivec2(pixel), vec4(color, 1.0));
}
