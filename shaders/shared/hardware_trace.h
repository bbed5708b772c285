// The hardware tracer's bindings (src/rt/hardware_tracer.h, shaders/rt/hw_trace.glsl): the
// scene's set 0 as every tracer binds it, plus set 1 holding the top-level acceleration
// structure built from the same triangles and instances as the software BVH.
#ifndef BOUNCE_SHARED_HARDWARE_TRACE_H
#define BOUNCE_SHARED_HARDWARE_TRACE_H
#include "shared/compat.h"

BOUNCE_BEGIN_SHARED

BOUNCE_CONST uint HW_TRACE_SET = 1u;
BOUNCE_CONST uint HW_TRACE_BINDING_TLAS = 0u;

BOUNCE_END_SHARED
#endif
