// The light a scene without any light gets, as glTF viewers give one: the built-in daylight
// (time_of_day.h: 45 degrees north at an equinox) at mid-morning, a sun of kDaylightSunKilolux
// and the Preetham clear sky it drives. Mid-morning, not noon: a sun 38 degrees up from the
// south-east lights tops and fronts differently, so shapes read, and it stands behind the
// default camera (which looks from +Z), so the side the camera sees is lit.
//
// "Without any light" means: no sun, a black sky (a constant sky of radiance 0, or a daylight
// sky without a sun), no KHR_lights_punctual light of positive intensity and no material that
// emits more than radiance 1. glTF's core emissiveFactor stops at 1: a file that means its
// emission to light a room (the Cornell box's lamp: 17) raises it with
// KHR_materials_emissive_strength, while emission at or below 1 is a glowing detail (the
// DamagedHelmet's displays), which would otherwise leave the model black. An explicit --sun or
// --sky replaces this default altogether, so `--sky 0,0,0` keeps an unlit scene dark.
#pragma once
#include <optional>
#include <string>

#include "scene/scene.h"
#include "scene/scene_options.h"

namespace bounce {

inline constexpr float kDefaultSunHours = 10.0f;

Sun defaultSun();
Sky defaultSky();

// Whether anything in the scene lights it (see above).
bool hasAnyLight(const Scene& scene);

// Gives an unlit scene the default sun and sky unless `overrides` sets the sun or the sky.
// Returns the line that says so ("<source> has no lights: using ..."), or nothing when the
// scene keeps its own light.
std::optional<std::string> applyDefaultLight(Scene& scene, const SceneOverrides& overrides,
                                             const std::string& source);

}  // namespace bounce
