#include "vk/shader_registry.h"

#include "core/error.h"

namespace bounce::vk {

std::span<const uint32_t> embeddedShader(std::string_view name) {
  for (const detail::EmbeddedShader* s = detail::kEmbeddedShaders; s->name; ++s)
    if (name == s->name) return {s->words, s->wordCount};
  fail("no embedded shader named '{}' (is shaders/{}.comp missing?)", name, name);
}

}  // namespace bounce::vk
