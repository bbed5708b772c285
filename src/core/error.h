// Bounce reports bad input and unusable devices with this exception; the command-line program
// prints what() to stderr and exits non-zero. Messages name the file (or option, or field) and
// say what was expected, e.g. "scene.gltf: accessor 3: count 2^40 exceeds 2^28".
#pragma once
#include <stdexcept>
#include <string>
#include <fmt/format.h>

namespace bounce {

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(message) {}
};

template <typename... Args>
[[noreturn]] void fail(fmt::format_string<Args...> format, Args&&... args) {
  throw Error(fmt::format(format, std::forward<Args>(args)...));
}

}  // namespace bounce
