// The small value types of the public API. Conventions as in glTF: +Y up, metres, right-handed;
// colours are linear RGB.
#pragma once
#include "bounce/config.h"

namespace bounce::api {

struct Vec3 {
  float x = 0.0f;
  float y = 0.0f;
  float z = 0.0f;
};

// A 4x4 matrix in column-major order, as glTF and GLSL store it: m[column * 4 + row], the
// translation in m[12], m[13], m[14]. Default: the identity.
struct Mat4 {
  float m[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};

  static Mat4 translation(Vec3 t) {
    Mat4 r;
    r.m[12] = t.x;
    r.m[13] = t.y;
    r.m[14] = t.z;
    return r;
  }
};

}  // namespace bounce::api
