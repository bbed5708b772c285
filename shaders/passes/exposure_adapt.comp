// exposure-adapt: meters this frame's histogram and moves the exposure towards it.
//
// Metering as histogram-based engines do it (e.g. Unreal's "Auto Exposure Histogram"): the
// darkest `lowPercentile` and the brightest pixels above `highPercentile` of the counted pixels
// are left out, and the mean log2 luminance of those between is the scene's level; it is clamped
// to [minLog2Luminance, maxLog2Luminance] and mapped to the key (middle grey, exposure =
// key / 2^level), with the compensation in stops on top.
//
// Adaptation is exponential in log2 luminance, as the eye's (and engines') is: each frame the
// adapted level covers 1 - exp(-dt / tau) of its distance to the target, with a shorter tau when
// the scene got brighter than when it got darker. It never overshoots; a snap (first frame, a
// reset) takes the target directly. One group: a thread per bin copies the histogram into the
// state and clears it for the next frame; the first thread meters (128 bins, serially).
#version 460
#include "passes/auto_exposure.glsl"

layout(local_size_x = EXPOSURE_HISTOGRAM_BINS) in;
layout(push_constant, scalar) uniform Push { ExposureAdaptConstants pc; };

shared uint counts[EXPOSURE_HISTOGRAM_BINS];

// The mean log2 luminance of the pixels between the two percentiles; each bin counts with the
// part of its pixels that falls inside the window, at its centre.
float meteredLog2Luminance(float total) {
  if (total == 0.0) return float(EXPOSURE_HISTOGRAM_MIN_LOG2);  // nothing lit: as dark as it gets
  float low = pc.lowPercentile * total, high = pc.highPercentile * total;
  float below = 0.0, weight = 0.0, weightedBin = 0.0;
  for (uint b = 0u; b < EXPOSURE_HISTOGRAM_BINS; ++b) {
    float count = float(counts[b]);
    float inside = max(0.0, min(below + count, high) - max(below, low));
    weight += inside;
    weightedBin += inside * float(b);
    below += count;
  }
  return exposureBinCentreLog2(weightedBin / weight);
}

float adaptedLog2Luminance(float target, float previous) {
  if (pc.snap != 0u || isnan(previous) || isinf(previous)) return target;
  float tau = target > previous ? pc.brighteningSeconds : pc.darkeningSeconds;
  float step = tau > 0.0 ? 1.0 - exp(-max(pc.deltaSeconds, 0.0) / tau) : 1.0;
  return mix(previous, target, step);
}

void main() {
  uint b = gl_LocalInvocationIndex;
  ExposureHistogramRef histogram = ExposureHistogramRef(pc.histogram);
  ExposureStateRef current = ExposureStateRef(pc.current);
  uint count = histogram.bins[b];
  counts[b] = count;
  current.v.bins[b] = count;
  histogram.bins[b] = 0u;  // ready for the next frame's exposure-histogram
  barrier();
  if (b != 0u) return;

  uint total = 0u;
  for (uint i = 0u; i < EXPOSURE_HISTOGRAM_BINS; ++i) total += counts[i];
  float metered = meteredLog2Luminance(float(total));
  float target = clamp(metered, pc.minLog2Luminance, pc.maxLog2Luminance);
  ExposureStateRef previous = ExposureStateRef(pc.previous);
  float adapted = adaptedLog2Luminance(target, previous.v.adaptedLog2Luminance);
  current.v.exposure = exp2(pc.log2Key - adapted + pc.compensationStops);
  current.v.adaptedLog2Luminance = adapted;
  current.v.targetLog2Luminance = target;
  current.v.meteredLog2Luminance = metered;
  current.v.countedPixels = total;
  current.v.framesSinceSnap = pc.snap != 0u ? 0u : previous.v.framesSinceSnap + 1u;
}
