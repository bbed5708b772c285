// The frame-graph GPU test (tests/test_frame_graph_gpu.cpp): constants, bindings, and the two
// rules its passes apply, so the test can compute the exact expected values on the CPU.
#ifndef BOUNCE_TESTS_GRAPH_TEST_IO_H
#define BOUNCE_TESTS_GRAPH_TEST_IO_H
#include "shared/compat.h"

BOUNCE_BEGIN_SHARED

BOUNCE_CONST uint GRAPH_TEST_GROUP_SIZE = 8u;

// graph_fill: binding 0 is the pattern (storage, written).
// graph_blend: 0 the pattern (sampled), 1 last frame's accumulation, 2 this frame's (storage).
// graph_sum_rows: binding 0 is this frame's accumulation (storage, read).
BOUNCE_CONST uint GRAPH_TEST_BINDING_PATTERN = 0u;
BOUNCE_CONST uint GRAPH_TEST_BINDING_PREVIOUS = 1u;
BOUNCE_CONST uint GRAPH_TEST_BINDING_CURRENT = 2u;
BOUNCE_CONST uint GRAPH_TEST_BINDING_ACCUMULATION = 0u;

struct GraphTestConstants {
  DeviceAddress rowSums;  // uint[height], written by graph_sum_rows
  uvec2 size;
  uint frame;
  uint historyValid;  // 0 in the first frame and after a history reset
};
BOUNCE_CHECK_SIZE(GraphTestConstants, 24);

// What graph_fill writes at `pixel` in `frame`.
BOUNCE_FN uint graphTestPattern(uvec2 pixel, uint frame) {
  return pixel.x + 7u * pixel.y + 13u * frame + 1u;
}

// What graph_blend writes: the pattern plus last frame's value here and twice that of the right
// neighbour (clamped at the edge), wrapping like all uint arithmetic.
BOUNCE_FN uint graphTestBlend(uint pattern, uint previousHere, uint previousRight) {
  return pattern + previousHere + 2u * previousRight;
}

BOUNCE_END_SHARED
#endif
