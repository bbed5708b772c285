// reference-path-trace: adds a batch of path-traced samples to every pixel's running sum (the
// ground-truth renderer, src/reference/path_tracer.h). Samples whose value is NaN or infinite are
// dropped and counted, so they can never poison the image; the count is reported.
#version 460
#include "reference/integrator.glsl"

layout(local_size_x = REFERENCE_GROUP_SIZE, local_size_y = REFERENCE_GROUP_SIZE) in;
layout(push_constant, scalar) uniform Push { ReferenceConstants pc; };

void main() {
  settings = ReferenceSettingsBlock(pc.settings).v;
  lightTables = settings.lights;
  uvec2 pixel = gl_GlobalInvocationID.xy;
  if (any(greaterThanEqual(pixel, settings.resolution))) return;
  AccumulationArray accumulation = AccumulationArray(settings.accumulation);
  uint index = pixel.y * settings.resolution.x + pixel.x;
  vec4 sum = accumulation.v[index];
  uint dropped = 0u;
  for (uint i = 0u; i < pc.sampleCount; ++i) {
    vec3 radiance = tracePath(pixel, pc.firstSample + i);
    if (any(isnan(radiance)) || any(isinf(radiance)))
      ++dropped;
    else
      sum.rgb += radiance;
  }
  accumulation.v[index] = sum;
  if (dropped > 0u) atomicAdd(CounterArray(settings.counters).v[REFERENCE_COUNTER_NON_FINITE], dropped);
}
