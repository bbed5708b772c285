#include "scene/default_light.h"

#include <fmt/format.h>
#include <algorithm>

#include "scene/time_of_day.h"

namespace bounce {

namespace {

bool positive(const glm::vec3& v) {
  return v.x > 0.0f || v.y > 0.0f || v.z > 0.0f;
}

bool sunShines(const Sun& sun) {
  return sun.irradiance > 0.0f && positive(sun.color);
}

bool skyShines(const Sky& sky, const Sun& sun) {
  return sky.model == SkyModel::Daylight ? sunShines(sun) : positive(sky.radiance);
}

}  // namespace

Sun defaultSun() {
  Sun sun;
  sun.direction = -towardSunAt(kDefaultSunHours);
  sun.irradiance = kDaylightSunKilolux;  // the sun the daylight sky's scale is defined for
  sun.color = glm::vec3(1.0f);
  return sun;
}

Sky defaultSky() {
  Sky sky;
  sky.model = SkyModel::Daylight;
  sky.turbidity = 3.0f;  // clear
  return sky;
}

bool hasAnyLight(const Scene& scene) {
  if (sunShines(scene.sun) || skyShines(scene.sky, scene.sun)) return true;
  for (const PunctualLight& light : scene.lights)
    if (light.intensity > 0.0f && positive(light.color)) return true;
  constexpr float kCoreGltfMaxEmission = 1.0f;  // emissiveFactor's range without a strength
  for (const Material& material : scene.materials)
    if (std::max({material.emissive.x, material.emissive.y, material.emissive.z}) >
        kCoreGltfMaxEmission)
      return true;
  return false;
}

std::optional<std::string> applyDefaultLight(Scene& scene, const SceneOverrides& overrides,
                                             const std::string& source) {
  if (overrides.sun || overrides.sky || hasAnyLight(scene)) return std::nullopt;
  scene.sun = defaultSun();
  scene.sky = defaultSky();
  return fmt::format(
      "{} has no lights: using a daylight sky and sun at {:g} h (--sun or --sky to choose your "
      "own)",
      source, kDefaultSunHours);
}

}  // namespace bounce
