#include "tools/soak_check.h"

#include <malloc.h>
#include <unistd.h>

#include <fstream>

#include <fmt/format.h>

namespace bounce {

uint64_t residentSetBytes() {
  std::ifstream statm("/proc/self/statm");
  uint64_t sizePages = 0, residentPages = 0;
  if (!(statm >> sizePages >> residentPages)) return 0;
  return residentPages * uint64_t(sysconf(_SC_PAGESIZE));
}

uint64_t heapInUseBytes() {
#if defined(__GLIBC__) && (__GLIBC__ > 2 || (__GLIBC__ == 2 && __GLIBC_MINOR__ >= 33))
  const struct mallinfo2 info = mallinfo2();
  return uint64_t(info.uordblks) + uint64_t(info.hblkhd);
#else
  return 0;
#endif
}

SoakCheck::SoakCheck(uint32_t warmupFrames, uint64_t maxResidentGrowthBytes)
    : warmupFrames_(warmupFrames), maxResidentGrowth_(maxResidentGrowthBytes) {}

void SoakCheck::add(const SoakSample& s) {
  ++frames_;
  last_ = s;
  if (s.nonFinitePixels > 0) {
    ++nonFiniteFrames_;
    if (!firstNonFinite_) firstNonFinite_ = s;
  }
  if (s.frame < warmupFrames_) return;
  if (!afterWarmup_) afterWarmup_ = s;
  if (!firstDeviceChange_ && (s.deviceBytes != afterWarmup_->deviceBytes ||
                              s.deviceAllocations != afterWarmup_->deviceAllocations))
    firstDeviceChange_ = s;
  peakResident_ = std::max(peakResident_, s.residentBytes);
  const double x = s.frame, y = double(s.residentBytes);
  n_ += 1;
  sumX_ += x;
  sumY_ += y;
  sumXX_ += x * x;
  sumXY_ += x * y;
}

double SoakCheck::residentSlopeBytesPerFrame() const {
  const double d = n_ * sumXX_ - sumX_ * sumX_;
  return n_ < 2 || d <= 0 ? 0.0 : (n_ * sumXY_ - sumX_ * sumY_) / d;
}

std::vector<std::string> SoakCheck::failures() const {
  std::vector<std::string> out;
  const double mib = double(1 << 20);
  if (firstNonFinite_)
    out.push_back(fmt::format(
        "{} of {} frames have NaN or infinite pixels (first: frame {}, {} "
        "pixels)",
        nonFiniteFrames_, frames_, firstNonFinite_->frame, firstNonFinite_->nonFinitePixels));
  if (!afterWarmup_) {
    out.push_back(
        fmt::format("the run has {} frames, no more than the warm-up of {}: memory "
                    "growth was not checked",
                    frames_, warmupFrames_));
    return out;
  }
  if (firstDeviceChange_)
    out.push_back(fmt::format(
        "device memory changed after the warm-up: {:.2f} MiB in {} allocations at frame {}, "
        "{:.2f} MiB in {} at frame {}",
        double(afterWarmup_->deviceBytes) / mib, afterWarmup_->deviceAllocations,
        afterWarmup_->frame, double(firstDeviceChange_->deviceBytes) / mib,
        firstDeviceChange_->deviceAllocations, firstDeviceChange_->frame));
  if (peakResident_ > afterWarmup_->residentBytes + maxResidentGrowth_)
    out.push_back(fmt::format(
        "host memory grew after the warm-up: resident {:.1f} MiB at frame {}, peak {:.1f} MiB "
        "(allowed growth {:.1f} MiB; slope {:.0f} bytes a frame)",
        double(afterWarmup_->residentBytes) / mib, afterWarmup_->frame, double(peakResident_) / mib,
        double(maxResidentGrowth_) / mib, residentSlopeBytesPerFrame()));
  return out;
}

}  // namespace bounce
