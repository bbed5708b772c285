// A frame's debug view as raw texels, for the tests that read the G-buffer and vbuffer images
// of a HybridFrame (ids, velocity, depth) by pixel.
#pragma once
#include <cstring>
#include <string>
#include <vector>

#include "frame/hybrid_frame.h"

namespace bounce::test {

// The texels of `view` (requested with requestDebugView before the frame), rows top to bottom,
// as T (e.g. glm::uvec4 for vbuffer.ids, glm::u16vec2 for gbuffer.velocity).
template <typename T>
std::vector<T> texels(const HybridFrame& frame, const std::string& view) {
  const graph::DebugView& v = frame.graph().readDebugView(view);
  std::vector<T> out(v.bytes.size() / sizeof(T));
  std::memcpy(out.data(), v.bytes.data(), out.size() * sizeof(T));
  return out;
}

}  // namespace bounce::test
