// Colour spaces used by the image metrics: linear sRGB (Rec. 709 primaries, D65), CIE XYZ,
// CIELAB and YCxCz (the linearised CIELAB of Edwards et al. that FLIP filters in). White is the
// XYZ of linear RGB (1,1,1), so RGB white maps to L* = 100, a* = b* = 0 exactly.
#pragma once
#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

namespace bounce::color {

// The RGB -> XYZ matrix derived from the sRGB primaries and the D65 white point (xy
// chromaticities of IEC 61966-2-1), rather than a rounded table, so that RGB and XYZ round-trip.
const glm::mat3& linearRgbToXyzMatrix();
const glm::mat3& xyzToLinearRgbMatrix();
// XYZ of linear RGB (1,1,1); Y = 1.
const glm::vec3& referenceWhite();

inline glm::vec3 linearRgbToXyz(const glm::vec3& rgb) {
  return linearRgbToXyzMatrix() * rgb;
}
inline glm::vec3 xyzToLinearRgb(const glm::vec3& xyz) {
  return xyzToLinearRgbMatrix() * xyz;
}

// CIELAB (CIE 15): L* in [0,100] for XYZ within the white.
glm::vec3 xyzToCielab(const glm::vec3& xyz);

// YCxCz: CIELAB with the cube root left out, so linear in XYZ and safe to filter.
glm::vec3 xyzToYCxCz(const glm::vec3& xyz);
glm::vec3 yCxCzToXyz(const glm::vec3& yCxCz);

}  // namespace bounce::color
