// reblur-stabilize (NRD REBLUR "temporal stabilisation" with anti-lag;
// research/gi10_lux_denoisers.md §2.3 (e), §3.2 step 8): a second, longer running mean (up to
// maxStabilizedFrames, NRD 63) of the post-blurred signal over its own reprojected history,
// reblur.stable, which is first clamped to the fast history's 3x3 neighbourhood, mean +-
// sigmaScale standard deviations (NRD's 2; seed 002's "3 sigma" is a TAA-style clamp, §2.4).
// Anti-lag: where the clamp moved the stable history, its length is cut by 1 + antilagSensitivity
// x (distance moved in standard deviations of luminance), so it follows a change in a few frames.
// Last, the albedo is multiplied back (REBLUR_FLAG_ALBEDO). Pixels without a surface pass through.
#version 460
#include "denoise/reblur_common.glsl"

layout(local_size_x = REBLUR_GROUP_SIZE, local_size_y = REBLUR_GROUP_SIZE) in;

layout(set = 1, binding = REBLUR_STABILIZE_BINDING_INPUT, rgba16f) uniform readonly image2D inputImage;
layout(set = 1, binding = REBLUR_STABILIZE_BINDING_FAST, rgba16f) uniform readonly image2D fastImage;
layout(set = 1, binding = REBLUR_STABILIZE_BINDING_SURFACE, rg32ui) uniform readonly uimage2D surfaces;
layout(set = 1, binding = REBLUR_STABILIZE_BINDING_MOTION, rg16f) uniform readonly image2D motions;
layout(set = 1, binding = REBLUR_STABILIZE_BINDING_PREVIOUS_SURFACE, rg32ui) uniform readonly uimage2D previousSurface;
layout(set = 1, binding = REBLUR_STABILIZE_BINDING_PREVIOUS_STABLE, rgba16f) uniform readonly image2D previousStable;
layout(set = 1, binding = REBLUR_STABILIZE_BINDING_ALBEDO, rgba16f) uniform readonly image2D albedos;
layout(set = 1, binding = REBLUR_STABILIZE_BINDING_STABLE, rgba16f) uniform writeonly image2D stableOut;
layout(set = 1, binding = REBLUR_STABILIZE_BINDING_OUTPUT, rgba16f) uniform writeonly image2D outputImage;

float surfaceDepth(ivec2 q) { return surfaceDepthOf(imageLoad(surfaces, q).xy); }
DEFINE_REBLUR_DEPTH_SLOPE(surfaceDepth)
DEFINE_REBLUR_REPROJECT(previousSurface)
DEFINE_REBLUR_NEIGHBOURHOOD(fastImage, surfaces)

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (!inImage(pixel)) return;
  vec4 current = finiteOrZero4(imageLoad(inputImage, pixel));
  vec4 s = unpackSurface(imageLoad(surfaces, pixel).xy);
  if (!hasSurface(s.w)) {
    imageStore(stableOut, pixel, vec4(current.rgb, 0.0));
    imageStore(outputImage, pixel, vec4(current.rgb, 0.0));
    return;
  }
  float slope = depthSlope(pixel, s.w);
  vec4 history = vec4(0.0);
  vec2 previous = vec2(pixel) + 0.5 - imageLoad(motions, pixel).xy;
  if (pc.historyValid != 0u && isFiniteValue(previous.x) && isFiniteValue(previous.y)) {
    ivec2 p0;
    vec4 w;
    float sum = reprojectWeights(previous, s.w, slope, s.xyz, p0, w);
    if (sum > 1e-3) {
      for (int i = 0; i < 4; ++i)
        if (w[i] > 0.0) history += w[i] * finiteOrZero4(imageLoad(previousStable, p0 + ivec2(i & 1, i >> 1)));
      history /= sum;
    }
  }
  float frames = history.a;
  if (frames > 0.0) {
    vec3 mean, sigma;
    neighbourhood(pixel, s.w, slope, s.xyz, mean, sigma);
    vec3 clamped = clamp(history.rgb, mean - pc.sigmaScale * sigma, mean + pc.sigmaScale * sigma);
    float moved = abs(reblurLuminance(history.rgb - clamped)) / max(reblurLuminance(sigma), 1e-6);
    frames = frames / (1.0 + pc.antilagSensitivity * moved);
    history.rgb = clamped;
  }
  frames = min(frames + 1.0, pc.maxStabilizedFrames);
  vec3 colour = mix(history.rgb, current.rgb, 1.0 / frames);
  imageStore(stableOut, pixel, vec4(colour, frames));
  if ((pc.flags & REBLUR_FLAG_ALBEDO) != 0u) colour *= safeAlbedo(imageLoad(albedos, pixel).rgb);
  imageStore(outputImage, pixel, vec4(colour, current.a));
}
