// Frame-graph test pass "fill": writes a pattern that changes every frame.
#version 460
#include "tests/graph_test_io.h"

layout(local_size_x = GRAPH_TEST_GROUP_SIZE, local_size_y = GRAPH_TEST_GROUP_SIZE) in;
layout(push_constant, scalar) uniform Push { GraphTestConstants pc; };
layout(binding = GRAPH_TEST_BINDING_PATTERN, r32ui) uniform writeonly uimage2D pattern;

void main() {
  uvec2 pixel = gl_GlobalInvocationID.xy;
  if (any(greaterThanEqual(pixel, pc.size))) return;
  imageStore(pattern, ivec2(pixel), uvec4(graphTestPattern(pixel, pc.frame)));
}
