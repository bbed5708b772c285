// Bounce reports bad input and unusable devices with bounce::Error (include/bounce/error.h: the
// public API throws the same class); the command-line program prints what() to stderr and exits
// non-zero. Messages name the file (or option, or field) and say what was expected, e.g.
// "scene.gltf: accessor 3: count 2^40 exceeds 2^28".
#pragma once
#include <string>

#include <bounce/error.h>
#include <fmt/format.h>

namespace bounce {

template <typename... Args>
[[noreturn]] void fail(fmt::format_string<Args...> format, Args&&... args) {
  throw Error(fmt::format(format, std::forward<Args>(args)...));
}

}  // namespace bounce
