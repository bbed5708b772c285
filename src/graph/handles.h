// Handles to the resources declared in one frame. Images and buffers have distinct types so a
// buffer can never be bound where an image is expected.
#pragma once
#include <cstdint>

namespace bounce::graph {

constexpr uint32_t kNoResource = UINT32_MAX;
constexpr uint32_t kNoBinding = UINT32_MAX;

struct ImageHandle {
  uint32_t index = kNoResource;
  bool valid() const { return index != kNoResource; }
};

struct BufferHandle {
  uint32_t index = kNoResource;
  bool valid() const { return index != kNoResource; }
};

// A history resource seen from one frame: passes write `current`, read `previous` (what
// `current` was last frame). The two swap at the end of each frame.
struct HistoryImage {
  ImageHandle current;
  ImageHandle previous;
};

struct HistoryBuffer {
  BufferHandle current;
  BufferHandle previous;
};

}  // namespace bounce::graph
