// hybrid-blend (src/denoise/hybrid_denoiser.h; research/gi10_lux_denoisers.md §2.3 (f);
// docs/denoise.md has the measured thresholds): per pixel, SVGF's output (spatial) or ReBLUR's
// (temporal), or a blend of the two. A pixel's spatial weight is the largest of three ramps,
// each 0 at its "temporal" end and 1 at its "spatial" end:
//   history  ReBLUR's history length n (after anti-lag): 1 at n <= historySpatial (SVGF's own
//            threshold of a young history), 0 at n >= historyTemporal;
//   motion   |motion| in pixels: 0 at motionTemporal, 1 at motionSpatial;
//   variance the signal's relative luminance variance (mu2 - mu1^2) / mu1^2 from SVGF's
//            temporal moments: 0 at varianceTemporal, 1 at varianceSpatial.
// The seed's rule (low variance and motion: temporal; high: spatial; no history: spatial) is
// the two corners; the linear ramps cover the mixed cases, and averaging the weight over
// (2 bandRadius + 1)^2 pixels makes the band where it changes a few pixels wide, so the switch
// between the two filters leaves no seam.
#version 460
#include "shared/reblur_io.h"

layout(local_size_x = REBLUR_GROUP_SIZE, local_size_y = REBLUR_GROUP_SIZE) in;
layout(push_constant, scalar) uniform Push { HybridBlendConstants pc; };

layout(set = 1, binding = HYBRID_BLEND_BINDING_SVGF, rgba16f) uniform readonly image2D svgfImage;
layout(set = 1, binding = HYBRID_BLEND_BINDING_REBLUR, rgba16f) uniform readonly image2D reblurImage;
layout(set = 1, binding = HYBRID_BLEND_BINDING_MOMENTS, rgba32f) uniform readonly image2D momentsImage;
layout(set = 1, binding = HYBRID_BLEND_BINDING_MOTION, rg16f) uniform readonly image2D motions;
layout(set = 1, binding = HYBRID_BLEND_BINDING_OUTPUT, rgba16f) uniform writeonly image2D outputImage;

bool inImage(ivec2 p) { return all(greaterThanEqual(p, ivec2(0))) && all(lessThan(p, ivec2(pc.resolution))); }

// 0 at `zero`, 1 at `one`, linear between (either order).
float ramp(float x, float zero, float one) { return clamp((x - zero) / (one - zero), 0.0, 1.0); }

float spatialWeight(ivec2 q) {
  float n = imageLoad(reblurImage, q).a;
  float historyRamp = ramp(n, pc.historyTemporal, pc.historySpatial);
  vec2 motion = imageLoad(motions, q).xy;
  float speed = any(isnan(motion)) || any(isinf(motion)) ? 1e30 : length(motion);
  float motionRamp = ramp(speed, pc.motionTemporal, pc.motionSpatial);
  vec2 m = imageLoad(momentsImage, q).xy;
  float relativeVariance = max(m.y - m.x * m.x, 0.0) / max(m.x * m.x, 1e-8);
  float varianceRamp = ramp(relativeVariance, pc.varianceTemporal, pc.varianceSpatial);
  float w = max(historyRamp, max(motionRamp, varianceRamp));
  return isnan(w) ? 1.0 : w;
}

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (!inImage(pixel)) return;
  int r = int(pc.bandRadius);
  float sum = 0.0, count = 0.0;
  for (int dy = -r; dy <= r; ++dy)
    for (int dx = -r; dx <= r; ++dx) {
      ivec2 q = pixel + ivec2(dx, dy);
      if (!inImage(q)) continue;
      sum += spatialWeight(q);
      count += 1.0;
    }
  float w = sum / count;
  vec3 colour = mix(imageLoad(reblurImage, pixel).rgb, imageLoad(svgfImage, pixel).rgb, w);
  imageStore(outputImage, pixel, pc.debugWeight != 0u ? vec4(w, w, w, 1.0) : vec4(colour, w));
}
