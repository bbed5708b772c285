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
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer EmissiveTriangleArray {
  GpuEmissiveTriangle v[];
};
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer PunctualLightArray {
  GpuPunctualLight v[];
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

#endif
