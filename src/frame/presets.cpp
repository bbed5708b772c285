#include "frame/presets.h"

namespace bounce {

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
      s.shadows.divisor = 2;
      s.restirGi = RestirGiSettings::mobilePreset();
      break;
    case Preset::Desktop:
      s.width = 1920;
      s.height = 1080;
      s.shadows.divisor = 2;
      s.cache.raysPerCell = 4;
      s.cache.validationRaysPerCell = 4;
      s.cache.alphaTest = true;
      s.restirGi = RestirGiSettings::desktopPreset();
      break;
  }
  return s;
}

}  // namespace bounce
