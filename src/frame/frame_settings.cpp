#include "frame/frame_settings.h"

namespace bounce {

std::optional<GiMode> giModeFromName(const std::string& name) {
  if (name == "none") return GiMode::None;
  if (name == "cache") return GiMode::Cache;
  if (name == "evolve") return GiMode::Evolve;
  return std::nullopt;
}

const char* giModeNames() {
  return "none, evolve, cache";
}

}  // namespace bounce
