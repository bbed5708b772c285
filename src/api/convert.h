// Conversions between the public types (include/bounce/, named api::X here) and the internal
// ones of the same names (bounce::X), with the checks the public API promises: bad values get a
// bounce::Error naming the function and the field.
#pragma once
#include <bounce/camera.h>
#include <bounce/image.h>
#include <bounce/math.h>
#include <bounce/scene.h>
#include <bounce/settings.h>
#include <glm/glm.hpp>

#include "frame/presets.h"
#include "scene/scene.h"
#include "tools/image_io.h"

namespace bounce::api {

inline glm::vec3 toGlm(const Vec3& v) {
  return {v.x, v.y, v.z};
}
inline Vec3 fromGlm(const glm::vec3& v) {
  return {v.x, v.y, v.z};
}
glm::mat4 toGlm(const Mat4& m);

// `where` names the caller in errors, e.g. "Renderer::render".
bounce::Camera toInternal(const Camera& camera, const char* where);
Camera fromInternal(const bounce::Camera& camera);
bounce::Sun toInternal(const Sun& sun, const char* where);
Sun fromInternal(const bounce::Sun& sun);
bounce::Sky toInternal(const Sky& sky, const char* where);
Sky fromInternal(const bounce::Sky& sky);

bounce::Preset toInternal(Preset preset, const char* where);
bounce::GiMode toInternal(GiMode gi, const char* where);
// The preset's HybridSettings with the public fields applied.
HybridSettings toInternal(const RendererSettings& settings, const char* where);

Image fromInternal(const ImageRGBA32F& image);
ImageRGBA32F toInternal(const Image& image, const char* where);

}  // namespace bounce::api
