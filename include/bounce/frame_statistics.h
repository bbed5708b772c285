// What Renderer::render reports about the frame it rendered.
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "bounce/config.h"

namespace bounce::api {

struct PassTime {
  // The pass's stable name (DESIGN.md §4: "vbuffer", "gbuffer", "shadows-trace",
  // "gi-restir-temporal", ..., "composite", "tonemap"). "debug-view:NAME" is the copy of an
  // image requested with Renderer::requestImage (and "debug-view:tonemap", always there).
  std::string name;
  double milliseconds = 0.0;  // GPU time from the device's timestamps
};

struct FrameStatistics {
  // 0 for the first frame a Renderer renders, then counting up (resetHistory does not reset it).
  uint64_t frameIndex = 0;
  // Every pass in recording order. Empty when the device's queue has no timestamps.
  std::vector<PassTime> passes;

  // The pass's milliseconds; nullopt when the frame has no pass of that name.
  std::optional<double> milliseconds(std::string_view pass) const {
    for (const PassTime& p : passes)
      if (p.name == pass) return p.milliseconds;
    return std::nullopt;
  }
  // The frame's GPU time: every pass but the image copies ("debug-view:*").
  double gpuMilliseconds() const {
    double sum = 0.0;
    for (const PassTime& p : passes)
      if (p.name.rfind("debug-view:", 0) != 0) sum += p.milliseconds;
    return sum;
  }
};

}  // namespace bounce::api
