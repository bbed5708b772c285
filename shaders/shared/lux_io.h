// Lux's ReSTIR indirect (`--gi lux`, seed 002; src/gi/lux/lux_gi.h): the push constants and the
// bindings of its own passes. Its reservoirs, the 2nd-vertex trace and the temporal, spatial and
// resolve stages are ReSTIR GI's (shared/restir_gi_io.h).
#ifndef BOUNCE_SHARED_LUX_IO_H
#define BOUNCE_SHARED_LUX_IO_H
#include "shared/compat.h"

BOUNCE_BEGIN_SHARED

// Push constants of every lux-* pass.
struct LuxPassConstants {
  DeviceAddress frame;   // FrameConstants (shared/hybrid_frame_io.h)
  DeviceAddress gi;      // RestirGiConstants (its cache address is the probe field)
  uint candidates;       // lux-candidates: cosine candidates per GI pixel (M)
  float targetFloor;     // lux-candidates: p_hat's floor, a fraction of the probe's mean radiance
  uint integralSamples;  // lux-probe-integral: directions per GI pixel
  uint integralUniform;  // lux-probe-integral: 1 uniform hemisphere, 0 cosine-distributed
};
BOUNCE_CHECK_SIZE(LuxPassConstants, 32);

// Set 1 bindings per pass.
// lux-candidates
BOUNCE_CONST uint LUX_CANDIDATES_BINDING_NORMALS = 0u;
BOUNCE_CONST uint LUX_CANDIDATES_BINDING_DEPTH = 1u;
BOUNCE_CONST uint LUX_CANDIDATES_BINDING_FLAGS = 2u;
// RGBA16F: the probe field's irradiance / pi at x1 (rgb), W of the chosen candidate (a)
BOUNCE_CONST uint LUX_CANDIDATES_BINDING_TARGET = 3u;
BOUNCE_CONST uint LUX_CANDIDATES_BINDING_RAYS = 4u;    // RGBA32F gi.rays (GI_RAY_FRESH in w)
BOUNCE_CONST uint LUX_CANDIDATES_BINDING_WEIGHT = 5u;  // R32F W of the ray's direction, 1/sr
BOUNCE_CONST uint LUX_CANDIDATES_BINDING_COUNT = 6u;

// lux-resolve-candidates
BOUNCE_CONST uint LUX_RESOLVE_BINDING_NORMALS = 0u;
BOUNCE_CONST uint LUX_RESOLVE_BINDING_DEPTH = 1u;
BOUNCE_CONST uint LUX_RESOLVE_BINDING_RAYS = 2u;
BOUNCE_CONST uint LUX_RESOLVE_BINDING_WEIGHT = 3u;
BOUNCE_CONST uint LUX_RESOLVE_BINDING_HIT = 4u;
BOUNCE_CONST uint LUX_RESOLVE_BINDING_HIT_NORMAL = 5u;
BOUNCE_CONST uint LUX_RESOLVE_BINDING_HIT_RADIANCE = 6u;
BOUNCE_CONST uint LUX_RESOLVE_BINDING_NEE_RADIANCE = 7u;
BOUNCE_CONST uint LUX_RESOLVE_BINDING_VISIBILITY = 8u;
BOUNCE_CONST uint LUX_RESOLVE_BINDING_ESTIMATE = 9u;  // RGBA16F the candidate's estimate
BOUNCE_CONST uint LUX_RESOLVE_BINDING_SAMPLE = 10u;   // 10-13 the candidate reservoir
BOUNCE_CONST uint LUX_RESOLVE_BINDING_VALIDITY = 14u;
BOUNCE_CONST uint LUX_RESOLVE_BINDING_COUNT = 15u;

// lux-probe-integral (test support and a debug view)
BOUNCE_CONST uint LUX_INTEGRAL_BINDING_NORMALS = 0u;
BOUNCE_CONST uint LUX_INTEGRAL_BINDING_DEPTH = 1u;
BOUNCE_CONST uint LUX_INTEGRAL_BINDING_FLAGS = 2u;
BOUNCE_CONST uint LUX_INTEGRAL_BINDING_OUTPUT = 3u;  // RGBA32F the mean estimate of gi.diffuse
BOUNCE_CONST uint LUX_INTEGRAL_BINDING_COUNT = 4u;

BOUNCE_END_SHARED

#endif
