#include "scene/load_warnings.h"

#include <algorithm>

#include <fmt/format.h>

namespace bounce {

namespace {

std::string singleLine(const LoadWarning& w) {
  const std::string& text = w.detail.empty() ? w.group : w.detail;
  return w.where.empty() ? text : fmt::format("{}: {}", w.where, text);
}

std::string summaryLine(const LoadWarning& first, uint64_t occurrences, uint64_t amount) {
  if (first.where.empty()) return fmt::format("{} ({} times)", first.group, occurrences);
  std::string total = first.unit.empty() ? "" : fmt::format(" ({} {})", amount, first.unit);
  return fmt::format("{}: {} {}{}, e.g. {}", first.group, occurrences, first.things, total,
                     first.where);
}

}  // namespace

void LoadWarnings::add(LoadWarning warning) {
  const uint64_t amount = warning.amount;
  auto it = std::find_if(groups_.begin(), groups_.end(),
                         [&](const Group& g) { return g.first.group == warning.group; });
  if (it == groups_.end()) {
    groups_.push_back({std::move(warning), 0, 0});
    it = groups_.end() - 1;
  }
  it->occurrences += 1;
  it->amount += amount;
}

std::vector<std::string> LoadWarnings::summary() const {
  std::vector<std::string> lines;
  for (const Group& g : groups_)
    lines.push_back(g.occurrences == 1 ? singleLine(g.first)
                                       : summaryLine(g.first, g.occurrences, g.amount));
  return lines;
}

uint64_t LoadWarnings::count(const std::string& group) const {
  for (const Group& g : groups_)
    if (g.first.group == group) return g.occurrences;
  return 0;
}

void LoadWarnings::print(std::FILE* out, const std::string& source) const {
  for (const std::string& line : summary()) fmt::print(out, "warning: {}: {}\n", source, line);
}

}  // namespace bounce
