// hybrid-blend (src/denoise/hybrid_denoiser.h; research/gi10_lux_denoisers.md §2.3 (f);
// docs/denoise.md has the measured thresholds): per pixel, SVGF's output (spatial) or ReBLUR's
// (temporal), or a blend of the two, mix(reblur, svgf, w). w is hybrid-classify's per-pixel
// spatial weight (the rule is there) averaged over (2 bandRadius + 1)^2 pixels, so that the band
// where it changes is a few pixels wide and the switch between the two filters leaves no seam.
// Where the average is exactly 0 or 1 only one filter ran on the tile (hybrid-classify's tile
// classes), so only that one is read.
#version 460
#include "shared/reblur_io.h"

layout(local_size_x = REBLUR_GROUP_SIZE, local_size_y = REBLUR_GROUP_SIZE) in;
layout(push_constant, scalar) uniform Push { HybridBlendConstants pc; };

layout(set = 1, binding = HYBRID_BLEND_BINDING_SVGF, rgba16f) uniform readonly image2D svgfImage;
layout(set = 1, binding = HYBRID_BLEND_BINDING_REBLUR, rgba16f) uniform readonly image2D reblurImage;
layout(set = 1, binding = HYBRID_BLEND_BINDING_WEIGHT, rgba16f) uniform readonly image2D weightImage;
layout(set = 1, binding = HYBRID_BLEND_BINDING_OUTPUT, rgba16f) uniform writeonly image2D outputImage;

bool inImage(ivec2 p) { return all(greaterThanEqual(p, ivec2(0))) && all(lessThan(p, ivec2(pc.resolution))); }

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (!inImage(pixel)) return;
  int r = int(pc.bandRadius);
  float sum = 0.0, count = 0.0;
  for (int dy = -r; dy <= r; ++dy)
    for (int dx = -r; dx <= r; ++dx) {
      ivec2 q = pixel + ivec2(dx, dy);
      if (!inImage(q)) continue;
      sum += imageLoad(weightImage, q).r;
      count += 1.0;
    }
  float w = sum / count;
  vec3 colour = w >= 1.0 ? imageLoad(svgfImage, pixel).rgb
              : w <= 0.0 ? imageLoad(reblurImage, pixel).rgb
                         : mix(imageLoad(reblurImage, pixel).rgb, imageLoad(svgfImage, pixel).rgb, w);
  imageStore(outputImage, pixel, pc.debugWeight != 0u ? vec4(w, w, w, 1.0) : vec4(colour, w));
}
