// Per-pass GPU times of the last frames, for the viewer's stacked graph: one column per frame,
// the passes in recording order (the image copies, "debug-view:*", left out: they are the
// viewer's cost, not the frame's), and each pass's rolling mean over the last 9 frames (seed
// 000's figures average over 9 frames).
#pragma once
#include <cstddef>
#include <deque>
#include <string>
#include <vector>

#include "vk/gpu_timer.h"

namespace bounce::view {

class PassTimeHistory {
 public:
  explicit PassTimeHistory(size_t frames = 240) : capacity_(frames) {}

  void add(const std::vector<vk::PassTiming>& passes);
  void clear() { columns_.clear(); }

  // Every pass seen in the kept frames, in first-recorded order.
  const std::vector<std::string>& passNames() const { return names_; }
  size_t frameCount() const { return columns_.size(); }
  // Milliseconds of pass `pass` (an index into passNames()) in kept frame `frame` (0 = oldest);
  // 0 where the frame had no such pass.
  double milliseconds(size_t frame, size_t pass) const;
  double frameMilliseconds(size_t frame) const;
  // Mean over the last min(9, frameCount()) frames.
  double rollingMean(size_t pass) const;
  double rollingFrameMean() const;
  double maxFrameMilliseconds() const;

  static constexpr size_t kRollingFrames = 9;

 private:
  size_t index(const std::string& name);
  size_t capacity_;
  std::vector<std::string> names_;
  std::deque<std::vector<double>> columns_;  // per frame: ms per index into names_
};

}  // namespace bounce::view
