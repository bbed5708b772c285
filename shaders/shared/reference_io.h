// The reference path tracer (pass "reference-path-trace", shaders/reference/path_trace.comp;
// src/reference/path_tracer.h): the settings block, with the light tables it samples for
// next-event estimation (shared/lighting_io.h), and the push constants of one batch of samples.
#ifndef BOUNCE_SHARED_REFERENCE_IO_H
#define BOUNCE_SHARED_REFERENCE_IO_H
#include "shared/camera.h"
#include "shared/lighting_io.h"

BOUNCE_BEGIN_SHARED

BOUNCE_CONST uint REFERENCE_FLAG_LAMBERT = 1u;  // every material pure Lambert (--lambert)
// Camera rays through pixel centres only (--pixel-centre): no anti-aliasing, like a real-time
// frame's single sample per pixel, so that the two can be compared pixel for pixel.
BOUNCE_CONST uint REFERENCE_FLAG_PIXEL_CENTRE = 2u;

BOUNCE_CONST uint REFERENCE_SKY_CONSTANT = 0u;
BOUNCE_CONST uint REFERENCE_SKY_DAYLIGHT = 1u;  // Preetham et al. 1999, shaders/common/sky.glsl

// Everything a batch needs besides the scene (set 0), in one buffer because lavapipe offers
// only 128 bytes of push constants.
struct ReferenceSettings {
  GpuCamera camera;
  DeviceAddress accumulation;  // vec4[width * height]: running sums of samples (rgb, 0)
  DeviceAddress counters;      // uint[REFERENCE_COUNTER_COUNT]
  LightTables lights;          // every light of the scene, the sun included
  uvec2 resolution;
  uint maxBounces;  // scattering events per path; 1 = direct lighting only
  uint seed;
  uint flags;
  vec3 skyRadiance;  // constant sky
  uint skyModel;
  vec3 skyTowardSun;  // daylight sky: unit direction to the sun
  float skyTurbidity;
  float skyScale;  // daylight sky: radiance per kcd/m^2 of the model's luminance
};
BOUNCE_CHECK_SIZE(ReferenceSettings, 192);

BOUNCE_CONST uint REFERENCE_COUNTER_NON_FINITE = 0u;  // samples dropped for being NaN or infinite
BOUNCE_CONST uint REFERENCE_COUNTER_COUNT = 4u;

// Push constants of one dispatch: every pixel adds samples firstSample .. firstSample +
// sampleCount - 1 to its running sum, one at a time in that order, so the sum does not depend
// on how samples are split into batches.
struct ReferenceConstants {
  DeviceAddress settings;  // ReferenceSettings
  uint firstSample;
  uint sampleCount;
};
BOUNCE_CHECK_SIZE(ReferenceConstants, 16);

BOUNCE_CONST uint REFERENCE_GROUP_SIZE = 8u;

BOUNCE_END_SHARED
#endif
