#include <bounce/settings.h>

#include "api/convert.h"

namespace bounce::api {

// The preset's resolution from the one table of presets (src/render/settings.cpp), which
// Renderer::create applies in full.
RendererSettings presetSettings(Preset preset) {
  HybridSettings internal = bounce::presetSettings(toInternal(preset, "bounce::presetSettings"));
  RendererSettings s;
  s.preset = preset;
  s.width = internal.width;
  s.height = internal.height;
  return s;
}

}  // namespace bounce::api
