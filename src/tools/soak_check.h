// What `bounce bench --soak` checks over a long animated run (issue 24): every frame's pixels
// finite, and neither host memory (the resident set) nor Bounce's device memory growing after a
// warm-up. Kept apart from the bench so that a test can feed it frames that must fail.
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace bounce {

// The process's resident set now (Linux: /proc/self/statm); 0 where it cannot be read.
uint64_t residentSetBytes();
// Bytes the C heap has handed out and not had back (glibc mallinfo2: arena and mmapped chunks
// in use), every thread's arena included; 0 where unknown. Against the resident set it tells a
// leak (both grow) from fragmentation or pages touched late (only the resident set grows).
uint64_t heapInUseBytes();

struct SoakSample {
  uint32_t frame = 0;
  uint64_t nonFinitePixels = 0;
  uint64_t residentBytes = 0;
  uint64_t deviceBytes = 0;  // Bounce's live device memory (vk::Context)
  uint64_t deviceAllocations = 0;
  uint64_t heapInUseBytes = 0;  // a diagnostic beside residentBytes, not checked
};

class SoakCheck {
 public:
  // Memory is compared from frame `warmupFrames` on (the caches, pipelines and the allocator's
  // arenas settle in the first frames). A leak of k bytes a frame grows the resident set by
  // k x frames, so `maxResidentGrowthBytes` over n frames finds any leak above about
  // maxResidentGrowthBytes / n bytes a frame (docs/testing.md, "Soak").
  SoakCheck(uint32_t warmupFrames, uint64_t maxResidentGrowthBytes);

  void add(const SoakSample& sample);

  bool passed() const { return failures().empty(); }
  // One sentence per broken rule, naming the frame and the numbers.
  std::vector<std::string> failures() const;

  uint32_t frames() const { return frames_; }
  uint32_t warmupFrames() const { return warmupFrames_; }
  uint32_t nonFiniteFrames() const { return nonFiniteFrames_; }
  std::optional<SoakSample> firstNonFinite() const { return firstNonFinite_; }
  std::optional<SoakSample> afterWarmup() const { return afterWarmup_; }
  std::optional<SoakSample> last() const { return last_; }
  uint64_t peakResidentAfterWarmup() const { return peakResident_; }
  // Least-squares slope of the resident set over the frames after the warm-up (bytes a frame).
  double residentSlopeBytesPerFrame() const;

 private:
  uint32_t warmupFrames_;
  uint64_t maxResidentGrowth_;
  uint32_t frames_ = 0;
  uint32_t nonFiniteFrames_ = 0;
  std::optional<SoakSample> firstNonFinite_, afterWarmup_, last_, firstDeviceChange_;
  uint64_t peakResident_ = 0;
  // Sums for the slope: frames after the warm-up, x = frame, y = resident bytes.
  double n_ = 0, sumX_ = 0, sumY_ = 0, sumXX_ = 0, sumXY_ = 0;
};

}  // namespace bounce
