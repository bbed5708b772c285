// The analytic clear-sky model of Preetham, Shirley and Smits 1999, "A Practical Analytic Model
// for Daylight" (SIGGRAPH 99), shared by the reference path tracer and the real-time sky.
//
// The sky's luminance Y and CIE chromaticity (x, y) in a direction at zenith angle theta, at
// angle gamma from the sun, follow the all-weather formula of Perez et al. (1993)
//   F(theta, gamma) = (1 + A exp(B / cos theta)) (1 + C exp(D gamma) + E cos^2 gamma),
// normalised by its value at the zenith:  Y = Y_zenith F(theta, gamma) / F(0, theta_sun),
// and likewise for x and y. The five coefficients are linear in the turbidity T (the paper's
// Appendix A.2: 2 = very clear, 3 = clear, 6 = hazy, 10 = thin overcast); the zenith values
// are the paper's fits in T and theta_sun. The model is meant for T in [2, 10] and the sun
// above the horizon; we fade it to black while the sun sinks from the horizon to 6 degrees
// below it (civil twilight, which the model does not describe), and directions below the
// horizon see the horizon's value (cos theta clamped to 0), a stand-in for the ground.
//
// Output: linear Rec. 709 RGB whose luminance is the model's Y in kcd/m^2; callers scale it
// into their radiance units.
#ifndef BOUNCE_COMMON_SKY_GLSL
#define BOUNCE_COMMON_SKY_GLSL

struct PerezCoefficients {
  float A;
  float B;
  float C;
  float D;
  float E;
};

float perezFunction(PerezCoefficients c, float cosTheta, float gamma, float cosGamma) {
  return (1.0 + c.A * exp(c.B / cosTheta)) * (1.0 + c.C * exp(c.D * gamma) + c.E * cosGamma * cosGamma);
}

PerezCoefficients perezLuminance(float T) {
  return PerezCoefficients(0.1787 * T - 1.4630, -0.3554 * T + 0.4275, -0.0227 * T + 5.3251,
                           0.1206 * T - 2.5771, -0.0670 * T + 0.3703);
}

PerezCoefficients perezChromaticityX(float T) {
  return PerezCoefficients(-0.0193 * T - 0.2592, -0.0665 * T + 0.0008, -0.0004 * T + 0.2125,
                           -0.0641 * T - 0.8989, -0.0033 * T + 0.0452);
}

PerezCoefficients perezChromaticityY(float T) {
  return PerezCoefficients(-0.0167 * T - 0.2608, -0.0950 * T + 0.0092, -0.0079 * T + 0.2102,
                           -0.0441 * T - 1.6537, -0.0109 * T + 0.0529);
}

// Zenith luminance in kcd/m^2 for the sun at zenith angle thetaSun (radians).
float daylightZenithLuminance(float thetaSun, float T) {
  float chi = (4.0 / 9.0 - T / 120.0) * (3.14159265358979 - 2.0 * thetaSun);
  return max((4.0453 * T - 4.9710) * tan(chi) - 0.2155 * T + 2.4192, 0.0);
}

// Zenith chromaticity (x, y): [T^2 T 1] M [thetaSun^3 thetaSun^2 thetaSun 1]^T.
vec2 daylightZenithChromaticity(float thetaSun, float T) {
  vec4 s = vec4(thetaSun * thetaSun * thetaSun, thetaSun * thetaSun, thetaSun, 1.0);
  vec3 t = vec3(T * T, T, 1.0);
  float x = t.x * dot(vec4(0.00166, -0.00375, 0.00209, 0.0), s) +
            t.y * dot(vec4(-0.02903, 0.06377, -0.03202, 0.00394), s) +
            t.z * dot(vec4(0.11693, -0.21196, 0.06052, 0.25886), s);
  float y = t.x * dot(vec4(0.00275, -0.00610, 0.00317, 0.0), s) +
            t.y * dot(vec4(-0.04214, 0.08970, -0.04153, 0.00516), s) +
            t.z * dot(vec4(0.15346, -0.26756, 0.06670, 0.26688), s);
  return vec2(x, y);
}

// CIE xyY to linear Rec. 709 RGB (D65).
vec3 xyYToLinearRgb(float x, float y, float Y) {
  float X = x / max(y, 1e-6) * Y;
  float Z = (1.0 - x - y) / max(y, 1e-6) * Y;
  return vec3(3.2404542 * X - 1.5371385 * Y - 0.4985314 * Z,
              -0.9692660 * X + 1.8760108 * Y + 0.0415560 * Z,
              0.0556434 * X - 0.2040259 * Y + 1.0572252 * Z);
}

// Sky radiance towards `direction` (unit, +Y up) for the sun towards `towardSun` (unit), as
// linear RGB with luminance in kcd/m^2.
vec3 daylightSky(vec3 direction, vec3 towardSun, float turbidity) {
  float twilight = smoothstep(-0.1045, 0.0, towardSun.y);  // sin(-6 degrees) .. horizon
  if (twilight <= 0.0) return vec3(0.0);
  float thetaSun = acos(clamp(towardSun.y, 0.0, 1.0));
  float cosTheta = max(direction.y, 0.0);
  float cosGamma = clamp(dot(direction, towardSun), -1.0, 1.0);
  float gamma = acos(cosGamma);
  float cosThetaSun = cos(thetaSun);
  // exp(B / cos theta) has B < 0: it goes to 0 at the horizon, where a tiny cos would overflow
  // the division; 1e-3 is well past that limit.
  float safeCosTheta = max(cosTheta, 1e-3);

  PerezCoefficients cY = perezLuminance(turbidity);
  PerezCoefficients cx = perezChromaticityX(turbidity);
  PerezCoefficients cy = perezChromaticityY(turbidity);
  vec2 zenithXy = daylightZenithChromaticity(thetaSun, turbidity);
  float Y = daylightZenithLuminance(thetaSun, turbidity) *
            perezFunction(cY, safeCosTheta, gamma, cosGamma) /
            perezFunction(cY, 1.0, thetaSun, cosThetaSun);
  float x = zenithXy.x * perezFunction(cx, safeCosTheta, gamma, cosGamma) /
            perezFunction(cx, 1.0, thetaSun, cosThetaSun);
  float y = zenithXy.y * perezFunction(cy, safeCosTheta, gamma, cosGamma) /
            perezFunction(cy, 1.0, thetaSun, cosThetaSun);
  return max(xyYToLinearRgb(x, y, Y), vec3(0.0)) * twilight;
}

#endif
