// The presets of seed 000 (DESIGN.md §4): one table of the fields each preset sets; every other
// field keeps the default its owner documents.
#pragma once
#include <optional>
#include <string>

#include "frame/frame_settings.h"

namespace bounce {

enum class Preset { Mobile, Desktop };
std::optional<Preset> presetFromName(const std::string& name);  // "mobile", "desktop"
const char* presetNames();

// The preset's settings (resolution, shadow resolution, cache rays, ReSTIR GI); other fields
// keep their defaults.
HybridSettings presetSettings(Preset preset);

}  // namespace bounce
