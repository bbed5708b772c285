// tonemap: exposure, then the ACES filmic curve as fitted by Narkowicz 2015 ("ACES Filmic Tone
// Mapping Curve"), which maps scene-referred radiance to display-referred [0, 1]. The exposure
// is automatic exposure's adapted one (exposure-adapt) or the frame's fixed one. The output
// stays linear; writing it to an sRGB file (or an sRGB swapchain) encodes it.
#version 460
#include "passes/auto_exposure.glsl"
#include "passes/hybrid_frame.glsl"

layout(local_size_x = HYBRID_GROUP_SIZE, local_size_y = HYBRID_GROUP_SIZE) in;
layout(push_constant, scalar) uniform Push { TonemapConstants pc; };

layout(set = 1, binding = TONEMAP_BINDING_HDR, rgba16f) uniform readonly image2D hdr;
layout(set = 1, binding = TONEMAP_BINDING_DISPLAY, rgba16f) uniform writeonly image2D displayOut;

vec3 acesFilmic(vec3 x) {
  const float a = 2.51, b = 0.03, c = 2.43, d = 0.59, e = 0.14;
  return clamp((x * (a * x + b)) / (x * (c * x + d) + e), 0.0, 1.0);
}

float exposure(FrameConstants f) {
  if (pc.exposureState == 0ul) return f.exposure;
  return ExposureStateRef(pc.exposureState).v.exposure;
}

void main() {
  FrameConstants f = FrameBlock(pc.frame).v;
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(pixel), f.resolution))) return;
  vec3 radiance = imageLoad(hdr, pixel).rgb;
  imageStore(displayOut, pixel, vec4(acesFilmic(radiance * exposure(f)), 1.0));
}
