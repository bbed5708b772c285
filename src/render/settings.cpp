#include "render/settings.h"

namespace bounce {

std::optional<VBufferMode> vbufferModeFromName(const std::string& name) {
  if (name == "raster") return VBufferMode::Raster;
  if (name == "trace") return VBufferMode::Trace;
  return std::nullopt;
}

std::optional<GiMode> giModeFromName(const std::string& name) {
  if (name == "none") return GiMode::None;
  if (name == "cache") return GiMode::Cache;
  if (name == "evolve") return GiMode::Evolve;
  return std::nullopt;
}

const char* giModeNames() {
  return "none, evolve, cache";
}

std::optional<Preset> presetFromName(const std::string& name) {
  if (name == "mobile") return Preset::Mobile;
  if (name == "desktop") return Preset::Desktop;
  return std::nullopt;
}

const char* presetNames() {
  return "mobile, desktop";
}

HybridSettings presetSettings(Preset preset) {
  HybridSettings s;
  switch (preset) {
    case Preset::Mobile:
      s.width = 1170;
      s.height = 540;
      s.shadowDivisor = 2;
      s.restirGi = RestirGiSettings::mobilePreset();
      break;
    case Preset::Desktop:
      s.width = 1920;
      s.height = 1080;
      s.shadowDivisor = 2;
      s.cache.raysPerCell = 4;
      s.cache.validationRaysPerCell = 4;
      s.cache.alphaTest = true;
      s.restirGi = RestirGiSettings::desktopPreset();
      break;
  }
  return s;
}

}  // namespace bounce
