#include "suggest.h"

#include <algorithm>

namespace bounce::app {

size_t editDistance(const std::string& a, const std::string& b) {
  // d[i][j]: distance between the first i characters of a and the first j of b.
  std::vector<std::vector<size_t>> d(a.size() + 1, std::vector<size_t>(b.size() + 1));
  for (size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
  for (size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
  for (size_t i = 1; i <= a.size(); ++i)
    for (size_t j = 1; j <= b.size(); ++j) {
      const size_t substitution = d[i - 1][j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1);
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, substitution});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  return d[a.size()][b.size()];
}

std::string closestName(const std::string& typed, const std::vector<std::string>& candidates) {
  std::string best;
  size_t bestDistance = std::string::npos;
  for (const std::string& c : candidates) {
    const size_t distance = editDistance(typed, c);
    if (distance < bestDistance && distance <= std::max<size_t>(2, c.size() / 3)) {
      best = c;
      bestDistance = distance;
    }
  }
  if (!best.empty() || typed.size() < 3) return best;
  std::vector<std::string> extensions;
  for (const std::string& c : candidates)
    if (c.rfind(typed, 0) == 0) extensions.push_back(c);
  return extensions.size() == 1 ? extensions[0] : std::string();
}

std::string didYouMean(const std::string& typed, const std::vector<std::string>& candidates) {
  const std::string best = closestName(typed, candidates);
  return best.empty() ? std::string() : " (did you mean " + best + "?)";
}

std::string joinNames(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

std::vector<std::string> splitNames(const std::string& commaSeparated) {
  std::vector<std::string> names;
  size_t start = 0;
  while (start < commaSeparated.size()) {
    size_t end = commaSeparated.find(',', start);
    if (end == std::string::npos) end = commaSeparated.size();
    std::string name = commaSeparated.substr(start, end - start);
    name.erase(0, name.find_first_not_of(' '));
    name.erase(name.find_last_not_of(' ') + 1);
    if (!name.empty()) names.push_back(name);
    start = end + 1;
  }
  return names;
}

}  // namespace bounce::app
