// Automatic exposure (src/passes/auto_exposure.h, docs/frame.md#automatic-exposure): a histogram
// of the HDR image's log2 luminance (`exposure-histogram`), metered and adapted over frames
// (`exposure-adapt`) into an ExposureState that `tonemap` reads; `exposure-debug` draws it.
//
// Buffers (frame graph, reached by buffer device address):
//   exposure.histogram  uint[EXPOSURE_HISTOGRAM_BINS]  pixels per bin, accumulated by
//                       exposure-histogram; zero between frames (exposure-adapt clears it after
//                       reading, so no clear pass is needed)
//   exposure.state      ExposureState (history: `previous` is last frame's)
// Images:
//   exposure            RGBA16F, EXPOSURE_VIEW_WIDTH x EXPOSURE_VIEW_HEIGHT: the histogram as
//                       bars (the metering window bright), the target (red) and adapted (green)
//                       luminance as vertical lines
#ifndef BOUNCE_SHARED_AUTO_EXPOSURE_IO_H
#define BOUNCE_SHARED_AUTO_EXPOSURE_IO_H
#include "shared/compat.h"

BOUNCE_BEGIN_SHARED

// The histogram's bins are quarter stops of Rec. 709 luminance Y (in the composite's radiance
// units) from 2^-16 to 2^16: bin b holds floor(4 log2 Y) = 4 * EXPOSURE_HISTOGRAM_MIN_LOG2 + b.
// fp16 (the composite's format) tops out at 65504 < 2^16, so no finite pixel lies above; pixels
// below 2^-16 (but above 0) count in bin 0. A quarter stop quantises each pixel's log luminance
// by at most 1/8 stop, which averaging over the metering window shrinks further.
BOUNCE_CONST uint EXPOSURE_HISTOGRAM_BINS = 128u;
BOUNCE_CONST uint EXPOSURE_BINS_PER_STOP = 4u;
BOUNCE_CONST int EXPOSURE_HISTOGRAM_MIN_LOG2 = -16;
// Bins are found by comparing the mantissa of Y (frexp: Y = m 2^e, m in [0.5, 1)) with these
// quarter-stop boundaries 2^(-3/4), 2^(-1/2), 2^(-1/4), not by a log2 whose rounding varies
// between devices: a pixel scaled by a power of two moves by exactly 4 bins per stop on every
// device, and the CPU can compute the same bins exactly.
BOUNCE_CONST float EXPOSURE_MANTISSA_QUARTER_1 = 0.594603558f;  // 2^(-3/4)
BOUNCE_CONST float EXPOSURE_MANTISSA_QUARTER_2 = 0.707106781f;  // 2^(-1/2)
BOUNCE_CONST float EXPOSURE_MANTISSA_QUARTER_3 = 0.840896415f;  // 2^(-1/4)

// Rec. 709 / sRGB luminance weights (ITU-R BT.709-6, item 3.2) of linear RGB.
BOUNCE_CONST float EXPOSURE_LUMINANCE_R = 0.2126f;
BOUNCE_CONST float EXPOSURE_LUMINANCE_G = 0.7152f;
BOUNCE_CONST float EXPOSURE_LUMINANCE_B = 0.0722f;

// exposure-histogram: one thread per pixel in groups of GROUP_SIZE^2, each group counting into
// shared memory before adding its non-zero bins to the global histogram.
BOUNCE_CONST uint EXPOSURE_HISTOGRAM_GROUP_SIZE = 16u;

BOUNCE_CONST uint EXPOSURE_VIEW_WIDTH = 256u;  // 2 pixels per bin
BOUNCE_CONST uint EXPOSURE_VIEW_HEIGHT = 64u;

// What exposure-adapt leaves for tonemap (and for tests and the debug view), one per frame.
struct ExposureState {
  float exposure;  // the radiance multiplier tonemap applies: 2^(log2 key - adapted + compensation)
  float adaptedLog2Luminance;  // the scene luminance (log2) the exposure maps to the key now
  float targetLog2Luminance;   // this frame's metered luminance clamped to the settings' range
  float meteredLog2Luminance;  // the metering window's mean log2 luminance (the histogram's
                               // lowest, -16, when no pixel was counted)
  uint countedPixels;          // pixels in the histogram: finite luminance above 0
  uint framesSinceSnap;        // 0: this frame took the metered value directly
  uint pad0;
  uint pad1;
  uint bins[EXPOSURE_HISTOGRAM_BINS];  // this frame's histogram
};
BOUNCE_CHECK_SIZE(ExposureState, 32 + 4 * 128);

struct ExposureHistogramConstants {
  DeviceAddress histogram;  // uint[EXPOSURE_HISTOGRAM_BINS]
};
BOUNCE_CHECK_SIZE(ExposureHistogramConstants, 8);

// exposure-adapt: the settings (AutoExposureSettings) and this frame's time step.
struct ExposureAdaptConstants {
  DeviceAddress histogram;  // uint[EXPOSURE_HISTOGRAM_BINS], read, then cleared
  DeviceAddress previous;   // ExposureState of the last frame
  DeviceAddress current;    // ExposureState written
  float lowPercentile;      // fraction of counted pixels, darkest first, left out of the mean
  float highPercentile;     // fraction below which pixels are metered; those above are left out
  float log2Key;            // log2 of the exposed luminance the metered mean is mapped to
  float compensationStops;  // added to the exposure
  float minLog2Luminance;   // the metered luminance is clamped to [min, max] (log2)
  float maxLog2Luminance;
  float brighteningSeconds;  // time constant when the scene got brighter (exposure falls)
  float darkeningSeconds;    // time constant when the scene got darker (exposure rises)
  float deltaSeconds;        // time since the last frame
  uint snap;                 // 1: take the target directly (first frame, after a reset)
};
BOUNCE_CHECK_SIZE(ExposureAdaptConstants, 64);

struct ExposureDebugConstants {
  DeviceAddress state;  // ExposureState
  float lowPercentile;
  float highPercentile;
};
BOUNCE_CHECK_SIZE(ExposureDebugConstants, 16);

// Set 1 bindings (storage images).
BOUNCE_CONST uint EXPOSURE_HISTOGRAM_BINDING_HDR = 0u;
BOUNCE_CONST uint EXPOSURE_HISTOGRAM_BINDING_COUNT = 1u;
BOUNCE_CONST uint EXPOSURE_ADAPT_BINDING_COUNT = 0u;
BOUNCE_CONST uint EXPOSURE_DEBUG_BINDING_VIEW = 0u;
BOUNCE_CONST uint EXPOSURE_DEBUG_BINDING_COUNT = 1u;

BOUNCE_END_SHARED
#endif
