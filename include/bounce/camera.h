// A pinhole camera: where it is, the point it looks at, and its vertical field of view.
#pragma once
#include "bounce/config.h"
#include "bounce/math.h"

namespace bounce::api {

struct Camera {
  Vec3 position{0.0f, 0.0f, 5.0f};   // metres
  Vec3 target{0.0f, 0.0f, 0.0f};     // a point the camera looks at; differs from position
  float verticalFovDegrees = 45.0f;  // (0, 180)
  Vec3 up{0.0f, 1.0f, 0.0f};         // the image's up direction, roughly
};

}  // namespace bounce::api
