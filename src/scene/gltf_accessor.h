// Range-checked reading of glTF accessors and buffer views (internal to the glTF loader).
// tinygltf 2.7 parses the JSON but does not check that accessors fit in their buffer views, that
// views fit in their buffers, or that counts are sane, so every read goes through here and
// either returns dense, converted data or throws bounce::Error naming the file and the problem.
#pragma once
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace tinygltf {
class Model;
}

namespace bounce {
class LoadWarnings;
}

namespace bounce::gltf {

// Largest element count we accept in one accessor (2^28: 3 GiB of float positions). Anything
// larger is treated as a corrupt file rather than allocated.
inline constexpr size_t kMaxAccessorCount = size_t(1) << 28;
// An accessor without a bufferView is all zeros (plus sparse substitutions), so its count is not
// bounded by the file size; cap it lower so a tiny file cannot demand gigabytes.
inline constexpr size_t kMaxUnbackedAccessorCount = size_t(1) << 20;

// What every read needs: the parsed model, the file path that starts each error message, and
// where non-fatal problems are collected.
struct Source {
  const tinygltf::Model& model;
  const std::string& path;
  LoadWarnings& warnings;
};

// The bytes of buffer view `index`, checked to lie inside its buffer. `what` says who refers to
// the view ("image 2") for the error message.
std::span<const uint8_t> bufferViewBytes(const Source& src, int index, const std::string& what);

// Accessor `index` as `components` floats per element, where `components` follows from
// `expectedType` (a TINYGLTF_TYPE_*; a different type is an error). Integer components are
// converted as the spec says: normalized ones to [0,1] or [-1,1], others by value. `what` names
// the use ("POSITION of mesh 2 primitive 0").
std::vector<float> readFloatAccessor(const Source& src, int index, int expectedType,
                                     const std::string& what);

// A SCALAR accessor of unsigned bytes, shorts or ints, as 32-bit indices.
std::vector<uint32_t> readIndexAccessor(const Source& src, int index, const std::string& what);

}  // namespace bounce::gltf
