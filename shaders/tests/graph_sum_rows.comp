// Frame-graph test pass "sum-rows": one invocation per row sums the accumulation into a buffer
// reached through its device address.
#version 460
#include "tests/graph_test_io.h"

layout(local_size_x = GRAPH_TEST_GROUP_SIZE) in;
layout(push_constant, scalar) uniform Push { GraphTestConstants pc; };
layout(binding = GRAPH_TEST_BINDING_ACCUMULATION, r32ui) uniform readonly uimage2D accumulation;
layout(buffer_reference, scalar, buffer_reference_align = 4) writeonly buffer RowSums { uint v[]; };

void main() {
  uint row = gl_GlobalInvocationID.x;
  if (row >= pc.size.y) return;
  uint sum = 0u;
  for (uint x = 0u; x < pc.size.x; ++x) sum += imageLoad(accumulation, ivec2(x, row)).r;
  RowSums(pc.rowSums).v[row] = sum;
}
