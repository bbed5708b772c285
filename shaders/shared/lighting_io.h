// The scene's lights as next-event estimation samples them, shared by the reference path
// tracer and the real-time frame: built on the CPU (src/lighting/light_table.h), uploaded
// behind one LightTables block (src/lighting/gpu_light_tables.h for the real-time frame,
// ReferenceSettings::lights for the reference) and sampled by shaders/lighting/lights.glsl.
//
// Lights come in two groups:
//   - distant lights (the sun and KHR directional lights): few, sampled at every vertex;
//   - local lights (emissive triangles and KHR point/spot lights): one is picked per vertex,
//     with probability proportional to its power, from Walker's alias table (Walker 1977;
//     construction after Vose 1991), so a vertex costs one shadow ray however many there are.
// Entry i of the alias table is emissive triangle i when i < emissiveTriangleCount, else
// punctual light i - emissiveTriangleCount.
#ifndef BOUNCE_SHARED_LIGHTING_IO_H
#define BOUNCE_SHARED_LIGHTING_IO_H
#include "shared/compat.h"

BOUNCE_BEGIN_SHARED

// One emissive triangle in world space. frontNormal is the unit normal of the side that emits
// (glTF front face; instances that mirror are accounted for), so the triangle emits towards a
// point x when dot(frontNormal, x - p0) > 0. geometry (global) and primitive locate the
// triangle's vertices for the emissive texture; a point p0 + b1 edge1 + b2 edge2 has the
// barycentric weights (b1, b2) of v1 and v2 as the tracer reports them. meanEmission is its
// material's mean emitted radiance (emissive factor x the mean of its emissive texture, what
// selection weighs it by) as RGB9E5 (shared exponent, decodeRgb9e5 in lighting/lights.glsl): a
// light's cheap estimate for target functions that must not fetch its texture (ReSTIR DI).
struct GpuEmissiveTriangle {
  vec3 p0;
  uint geometry;
  vec3 edge1;
  uint primitive;
  vec3 edge2;
  float area;
  vec3 frontNormal;
  uint meanEmission;
};
BOUNCE_CHECK_SIZE(GpuEmissiveTriangle, 64);

BOUNCE_CONST uint PUNCTUAL_LIGHT_POINT = 0u;
BOUNCE_CONST uint PUNCTUAL_LIGHT_SPOT = 1u;

// A KHR_lights_punctual point or spot light. intensity is the radiant intensity in W/sr
// (candela read as W/sr, colour multiplied in). A spot's angular attenuation is the glTF
// smooth falloff: a = clamp(dot(spotDirection, lightToPoint) * angleScale + angleOffset, 0, 1)^2.
struct GpuPunctualLight {
  vec3 position;
  uint type;
  vec3 spotDirection;  // unit, the direction the spot shines
  float angleScale;
  vec3 intensity;
  float angleOffset;
};
BOUNCE_CHECK_SIZE(GpuPunctualLight, 48);

// One entry of the alias table over local lights: entry i is kept when the second uniform
// number is below `threshold`, else `alias` is taken; pmf is the final probability of
// choosing light i (its power over the total).
struct GpuLightAlias {
  float pmf;
  float threshold;
  uint alias;
  uint pad0;
};
BOUNCE_CHECK_SIZE(GpuLightAlias, 16);

// A light at infinity seen within a cone of half-angle acos(cosHalfAngle) around towardLight
// (cosHalfAngle = 1: a delta direction). irradiance is what a surface facing it receives;
// sampling the cone uniformly, a sample's contribution is f cos(theta) * coneWeight where
// coneWeight = irradiance for a delta light and irradiance * 2 / (1 + cosHalfAngle) for a cone
// (the radiance E / (pi sin^2) times the cone's solid angle, see src/lighting/light_table.cpp).
struct GpuDistantLight {
  vec3 towardLight;
  float cosHalfAngle;
  vec3 coneWeight;
  float pad0;
};
BOUNCE_CHECK_SIZE(GpuDistantLight, 32);

BOUNCE_CONST uint MAX_DISTANT_LIGHTS = 16u;

// The light tables' addresses and sizes, the block the light sampling shaders load.
struct LightTables {
  DeviceAddress emissiveTriangles;  // GpuEmissiveTriangle[emissiveTriangleCount]
  DeviceAddress punctualLights;     // GpuPunctualLight[]
  DeviceAddress lightAlias;         // GpuLightAlias[localLightCount]
  DeviceAddress distantLights;      // GpuDistantLight[distantLightCount]
  // float[materialCount]: for an emissive material, pi * luminance(mean emission) / total local
  // light power, which is the area density with which next-event estimation picks a point on
  // any one of its triangles (the triangle's pmf / its area). 0 for materials not in the table.
  DeviceAddress materialLightAreaPdf;
  uint emissiveTriangleCount;
  uint localLightCount;  // emissive triangles + punctual lights
  uint distantLightCount;
  uint pad0;  // the size a multiple of 8 in both C++ and GLSL scalar layout
};
BOUNCE_CHECK_SIZE(LightTables, 56);

BOUNCE_END_SHARED
#endif
