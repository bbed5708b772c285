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

// The table of what each preset changes (DESIGN.md §4, seed 000); every other field keeps the
// default its owner documents.
HybridSettings presetSettings(Preset preset) {
  HybridSettings s;
  s.restirGi.secondVertex = RestirGiSecondVertex::Cache;  // both presets: the clipmap cache at x2
  switch (preset) {
    case Preset::Mobile:
      s.width = 1170;
      s.height = 540;
      s.shadows.divisor = 2;                  // half-resolution shadows
      s.reflections.divisor = 2;              // half-resolution reflections
      s.restirGi.divisor = 4;                 // quarter-resolution diffuse GI
      s.restirGi.occluderVisibility = false;  // its rays cost too much of the mobile budget
      s.cache.raysPerCell = 1;
      s.cache.validationRaysPerCell = 0;
      s.cache.alphaTest = false;
      s.gi10.spawnTile = 32;  // GI-1.0's SixteenthSpp: 1/16 probe ray per pixel
      s.gi10.alphaTest = false;
      break;
    case Preset::Desktop:
      s.width = 1920;
      s.height = 1080;
      s.shadows.divisor = 2;             // half-resolution shadows
      s.reflections.divisor = 2;         // half-resolution reflections
      s.restirGi.divisor = 2;            // half-resolution diffuse GI
      s.restirGi.spatialDenoise = true;  // seed 000's "additional spatial denoising step"
      s.cache.raysPerCell = 4;
      s.cache.validationRaysPerCell = 4;
      s.cache.alphaTest = true;
      break;
  }
  return s;
}

}  // namespace bounce
