// hybrid-classify (src/denoise/hybrid_denoiser.h; docs/denoise.md, "The hybrid's tiles"): each
// pixel's spatial weight w (1: SVGF alone, 0: ReBLUR alone), and for each 8x8 tile which filter
// the blend will read there, so that the expensive passes (SVGF's à-trous iterations, ReBLUR's
// blurs) skip the tiles where their output is not used. It runs after svgf-temporal and
// reblur-history-fix, whose outputs the rule reads. w is the largest of three ramps, each 0 at
// its "temporal" end and 1 at its "spatial" end (research/gi10_lux_denoisers.md §2.3 (f)):
//   history  ReBLUR's history length n after anti-lag: 1 at n <= historySpatial (SVGF's own
//            threshold of a young history), 0 at n >= historyTemporal;
//   motion   |motion| in pixels: 0 at motionTemporal, 1 at motionSpatial;
//   variance the signal's relative luminance variance (mu2 - mu1^2) / mu1^2 from SVGF's
//            temporal moments: 0 at varianceTemporal, 1 at varianceSpatial.
// hybrid-blend averages w over (2 bandRadius + 1)^2 pixels, so a tile's class looks at the tile
// widened by bandRadius: SVGF is needed where any w there is above 0, ReBLUR where any is below 1.
#version 460
#include "shared/reblur_io.h"

layout(local_size_x = HYBRID_TILE_SIZE, local_size_y = HYBRID_TILE_SIZE) in;
layout(push_constant, scalar) uniform Push { HybridBlendConstants pc; };

layout(set = 1, binding = HYBRID_CLASSIFY_BINDING_REBLUR, rgba16f) uniform readonly image2D reblurImage;
layout(set = 1, binding = HYBRID_CLASSIFY_BINDING_MOMENTS, rgba32f) uniform readonly image2D momentsImage;
layout(set = 1, binding = HYBRID_CLASSIFY_BINDING_MOTION, rg16f) uniform readonly image2D motions;
layout(set = 1, binding = HYBRID_CLASSIFY_BINDING_WEIGHT, rgba16f) uniform writeonly image2D weightImage;
layout(set = 1, binding = HYBRID_CLASSIFY_BINDING_TILES, rgba16f) uniform writeonly image2D tileImage;

shared uint needsSvgf;
shared uint needsReblur;

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
  if (gl_LocalInvocationIndex == 0u) {
    needsSvgf = 0u;
    needsReblur = 0u;
  }
  barrier();
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (inImage(pixel)) imageStore(weightImage, pixel, vec4(spatialWeight(pixel), 0.0, 0.0, 1.0));
  // The tile widened by the band, (8 + 2 r)^2 pixels, shared out over the 64 invocations.
  int r = int(pc.bandRadius);
  int side = int(HYBRID_TILE_SIZE) + 2 * r;
  ivec2 origin = ivec2(gl_WorkGroupID.xy) * int(HYBRID_TILE_SIZE) - r;
  bool svgf = false, reblur = false;
  for (int i = int(gl_LocalInvocationIndex); i < side * side; i += int(HYBRID_TILE_SIZE * HYBRID_TILE_SIZE)) {
    ivec2 q = origin + ivec2(i % side, i / side);
    if (!inImage(q)) continue;
    float w = spatialWeight(q);
    svgf = svgf || w > 0.0;
    reblur = reblur || w < 1.0;
  }
  if (svgf) atomicOr(needsSvgf, 1u);
  if (reblur) atomicOr(needsReblur, 1u);
  barrier();
  if (gl_LocalInvocationIndex == 0u)
    imageStore(tileImage, ivec2(gl_WorkGroupID.xy), vec4(float(needsSvgf), float(needsReblur), 0.0, 1.0));
}
