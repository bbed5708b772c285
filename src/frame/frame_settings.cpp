#include "frame/frame_settings.h"

#include <cmath>

#include "core/error.h"

namespace bounce {

std::optional<GiMode> giModeFromName(const std::string& name) {
  if (name == "none") return GiMode::None;
  if (name == "cache") return GiMode::Cache;
  if (name == "evolve") return GiMode::Evolve;
  if (name == "lux") return GiMode::Lux;
  if (name == "gi10") return GiMode::Gi10;
  return std::nullopt;
}

const char* giModeNames() {
  return "none, evolve, cache, lux, gi10";
}

void validate(const HybridSettings& s) {
  if (s.width == 0 || s.height == 0 || s.width > 16384 || s.height > 16384)
    fail("resolution {}x{}: expected 1 to 16384 pixels a side", s.width, s.height);
  if (s.shadows.divisor == 0 || s.shadows.divisor > 16)
    fail("shadow divisor {}: expected 1 to 16", s.shadows.divisor);
  validate(s.reflections);
  validate(s.reflectionDenoise);
  if (!(s.shadows.maxHistory >= 1.0f))
    fail("shadow history {} frames: expected at least 1", s.shadows.maxHistory);
  if (!(std::abs(s.exposureStops) <= 64.0f))
    fail("exposure {} stops: expected -64 to 64", s.exposureStops);
  if (s.autoExposure) validate(s.exposure);
  if (s.taa.enabled) validate(s.taa);
  if (!(s.skyAmbientStrength >= 0.0f) || !std::isfinite(s.skyAmbientStrength))
    fail("sky ambient {}: must be >= 0", s.skyAmbientStrength);
  if (s.di.enabled()) validate(s.di);
  if (s.gi == GiMode::Evolve) validate(s.restirGi);
  if (s.gi == GiMode::Lux) validate(s.lux);
  if (s.gi == GiMode::Gi10) validate(s.gi10);
  if (s.gi == GiMode::Cache || s.gi == GiMode::Lux ||
      (s.gi == GiMode::Evolve && s.restirGi.secondVertex == RestirGiSecondVertex::Cache))
    validate(s.cache);
}

}  // namespace bounce
