#include "pass_time_history.h"

#include <algorithm>

namespace bounce::view {

size_t PassTimeHistory::index(const std::string& name) {
  auto it = std::find(names_.begin(), names_.end(), name);
  if (it != names_.end()) return size_t(it - names_.begin());
  names_.push_back(name);
  return names_.size() - 1;
}

void PassTimeHistory::add(const std::vector<vk::PassTiming>& passes) {
  std::vector<double> column(names_.size(), 0.0);
  for (const vk::PassTiming& p : passes) {
    if (p.name.rfind("debug-view:", 0) == 0) continue;
    size_t i = index(p.name);
    if (i >= column.size()) column.resize(i + 1, 0.0);
    column[i] += p.milliseconds;
  }
  columns_.push_back(std::move(column));
  while (columns_.size() > capacity_) columns_.pop_front();
}

double PassTimeHistory::milliseconds(size_t frame, size_t pass) const {
  const std::vector<double>& column = columns_.at(frame);
  return pass < column.size() ? column[pass] : 0.0;
}

double PassTimeHistory::frameMilliseconds(size_t frame) const {
  double sum = 0.0;
  for (double ms : columns_.at(frame)) sum += ms;
  return sum;
}

double PassTimeHistory::rollingMean(size_t pass) const {
  const size_t n = std::min(kRollingFrames, columns_.size());
  if (n == 0) return 0.0;
  double sum = 0.0;
  for (size_t i = columns_.size() - n; i < columns_.size(); ++i) sum += milliseconds(i, pass);
  return sum / double(n);
}

double PassTimeHistory::rollingFrameMean() const {
  double sum = 0.0;
  for (size_t p = 0; p < names_.size(); ++p) sum += rollingMean(p);
  return sum;
}

double PassTimeHistory::maxFrameMilliseconds() const {
  double m = 0.0;
  for (size_t i = 0; i < columns_.size(); ++i) m = std::max(m, frameMilliseconds(i));
  return m;
}

}  // namespace bounce::view
