// The light tables (shared/lighting_io.h) as buffer_reference views, and `lightTables`, the
// LightTables block that lights.glsl samples. The entry point loads it once: the reference
// tracer from its settings, the real-time passes from the address src/lighting/gpu_light_tables.h
// gives them.
#ifndef BOUNCE_LIGHTING_LIGHT_TABLES_GLSL
#define BOUNCE_LIGHTING_LIGHT_TABLES_GLSL
#include "shared/lighting_io.h"

layout(buffer_reference, scalar, buffer_reference_align = 8) readonly buffer LightTablesBlock {
  LightTables v;
};
// Emissive triangles and punctual lights as 16-byte quarters: every table starts on 16 bytes
// (src/lighting/gpu_light_tables.cpp, kAlignment) and both structs are whole quarters, so a
// light is fetched with 128-bit loads (the scalar layout's 4-byte alignment gets 32-bit ones:
// docs/ray-tracing.md, "128-bit loads").
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer LightQuadArray {
  vec4 v[];
};
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer LightAliasArray {
  GpuLightAlias v[];
};
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer DistantLightArray {
  GpuDistantLight v[];
};
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer FloatArray {
  float v[];
};

LightTables lightTables;

GpuEmissiveTriangle loadEmissiveTriangle(uint index) {
  LightQuadArray quads = LightQuadArray(lightTables.emissiveTriangles);
  vec4 q0 = quads.v[4u * index];
  vec4 q1 = quads.v[4u * index + 1u];
  vec4 q2 = quads.v[4u * index + 2u];
  vec4 q3 = quads.v[4u * index + 3u];
  return GpuEmissiveTriangle(q0.xyz, floatBitsToUint(q0.w), q1.xyz, floatBitsToUint(q1.w), q2.xyz,
                             q2.w, q3.xyz, floatBitsToUint(q3.w));
}

GpuPunctualLight loadPunctualLight(uint index) {
  LightQuadArray quads = LightQuadArray(lightTables.punctualLights);
  vec4 q0 = quads.v[3u * index];
  vec4 q1 = quads.v[3u * index + 1u];
  vec4 q2 = quads.v[3u * index + 2u];
  return GpuPunctualLight(q0.xyz, floatBitsToUint(q0.w), q1.xyz, q1.w, q2.xyz, q2.w);
}

#endif
