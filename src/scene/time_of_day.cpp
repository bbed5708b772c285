#include "scene/time_of_day.h"

#include <algorithm>
#include <cmath>

namespace bounce {

glm::vec3 towardSunAt(float hours, const SolarSite& site) {
  float h = glm::radians(15.0f * (std::fmod(std::fmod(hours, 24.0f) + 24.0f, 24.0f) - 12.0f));
  float lat = glm::radians(site.latitudeDegrees);
  float dec = glm::radians(site.declinationDegrees);
  float east = -std::cos(dec) * std::sin(h);
  float north = std::cos(lat) * std::sin(dec) - std::sin(lat) * std::cos(dec) * std::cos(h);
  float up = std::sin(lat) * std::sin(dec) + std::cos(lat) * std::cos(dec) * std::cos(h);
  return glm::normalize(glm::vec3(east, up, -north));
}

float sunElevationDegrees(float hours, const SolarSite& site) {
  return glm::degrees(std::asin(std::clamp(towardSunAt(hours, site).y, -1.0f, 1.0f)));
}

void applyTimeOfDay(float hours, const Sun& daySun, const Sky& daySky, Sun& sun, Sky& sky,
                    const SolarSite& site) {
  glm::vec3 toward = towardSunAt(hours, site);
  // The scene's own sun fixes the compass: the noon sun comes from its azimuth (the model's
  // noon sun is due south, +Z), so a room built around its sun keeps it at midday.
  glm::vec2 authored(-daySun.direction.x, -daySun.direction.z);
  if (glm::length(authored) > 1e-4f) {
    authored = glm::normalize(authored);  // (sin a, cos a) of the authored azimuth from +Z
    glm::vec2 xz(toward.x, toward.z);
    // Rotate +Z onto `authored`: x' = x cos a + z sin a, z' = -x sin a + z cos a.
    toward.x = xz.x * authored.y + xz.y * authored.x;
    toward.z = -xz.x * authored.x + xz.y * authored.y;
  }
  float elevation = glm::degrees(std::asin(std::clamp(toward.y, -1.0f, 1.0f)));
  sun = daySun;
  sun.direction = -toward;
  sky = daySky;
  float fade = std::clamp(elevation / kTwilightDegrees, 0.0f, 1.0f);
  sun.irradiance = daySun.irradiance * fade;
  if (elevation > 0.0f) {
    // A constant day sky dims with the sun too; a daylight sky already follows its irradiance.
    if (daySky.model == SkyModel::Constant)
      sky.radiance = daySky.radiance * std::max(fade, kNightSkyFraction);
    return;
  }
  // Night: the day sky's brightness stands for "sky"; the Preetham sky's zenith is roughly the
  // sun's irradiance / pi x 0.1 in these units (a clear day's zenith luminance is ~10% of the
  // sun's direct-normal illuminance / pi per steradian).
  float dayLevel = daySky.model == SkyModel::Daylight
                       ? 0.1f * daySun.irradiance / float(M_PI)
                       : std::max({daySky.radiance.x, daySky.radiance.y, daySky.radiance.z});
  sky.model = SkyModel::Constant;
  sky.radiance = kNightSkyFraction * dayLevel * glm::vec3(0.6f, 0.75f, 1.0f);
}

}  // namespace bounce
