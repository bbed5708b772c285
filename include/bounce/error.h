// Bounce reports bad input and unusable devices with this exception: a file that cannot be
// loaded, an unknown scene or image name, a device without a feature Bounce needs. Messages
// name the file (or option, or field) and say what was expected, e.g.
// "scene.gltf: accessor 3: count 2^40 exceeds 2^28".
#pragma once
#include <stdexcept>
#include <string>

namespace bounce {

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace bounce
