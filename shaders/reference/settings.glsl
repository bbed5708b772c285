// The reference path tracer's settings block (shared/reference_io.h) and the arrays it points
// to, as buffer_reference views. The entry point loads the block once into `settings`, and its
// light tables into `lightTables` (lighting/light_tables.glsl).
#ifndef BOUNCE_REFERENCE_SETTINGS_GLSL
#define BOUNCE_REFERENCE_SETTINGS_GLSL
#include "shared/reference_io.h"

layout(buffer_reference, scalar, buffer_reference_align = 8) readonly buffer ReferenceSettingsBlock {
  ReferenceSettings v;
};
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer AccumulationArray {
  vec4 v[];
};
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer CounterArray {
  uint v[];
};

ReferenceSettings settings;

#endif
