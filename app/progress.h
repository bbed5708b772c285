// The progress line long verbs draw on stderr: "[#####-----]  50%  4/8 frames  1.2 s/frame
// 4.8 s  ETA 4.8 s", redrawn in place. Only on a terminal: piped or redirected output gets no
// carriage returns, only the verb's final summary.
#pragma once
#include <chrono>
#include <string>

namespace bounce::app {

class ProgressLine {
 public:
  ProgressLine();  // enabled when stderr is a terminal

  bool enabled() const { return enabled_; }
  // fraction in [0, 1]; `detail` says what was done ("29 spp", "3/8 frames  120 ms/frame").
  void draw(double fraction, const std::string& detail, double seconds, double etaSeconds);
  // Ends the line (once something was drawn), so that what follows starts on its own line.
  void finish();

 private:
  bool enabled_ = false;
  bool drawn_ = false;
};

// Seconds since `start`.
double secondsSince(std::chrono::steady_clock::time_point start);

}  // namespace bounce::app
