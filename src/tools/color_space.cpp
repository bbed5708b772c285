#include "tools/color_space.h"

#include <cmath>

#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

namespace bounce::color {
namespace {

glm::dvec3 xyFromChromaticity(double x, double y) {
  return {x / y, 1.0, (1.0 - x - y) / y};
}

// Standard construction: scale the primaries' XYZ (at Y = 1) so that RGB (1,1,1) is the white.
glm::dmat3 deriveRgbToXyz() {
  const glm::dmat3 primaries(xyFromChromaticity(0.64, 0.33), xyFromChromaticity(0.30, 0.60),
                             xyFromChromaticity(0.15, 0.06));
  const glm::dvec3 white = xyFromChromaticity(0.3127, 0.3290);
  const glm::dvec3 scale = glm::inverse(primaries) * white;
  return glm::dmat3(primaries[0] * scale.x, primaries[1] * scale.y, primaries[2] * scale.z);
}

// CIELAB's companding function f(t), with the linear segment below (6/29)^3.
float labCompand(float t) {
  constexpr float delta = 6.0f / 29.0f;
  if (t > delta * delta * delta) return std::cbrt(t);
  return t / (3.0f * delta * delta) + 4.0f / 29.0f;
}

}  // namespace

const glm::mat3& linearRgbToXyzMatrix() {
  static const glm::mat3 matrix(deriveRgbToXyz());
  return matrix;
}

const glm::mat3& xyzToLinearRgbMatrix() {
  static const glm::mat3 matrix(glm::inverse(deriveRgbToXyz()));
  return matrix;
}

const glm::vec3& referenceWhite() {
  static const glm::vec3 white(deriveRgbToXyz() * glm::dvec3(1.0));
  return white;
}

glm::vec3 xyzToCielab(const glm::vec3& xyz) {
  const glm::vec3 n = xyz / referenceWhite();
  const float fx = labCompand(n.x), fy = labCompand(n.y), fz = labCompand(n.z);
  return {116.0f * fy - 16.0f, 500.0f * (fx - fy), 200.0f * (fy - fz)};
}

glm::vec3 xyzToYCxCz(const glm::vec3& xyz) {
  const glm::vec3 n = xyz / referenceWhite();
  return {116.0f * n.y - 16.0f, 500.0f * (n.x - n.y), 200.0f * (n.y - n.z)};
}

glm::vec3 yCxCzToXyz(const glm::vec3& yCxCz) {
  const float y = (yCxCz.x + 16.0f) / 116.0f;
  const glm::vec3 n(y + yCxCz.y / 500.0f, y, y - yCxCz.z / 200.0f);
  return n * referenceWhite();
}

}  // namespace bounce::color
