// Frame-graph test pass "blend": samples the pattern and reads last frame's accumulation (a
// history image) at this pixel and its right neighbour.
#version 460
#extension GL_EXT_samplerless_texture_functions : require
#include "tests/graph_test_io.h"

layout(local_size_x = GRAPH_TEST_GROUP_SIZE, local_size_y = GRAPH_TEST_GROUP_SIZE) in;
layout(push_constant, scalar) uniform Push { GraphTestConstants pc; };
layout(binding = GRAPH_TEST_BINDING_PATTERN) uniform utexture2D pattern;
layout(binding = GRAPH_TEST_BINDING_PREVIOUS, r32ui) uniform readonly uimage2D previous;
layout(binding = GRAPH_TEST_BINDING_CURRENT, r32ui) uniform writeonly uimage2D current;

void main() {
  uvec2 pixel = gl_GlobalInvocationID.xy;
  if (any(greaterThanEqual(pixel, pc.size))) return;
  uint here = 0u, right = 0u;
  if (pc.historyValid != 0u) {
    here = imageLoad(previous, ivec2(pixel)).r;
    right = imageLoad(previous, ivec2(min(pixel.x + 1u, pc.size.x - 1u), pixel.y)).r;
  }
  uint value = graphTestBlend(texelFetch(pattern, ivec2(pixel), 0).r, here, right);
  imageStore(current, ivec2(pixel), uvec4(value));
}
