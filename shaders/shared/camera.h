// A pinhole camera as the shaders see it: primary ray through pixel (x, y) of a W x H image is
//   dir = forward + (2 (x + 0.5) / W - 1) * right - (2 (y + 0.5) / H - 1) * up
// with `right` and `up` pre-scaled by tan(vfov / 2) * aspect and tan(vfov / 2).
#ifndef BOUNCE_SHARED_CAMERA_H
#define BOUNCE_SHARED_CAMERA_H
#include "shared/compat.h"

BOUNCE_BEGIN_SHARED

struct GpuCamera {
  vec3 position;
  float nearDepth;  // for depth visualisation
  vec3 forward;     // unit length
  float farDepth;
  vec3 right;  // scaled, see above
  float pad0;
  vec3 up;  // scaled, see above
  float pad1;
};
BOUNCE_CHECK_SIZE(GpuCamera, 64);

BOUNCE_FN vec3 cameraRayDirection(GpuCamera cam, vec2 pixel, vec2 resolution) {
  vec2 ndc = 2.0f * (pixel / resolution) - vec2(1.0f);
  return normalize(cam.forward + ndc.x * cam.right - ndc.y * cam.up);
}

BOUNCE_END_SHARED
#endif
