// Temporal anti-aliasing (`taa`, src/passes/taa.h, docs/frame.md#temporal-anti-aliasing): the
// frame's primary visibility is jittered by a sub-pixel offset (FrameConstants::jitter, a Halton
// (2, 3) sequence), and `taa` blends each frame's composite into a history reprojected with
// gbuffer.velocity and clipped to the current neighbourhood.
//
// Images:
//   taa.color  RGBA16F (history)  anti-aliased radiance (rgb, W/(m^2 sr), like composite.hdr)
//                                 and the frames it averages (a, capped); what tonemap reads
#ifndef BOUNCE_SHARED_TAA_IO_H
#define BOUNCE_SHARED_TAA_IO_H
#include "shared/compat.h"

BOUNCE_BEGIN_SHARED

// Push constants of `taa`.
struct TaaConstants {
  DeviceAddress frame;          // FrameConstants
  DeviceAddress exposureState;  // ExposureState of automatic exposure; 0: FrameConstants::exposure
  float blend;                  // weight of the current frame once the history is long
  float clipSigma;              // half-width of the clip box in standard deviations
  uint historyValid;            // 0 in the first frame and after a reset
  uint pad0;
};
BOUNCE_CHECK_SIZE(TaaConstants, 32);

BOUNCE_CONST uint TAA_BINDING_HDR = 0u;       // composite.hdr
BOUNCE_CONST uint TAA_BINDING_VELOCITY = 1u;  // gbuffer.velocity
BOUNCE_CONST uint TAA_BINDING_DEPTH = 2u;     // gbuffer.depth
BOUNCE_CONST uint TAA_BINDING_PREVIOUS = 3u;  // taa.color, last frame's
BOUNCE_CONST uint TAA_BINDING_CURRENT = 4u;   // taa.color
BOUNCE_CONST uint TAA_BINDING_COUNT = 5u;

BOUNCE_END_SHARED
#endif
