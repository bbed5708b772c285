// What the automatic-exposure passes and tonemap share (shared/auto_exposure_io.h): the
// luminance a pixel is metered by, its histogram bin, and the buffers by reference.
#ifndef BOUNCE_PASSES_AUTO_EXPOSURE_GLSL
#define BOUNCE_PASSES_AUTO_EXPOSURE_GLSL
#include "shared/auto_exposure_io.h"

layout(buffer_reference, scalar, buffer_reference_align = 4) buffer ExposureStateRef {
  ExposureState v;
};
layout(buffer_reference, scalar, buffer_reference_align = 4) coherent buffer ExposureHistogramRef {
  uint bins[EXPOSURE_HISTOGRAM_BINS];
};

const uint EXPOSURE_NOT_COUNTED = 0xFFFFFFFFu;

float exposureLuminance(vec3 rgb) {
  return dot(rgb, vec3(EXPOSURE_LUMINANCE_R, EXPOSURE_LUMINANCE_G, EXPOSURE_LUMINANCE_B));
}

// The bin of luminance y: floor(4 log2 y) - 4 EXPOSURE_HISTOGRAM_MIN_LOG2, clamped to the
// histogram; EXPOSURE_NOT_COUNTED for y <= 0, NaN or infinite (black pixels say nothing about
// the light level, and a NaN or Inf must not decide the exposure of every other pixel).
uint exposureBin(float y) {
  if (!(y > 0.0) || isinf(y)) return EXPOSURE_NOT_COUNTED;
  int e;
  float m = frexp(y, e);  // y = m 2^e, m in [0.5, 1): floor(4 log2 y) = 4 (e - 1) + quarter
  int quarter = int(m >= EXPOSURE_MANTISSA_QUARTER_1) + int(m >= EXPOSURE_MANTISSA_QUARTER_2) +
                int(m >= EXPOSURE_MANTISSA_QUARTER_3);
  int bin = int(EXPOSURE_BINS_PER_STOP) * (e - 1 - EXPOSURE_HISTOGRAM_MIN_LOG2) + quarter;
  return uint(clamp(bin, 0, int(EXPOSURE_HISTOGRAM_BINS) - 1));
}

// log2 of the luminance at the middle of bin b.
float exposureBinCentreLog2(float bin) {
  return float(EXPOSURE_HISTOGRAM_MIN_LOG2) + (bin + 0.5) / float(EXPOSURE_BINS_PER_STOP);
}

#endif
