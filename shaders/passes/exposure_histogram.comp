// exposure-histogram: counts the HDR image's pixels per quarter stop of luminance
// (auto_exposure.glsl: exposureBin), first in shared memory per group, then into the frame's
// histogram with one global atomic per non-empty bin of the group.
#version 460
#include "passes/auto_exposure.glsl"

layout(local_size_x = EXPOSURE_HISTOGRAM_GROUP_SIZE, local_size_y = EXPOSURE_HISTOGRAM_GROUP_SIZE) in;
layout(push_constant, scalar) uniform Push { ExposureHistogramConstants pc; };

layout(set = 1, binding = EXPOSURE_HISTOGRAM_BINDING_HDR, rgba16f) uniform readonly image2D hdr;

shared uint groupBins[EXPOSURE_HISTOGRAM_BINS];

const uint GROUP_THREADS = EXPOSURE_HISTOGRAM_GROUP_SIZE * EXPOSURE_HISTOGRAM_GROUP_SIZE;

void main() {
  for (uint b = gl_LocalInvocationIndex; b < EXPOSURE_HISTOGRAM_BINS; b += GROUP_THREADS)
    groupBins[b] = 0u;
  barrier();

  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (all(lessThan(pixel, imageSize(hdr)))) {
    uint bin = exposureBin(exposureLuminance(imageLoad(hdr, pixel).rgb));
    if (bin != EXPOSURE_NOT_COUNTED) atomicAdd(groupBins[bin], 1u);
  }
  barrier();

  ExposureHistogramRef histogram = ExposureHistogramRef(pc.histogram);
  for (uint b = gl_LocalInvocationIndex; b < EXPOSURE_HISTOGRAM_BINS; b += GROUP_THREADS)
    if (groupBins[b] != 0u) atomicAdd(histogram.bins[b], groupBins[b]);
}
