// exposure-debug: the frame's luminance histogram as an image (shared/auto_exposure_io.h):
// one bar per bin (two pixels wide, height relative to the fullest bin), bright where the bin's
// pixels are metered (between the percentiles), dim where they are left out; a red line at the
// target luminance and a green one at the adapted luminance the exposure maps to the key.
#version 460
#include "passes/auto_exposure.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(push_constant, scalar) uniform Push { ExposureDebugConstants pc; };

layout(set = 1, binding = EXPOSURE_DEBUG_BINDING_VIEW, rgba16f) uniform writeonly image2D view;

const float PIXELS_PER_BIN = float(EXPOSURE_VIEW_WIDTH) / float(EXPOSURE_HISTOGRAM_BINS);

// Horizontal position of a log2 luminance, in pixels.
float columnOf(float log2Luminance) {
  return (log2Luminance - float(EXPOSURE_HISTOGRAM_MIN_LOG2)) * float(EXPOSURE_BINS_PER_STOP) *
         PIXELS_PER_BIN;
}

bool onLine(float x, float log2Luminance) { return abs(x + 0.5 - columnOf(log2Luminance)) < 1.0; }

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(pixel), uvec2(EXPOSURE_VIEW_WIDTH, EXPOSURE_VIEW_HEIGHT)))) return;
  ExposureStateRef state = ExposureStateRef(pc.state);
  uint bin = uint(float(pixel.x) / PIXELS_PER_BIN);
  uint fullest = 1u;
  uint below = 0u;  // counted pixels in darker bins
  for (uint b = 0u; b < EXPOSURE_HISTOGRAM_BINS; ++b) {
    fullest = max(fullest, state.v.bins[b]);
    if (b < bin) below += state.v.bins[b];
  }
  float total = float(state.v.countedPixels);
  uint count = state.v.bins[bin];
  bool metered = float(below + count) > pc.lowPercentile * total &&
                 float(below) < pc.highPercentile * total;
  float barTop = float(EXPOSURE_VIEW_HEIGHT) * (1.0 - float(count) / float(fullest));
  vec3 colour = float(pixel.y) + 0.5 >= barTop ? vec3(metered ? 0.8 : 0.15) : vec3(0.0);
  if (onLine(float(pixel.x), state.v.targetLog2Luminance)) colour = vec3(1.0, 0.0, 0.0);
  if (onLine(float(pixel.x), state.v.adaptedLog2Luminance)) colour = vec3(0.0, 1.0, 0.0);
  imageStore(view, pixel, vec4(colour, 1.0));
}
