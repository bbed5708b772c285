// The sun and sky at a time of day, for --time-of-day and --day-cycle.
//
// Solar model: a fixed latitude and declination (defaults: 45 degrees north at an equinox, so
// the sun rises at 6 h due east, culminates at 12 h 45 degrees above the southern horizon and
// sets at 18 h due west); solar time, no equation of time. The unit vector towards the sun in
// (east, north, up) is (-cos d sin h, cos L sin d - sin L cos d cos h, sin L sin d +
// cos L cos d cos h) for hour angle h = 15 degrees x (hours - 12) (e.g. Duffie & Beckman,
// "Solar Engineering of Thermal Processes", ch. 1). Scene axes: +Y up, -Z north, +X east,
// turned about +Y by applyTimeOfDay so that the noon sun comes from the azimuth of the scene's
// own sun (a scene built around its sun, like sunroom's window, keeps it at midday).
//
// Day and night: above the horizon the sun keeps the scene's irradiance and colour, faded
// linearly to 0 over the last kTwilightDegrees of elevation so sunset has no pop (a daylight
// sky fades with it, as its scale follows the sun's irradiance). Below the horizon there is no
// sun and the sky becomes a dim constant night sky (kNightSkyFraction of the day sky's
// brightness, bluish: moonlight and airglow stand-in), so a night frame is dark but not black.
#pragma once
#include "scene/scene.h"

namespace bounce {

struct SolarSite {
  float latitudeDegrees = 45.0f;
  float declinationDegrees = 0.0f;
};

inline constexpr float kTwilightDegrees = 4.0f;
inline constexpr float kNightSkyFraction = 0.005f;

// Unit vector towards the sun at `hours` (solar time, wrapped into [0, 24)), unturned.
glm::vec3 towardSunAt(float hours, const SolarSite& site = {});
// Elevation above the horizon in degrees (negative at night).
float sunElevationDegrees(float hours, const SolarSite& site = {});

// `day` is the scene's sun and sky at full daylight (its irradiance and colour, its sky model);
// returns them at `hours`: the model's direction (turned as above), faded irradiance, sky.
void applyTimeOfDay(float hours, const Sun& daySun, const Sky& daySky, Sun& sun, Sky& sky,
                    const SolarSite& site = {});

}  // namespace bounce
