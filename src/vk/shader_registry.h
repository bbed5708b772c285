// SPIR-V compiled at build time by glslc and embedded in the binary (cmake/shaders.cmake).
// Shaders are named by their path under shaders/ without the extension: "rt/trace_rays".
#pragma once
#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>

namespace bounce::vk {

namespace detail {
struct EmbeddedShader {
  const char* name;
  const uint32_t* words;
  size_t wordCount;
};
extern const EmbeddedShader kEmbeddedShaders[];  // ends with a null name
}  // namespace detail

// Throws bounce::Error if no shader has that name.
std::span<const uint32_t> embeddedShader(std::string_view name);

}  // namespace bounce::vk
