#include "api/convert.h"

#include <cmath>

#include "core/error.h"

namespace bounce::api {

namespace {

bool finite(const Vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

bool nonNegative(const Vec3& v) {
  return finite(v) && v.x >= 0.0f && v.y >= 0.0f && v.z >= 0.0f;
}

}  // namespace

glm::mat4 toGlm(const Mat4& m) {
  glm::mat4 r;
  for (int c = 0; c < 4; ++c)
    for (int row = 0; row < 4; ++row) r[c][row] = m.m[c * 4 + row];
  return r;
}

bounce::Camera toInternal(const Camera& camera, const char* where) {
  if (!finite(camera.position) || !finite(camera.target) || !finite(camera.up))
    fail("{}: camera position, target and up must be finite", where);
  if (!(camera.verticalFovDegrees > 0.0f && camera.verticalFovDegrees < 180.0f))
    fail("{}: camera vertical field of view {} degrees: expected (0, 180)", where,
         camera.verticalFovDegrees);
  bounce::Camera c;
  c.position = toGlm(camera.position);
  c.target = toGlm(camera.target);
  c.up = toGlm(camera.up);
  c.verticalFovDegrees = camera.verticalFovDegrees;
  glm::vec3 forward = c.target - c.position;
  if (glm::dot(forward, forward) == 0.0f) fail("{}: camera position and target coincide", where);
  glm::vec3 side = glm::cross(forward, c.up);
  if (glm::dot(side, side) == 0.0f) fail("{}: camera up is parallel to the view direction", where);
  return c;
}

Camera fromInternal(const bounce::Camera& camera) {
  return {.position = fromGlm(camera.position),
          .target = fromGlm(camera.target),
          .verticalFovDegrees = camera.verticalFovDegrees,
          .up = fromGlm(camera.up)};
}

bounce::Sun toInternal(const Sun& sun, const char* where) {
  if (!finite(sun.direction) ||
      (sun.direction.x == 0.0f && sun.direction.y == 0.0f && sun.direction.z == 0.0f))
    fail("{}: sun direction must be finite and not zero", where);
  if (!(std::isfinite(sun.irradiance) && sun.irradiance >= 0.0f))
    fail("{}: sun irradiance {}: expected a finite value >= 0 (W/m^2)", where, sun.irradiance);
  if (!nonNegative(sun.color)) fail("{}: sun colour must be finite and >= 0", where);
  if (!(sun.angularDiameterDegrees >= 0.0f && sun.angularDiameterDegrees < 90.0f))
    fail("{}: sun angular diameter {} degrees: expected [0, 90)", where,
         sun.angularDiameterDegrees);
  bounce::Sun s;
  s.direction = glm::normalize(toGlm(sun.direction));
  s.irradiance = sun.irradiance;
  s.color = toGlm(sun.color);
  s.angularDiameterDegrees = sun.angularDiameterDegrees;
  return s;
}

Sun fromInternal(const bounce::Sun& sun) {
  return {.direction = fromGlm(sun.direction),
          .irradiance = sun.irradiance,
          .color = fromGlm(sun.color),
          .angularDiameterDegrees = sun.angularDiameterDegrees};
}

bounce::Sky toInternal(const Sky& sky, const char* where) {
  if (!nonNegative(sky.radiance)) fail("{}: sky radiance must be finite and >= 0", where);
  if (!(sky.turbidity >= 2.0f && sky.turbidity <= 10.0f))
    fail("{}: sky turbidity {}: expected [2, 10]", where, sky.turbidity);
  bounce::Sky s;
  switch (sky.model) {
    case Sky::Model::Constant:
      s.model = SkyModel::Constant;
      break;
    case Sky::Model::Daylight:
      s.model = SkyModel::Daylight;
      break;
    default:
      fail("{}: unknown sky model {}", where, int(sky.model));
  }
  s.radiance = toGlm(sky.radiance);
  s.turbidity = sky.turbidity;
  return s;
}

Sky fromInternal(const bounce::Sky& sky) {
  return {.model = sky.model == SkyModel::Daylight ? Sky::Model::Daylight : Sky::Model::Constant,
          .radiance = fromGlm(sky.radiance),
          .turbidity = sky.turbidity};
}

bounce::Preset toInternal(Preset preset, const char* where) {
  switch (preset) {
    case Preset::Mobile:
      return bounce::Preset::Mobile;
    case Preset::Desktop:
      return bounce::Preset::Desktop;
  }
  fail("{}: unknown preset {}", where, int(preset));
}

bounce::GiMode toInternal(GiMode gi, const char* where) {
  switch (gi) {
    case GiMode::Evolve:
      return bounce::GiMode::Evolve;
    case GiMode::Cache:
      return bounce::GiMode::Cache;
    case GiMode::None:
      return bounce::GiMode::None;
    case GiMode::Lux:
      return bounce::GiMode::Lux;
    case GiMode::Gi10:
      return bounce::GiMode::Gi10;
  }
  fail("{}: unknown GI mode {}", where, int(gi));
}

HybridSettings toInternal(const RendererSettings& settings, const char* where) {
  constexpr uint32_t kMaxSide = 16384;
  if (settings.width < 1 || settings.width > kMaxSide || settings.height < 1 ||
      settings.height > kMaxSide)
    fail("{}: resolution {}x{}: each side must be 1 .. {}", where, settings.width, settings.height,
         kMaxSide);
  if (!(std::abs(settings.exposureStops) <= 64.0f))
    fail("{}: exposureStops {}: expected -64 to 64", where, settings.exposureStops);
  HybridSettings s = bounce::presetSettings(toInternal(settings.preset, where));
  s.gi = toInternal(settings.gi, where);
  s.width = settings.width;
  s.height = settings.height;
  s.autoExposure = settings.autoExposure;
  s.exposureStops = settings.exposureStops;
  return s;
}

Image fromInternal(const ImageRGBA32F& image) {
  return {.width = uint32_t(image.width), .height = uint32_t(image.height), .rgba = image.pixels};
}

ImageRGBA32F toInternal(const Image& image, const char* where) {
  if (image.width == 0 || image.height == 0 ||
      image.rgba.size() != size_t(image.width) * image.height * 4)
    fail("{}: image of {}x{} pixels has {} floats: expected 4 per pixel", where, image.width,
         image.height, image.rgba.size());
  ImageRGBA32F r;
  r.width = int(image.width);
  r.height = int(image.height);
  r.pixels = image.rgba;
  return r;
}

}  // namespace bounce::api
