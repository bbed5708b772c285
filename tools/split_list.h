// A list option of the diagnostic tools, split into its items.
#pragma once
#include <string>
#include <vector>

namespace bounce {

// The non-empty pieces of `text` between `separator`s: "a,,b" gives {"a", "b"}.
inline std::vector<std::string> splitList(const std::string& text, char separator) {
  std::vector<std::string> items;
  for (size_t start = 0; start < text.size();) {
    size_t end = text.find(separator, start);
    if (end == std::string::npos) end = text.size();
    if (end > start) items.push_back(text.substr(start, end - start));
    start = end + 1;
  }
  return items;
}

}  // namespace bounce
