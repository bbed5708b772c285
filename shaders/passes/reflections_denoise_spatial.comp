// reflections-denoise-spatial (DESIGN.md §4 step 6; docs/reflections.md): a few-tap
// edge-stopping filter of reflections.temporal within the reflection lobe's footprint on screen
// (lobeFootprintRadius: zero for mirrors, growing with roughness and hit distance, at most
// spatialMaxRadius). Taps lie on a golden-angle spiral (Vogel 1979) turned by a per-pixel
// angle; each counts only on this pixel's surface (plane, normal, roughness: sameSurface), with
// a Gaussian falloff in distance times its history length in frames: a running mean of N frames
// has 1/N of a sample's variance, so that is its inverse-variance weight. Taps without a sample
// (REFLECTION_NO_SAMPLE: sky, too rough, no history yet) never enter. The weights do not depend
// on the signal, so the filter moves no energy: it blurs the demodulated signal, which holds
// incident radiance only (composite multiplies the reflectance back after).
#version 460
#include "passes/hybrid_frame.glsl"
#include "shared/reflections_denoise_io.h"

layout(local_size_x = HYBRID_GROUP_SIZE, local_size_y = HYBRID_GROUP_SIZE) in;
layout(push_constant, scalar) uniform Push { ReflectionDenoiseConstants pc; };

#include "common/random.glsl"
#include "passes/reflections_denoise.glsl"

layout(set = 1, binding = REFLECTIONS_DENOISE_SPATIAL_BINDING_TEMPORAL, rgba16f) uniform readonly image2D temporal;
layout(set = 1, binding = REFLECTIONS_DENOISE_SPATIAL_BINDING_MOMENTS, rgba32f) uniform readonly image2D moments;
layout(set = 1, binding = REFLECTIONS_DENOISE_SPATIAL_BINDING_SURFACE, rgba32f) uniform readonly image2D surfaces;
layout(set = 1, binding = REFLECTIONS_DENOISE_SPATIAL_BINDING_DEPTH, r32f) uniform readonly image2D depths;
layout(set = 1, binding = REFLECTIONS_DENOISE_SPATIAL_BINDING_OUTPUT, rgba16f) uniform writeonly image2D denoisedOut;

const int SPATIAL_TAPS = 12;
const float GOLDEN_ANGLE = 2.39996323;
const uint RANDOM_REFLECTION_DENOISE_ROTATION = 0x52440001u;

// The surface at traced pixel q as reflections-denoise-temporal kept it; position from the
// GBuffer depth of its full-res pixel.
DenoiseSurface surfaceAt(FrameConstants f, ivec2 q) {
  vec4 e = imageLoad(surfaces, q);
  ivec2 p = fullResPixel(f, q);
  DenoiseSurface s;
  s.viewDepth = imageLoad(depths, p).x;
  s.position = positionFromDepth(f, vec2(p) + 0.5, s.viewDepth);
  s.normal = decodeOctahedral(e.xy);
  s.roughness = e.z;
  return s;
}

// A pixel's filter radius: its lobe's footprint.
float filterRadius(FrameConstants f, float roughness, vec4 pixelMoments) {
  return lobeFootprintRadius(f, roughness, pixelMoments.z);
}

vec4 filtered(FrameConstants f, ivec2 tracedPixel) {
  vec4 centre = imageLoad(temporal, tracedPixel);
  if (centre.w == REFLECTION_NO_SAMPLE) return centre;
  DenoiseSurface here = surfaceAt(f, tracedPixel);
  vec4 centreMoments = imageLoad(moments, tracedPixel);
  float centreFrames = max(centreMoments.y, 1.0);
  float radius = filterRadius(f, here.roughness, centreMoments);
  if (radius < 0.5) return centre;
  vec3 sum = centre.rgb * centreFrames;
  float weightSum = centreFrames;
  // A fixed angle per pixel (not per frame): the output is not fed back, so a per-frame angle
  // would only add flicker.
  float rotation = 6.28318531 * random2(uvec2(tracedPixel), 0u, RANDOM_REFLECTION_DENOISE_ROTATION).x;
  float sigma = 0.5 * radius;
  for (int k = 0; k < SPATIAL_TAPS; ++k) {
    float r = radius * sqrt((float(k) + 0.5) / float(SPATIAL_TAPS));
    float angle = rotation + float(k) * GOLDEN_ANGLE;
    ivec2 q = tracedPixel + ivec2(round(r * vec2(cos(angle), sin(angle))));
    if (q == tracedPixel || !insideTraced(q)) continue;
    vec4 value = imageLoad(temporal, q);
    if (value.w == REFLECTION_NO_SAMPLE || !sameSurface(here, imageLoad(surfaces, q))) continue;
    vec4 tapMoments = imageLoad(moments, q);
    vec2 d = vec2(q - tracedPixel);
    // The support is symmetric: a tap counts only within its own radius too, so that a sharp
    // reflection (a near hit: small footprint) is neither blurred nor blurred into a wide one.
    if (length(d) > filterRadius(f, imageLoad(surfaces, q).z, tapMoments) + 0.5) continue;
    float frames = tapMoments.y;
    float w = exp(-dot(d, d) / (2.0 * sigma * sigma)) * frames;
    if (!(w > 0.0)) continue;
    sum += w * value.rgb;
    weightSum += w;
  }
  return vec4(sum / weightSum, centre.w);
}

void main() {
  FrameConstants f = FrameBlock(pc.frame).v;
  ivec2 tracedPixel = ivec2(gl_GlobalInvocationID.xy);
  if (!insideTraced(tracedPixel)) return;
  imageStore(denoisedOut, tracedPixel, filtered(f, tracedPixel));
}
