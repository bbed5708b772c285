// The primary-visibility debug views (pass "primary-view"): primary rays cast through the BVH
// and shaded with one surface attribute, so a person can check that a scene loaded right.
#ifndef BOUNCE_SHARED_PRIMARY_VIEW_IO_H
#define BOUNCE_SHARED_PRIMARY_VIEW_IO_H
#include "shared/camera.h"

BOUNCE_BEGIN_SHARED

BOUNCE_CONST uint PRIMARY_VIEW_ALBEDO = 0u;    // base colour x texture (linear)
BOUNCE_CONST uint PRIMARY_VIEW_NORMAL = 1u;    // world shading normal, n * 0.5 + 0.5
BOUNCE_CONST uint PRIMARY_VIEW_DEPTH = 2u;     // view depth, near bright, far dark
BOUNCE_CONST uint PRIMARY_VIEW_INSTANCE = 3u;  // a colour per instance id
BOUNCE_CONST uint PRIMARY_VIEW_GEOMETRY = 4u;  // a colour per geometry id

struct PrimaryViewConstants {
  GpuCamera camera;
  DeviceAddress outputImage;  // vec4[width * height], linear RGB (black where rays miss), alpha 1
  uvec2 resolution;
  uint view;
  uint alphaTest;
};
BOUNCE_CHECK_SIZE(PrimaryViewConstants, 88);

BOUNCE_CONST uint PRIMARY_VIEW_GROUP_SIZE = 8u;

BOUNCE_END_SHARED
#endif
