// The reference path tracer (pass "reference-path-trace", shaders/reference/path_trace.comp;
// src/reference/path_tracer.h): the settings block, the light tables it samples for next-event
// estimation, and the push constants of one batch of samples.
//
// Lights come in two groups:
//   - distant lights (the sun and KHR directional lights): few, sampled at every vertex;
//   - local lights (emissive triangles and KHR point/spot lights): one is picked per vertex,
//     with probability proportional to its power, from Walker's alias table (Walker 1977;
//     construction after Vose 1991), so a vertex costs one shadow ray however many there are.
// Entry i of the alias table is emissive triangle i when i < emissiveTriangleCount, else
// punctual light i - emissiveTriangleCount.
#ifndef BOUNCE_SHARED_REFERENCE_IO_H
#define BOUNCE_SHARED_REFERENCE_IO_H
#include "shared/camera.h"

BOUNCE_BEGIN_SHARED

// One emissive triangle in world space. frontNormal is the unit normal of the side that emits
// (glTF front face; instances that mirror are accounted for), so the triangle emits towards a
// point x when dot(frontNormal, x - p0) > 0. geometry (global) and primitive locate the
// triangle's vertices for the emissive texture; a point p0 + b1 edge1 + b2 edge2 has the
// barycentric weights (b1, b2) of v1 and v2 as the tracer reports them.
struct ReferenceEmissiveTriangle {
  vec3 p0;
  uint geometry;
  vec3 edge1;
  uint primitive;
  vec3 edge2;
  float area;
  vec3 frontNormal;
  float pad0;
};
BOUNCE_CHECK_SIZE(ReferenceEmissiveTriangle, 64);

BOUNCE_CONST uint REFERENCE_LIGHT_POINT = 0u;
BOUNCE_CONST uint REFERENCE_LIGHT_SPOT = 1u;

// A KHR_lights_punctual point or spot light. intensity is the radiant intensity in W/sr
// (candela read as W/sr, colour multiplied in). A spot's angular attenuation is the glTF
// smooth falloff: a = clamp(dot(spotDirection, lightToPoint) * angleScale + angleOffset, 0, 1)^2.
struct ReferencePunctualLight {
  vec3 position;
  uint type;
  vec3 spotDirection;  // unit, the direction the spot shines
  float angleScale;
  vec3 intensity;
  float angleOffset;
};
BOUNCE_CHECK_SIZE(ReferencePunctualLight, 48);

// One entry of the alias table over local lights: entry i is kept when the second uniform
// number is below `threshold`, else `alias` is taken; pmf is the final probability of
// choosing light i (its power over the total).
struct ReferenceLightAlias {
  float pmf;
  float threshold;
  uint alias;
  uint pad0;
};
BOUNCE_CHECK_SIZE(ReferenceLightAlias, 16);

// A light at infinity seen within a cone of half-angle acos(cosHalfAngle) around towardLight
// (cosHalfAngle = 1: a delta direction). irradiance is what a surface facing it receives;
// sampling the cone uniformly, a sample's contribution is f cos(theta) * coneWeight where
// coneWeight = irradiance for a delta light and irradiance * 2 / (1 + cosHalfAngle) for a cone
// (the radiance E / (pi sin^2) times the cone's solid angle, see light_table.cpp).
struct ReferenceDistantLight {
  vec3 towardLight;
  float cosHalfAngle;
  vec3 coneWeight;
  float pad0;
};
BOUNCE_CHECK_SIZE(ReferenceDistantLight, 32);

BOUNCE_CONST uint REFERENCE_MAX_DISTANT_LIGHTS = 16u;

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
  DeviceAddress accumulation;       // vec4[width * height]: running sums of samples (rgb, 0)
  DeviceAddress counters;           // uint[REFERENCE_COUNTER_COUNT]
  DeviceAddress emissiveTriangles;  // ReferenceEmissiveTriangle[emissiveTriangleCount]
  DeviceAddress punctualLights;     // ReferencePunctualLight[]
  DeviceAddress lightAlias;         // ReferenceLightAlias[localLightCount]
  DeviceAddress distantLights;      // ReferenceDistantLight[distantLightCount]
  // float[materialCount]: for an emissive material, pi * luminance(mean emission) / total local
  // light power, which is the area density with which next-event estimation picks a point on
  // any one of its triangles (the triangle's pmf / its area). 0 for materials not in the table.
  DeviceAddress materialLightAreaPdf;
  uvec2 resolution;
  uint maxBounces;  // scattering events per path; 1 = direct lighting only
  uint seed;
  uint flags;
  uint emissiveTriangleCount;
  uint localLightCount;  // emissive triangles + punctual lights
  uint distantLightCount;
  vec3 skyRadiance;  // constant sky
  uint skyModel;
  vec3 skyTowardSun;  // daylight sky: unit direction to the sun
  float skyTurbidity;
  float skyScale;  // daylight sky: radiance per kcd/m^2 of the model's luminance
  uint pad0;
  uint pad1;
  uint pad2;
};
BOUNCE_CHECK_SIZE(ReferenceSettings, 200);

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
