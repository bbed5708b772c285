#include "progress.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace bounce::app {

ProgressLine::ProgressLine() : enabled_(::isatty(STDERR_FILENO) != 0) {}

void ProgressLine::draw(double fraction, const std::string& detail, double seconds,
                        double etaSeconds) {
  if (!enabled_) return;
  constexpr int kWidth = 30;
  fraction = std::clamp(fraction, 0.0, 1.0);
  const int filled = int(std::round(fraction * kWidth));
  std::string bar(size_t(filled), '#');
  bar.append(size_t(kWidth - filled), '-');
  // Trailing spaces clear what a longer previous line left behind.
  std::fprintf(stderr, "\r[%s] %3d%%  %s  %.1f s  ETA %.1f s   ", bar.c_str(),
               int(std::round(100.0 * fraction)), detail.c_str(), seconds, etaSeconds);
  std::fflush(stderr);
  drawn_ = true;
}

void ProgressLine::finish() {
  if (drawn_) std::fputc('\n', stderr);
  drawn_ = false;
}

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace bounce::app
