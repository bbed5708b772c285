// Lighting cuts: a change of sun or sky that is no longer motion (the GI systems then rebuild
// their light quickly while the view's history stays valid).
#pragma once
#include "scene/scene.h"

namespace bounce {

// Tells a lighting cut from motion (HybridSettings::lightingCutDegrees): from one sun and sky
// to the next, the lit sun turned by more than cutDegrees, or the sun's irradiance or the
// sky's radiance changed by more than half of the brightest seen so far (so that a sun
// fading out at dusk, step by small step, is motion, and switching it off is a cut), or the
// sky model changed. cutDegrees < 0: never a cut.
class LightingCutDetector {
 public:
  LightingCutDetector(const Sun& sun, const Sky& sky, float cutDegrees);
  // Takes the next sun and sky; whether they are a cut from the last ones.
  bool next(const Sun& sun, const Sky& sky);

 private:
  Sun sun_;
  Sky sky_;
  float cutDegrees_;
  float brightestSun_;  // irradiance, W/m^2
  float brightestSky_;  // radiance summed over r, g, b
};

}  // namespace bounce
