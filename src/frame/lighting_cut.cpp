#include "frame/lighting_cut.h"

#include <algorithm>
#include <cmath>

namespace bounce {

namespace {
float skyBrightness(const Sky& sky) {
  return sky.radiance.x + sky.radiance.y + sky.radiance.z;
}
}  // namespace

LightingCutDetector::LightingCutDetector(const Sun& sun, const Sky& sky, float cutDegrees)
    : sun_(sun),
      sky_(sky),
      cutDegrees_(cutDegrees),
      brightestSun_(sun.irradiance),
      brightestSky_(skyBrightness(sky)) {}

bool LightingCutDetector::next(const Sun& sun, const Sky& sky) {
  brightestSun_ = std::max(brightestSun_, sun.irradiance);
  brightestSky_ = std::max(brightestSky_, skyBrightness(sky));
  const bool lit = sun_.irradiance > 0.0f && sun.irradiance > 0.0f;
  const float cosine = glm::dot(glm::normalize(sun_.direction), glm::normalize(sun.direction));
  const bool turned = lit && cosine < std::cos(glm::radians(cutDegrees_)) - 1e-6f;
  const bool sunJumped = std::abs(sun.irradiance - sun_.irradiance) > 0.5f * brightestSun_;
  const bool skyJumped = std::abs(skyBrightness(sky) - skyBrightness(sky_)) > 0.5f * brightestSky_;
  const bool cut =
      cutDegrees_ >= 0.0f && (turned || sunJumped || skyJumped || sky.model != sky_.model);
  sun_ = sun;
  sky_ = sky;
  return cut;
}

}  // namespace bounce
