// gbuffer-import (bring your own G-buffer): the host's depth, normal, albedo and motion images
// (shared/hybrid_frame_io.h, include/bounce/host_gbuffer.h) turned into Bounce's GBuffer, in the
// encodings `gbuffer` writes, so that shadows and GI run on them unchanged. What the host does
// not give gets fixed defaults: no emission, no UVs, metallic 0, roughness 1, flags SURFACE
// where the depth is positive and finite (else the pixel is sky, all zero as `gbuffer` writes it).
#version 460
#include "passes/hybrid_frame.glsl"

layout(local_size_x = HYBRID_GROUP_SIZE, local_size_y = HYBRID_GROUP_SIZE) in;
layout(push_constant, scalar) uniform Push { HybridPassConstants pc; };

layout(set = 1, binding = GBUFFER_IMPORT_BINDING_HOST_DEPTH, r32f) uniform readonly image2D hostDepth;
layout(set = 1, binding = GBUFFER_IMPORT_BINDING_HOST_NORMAL, rgba16f) uniform readonly image2D hostNormal;
layout(set = 1, binding = GBUFFER_IMPORT_BINDING_HOST_ALBEDO, rgba8) uniform readonly image2D hostAlbedo;
layout(set = 1, binding = GBUFFER_IMPORT_BINDING_HOST_MOTION, rg16f) uniform readonly image2D hostMotion;
layout(set = 1, binding = GBUFFER_IMPORT_BINDING_BASE_COLOR, rgba16f) uniform writeonly image2D baseColorOut;
layout(set = 1, binding = GBUFFER_IMPORT_BINDING_NORMALS, rgba16f) uniform writeonly image2D normalsOut;
layout(set = 1, binding = GBUFFER_IMPORT_BINDING_DEPTH, r32f) uniform writeonly image2D depthOut;
layout(set = 1, binding = GBUFFER_IMPORT_BINDING_UV, rg32f) uniform writeonly image2D uvOut;
layout(set = 1, binding = GBUFFER_IMPORT_BINDING_VELOCITY, rg16f) uniform writeonly image2D velocityOut;
layout(set = 1, binding = GBUFFER_IMPORT_BINDING_EMISSIVE, rgba16f) uniform writeonly image2D emissiveOut;
layout(set = 1, binding = GBUFFER_IMPORT_BINDING_FLAGS, r32ui) uniform writeonly uimage2D flagsOut;

void writeSky(ivec2 pixel) {
  imageStore(baseColorOut, pixel, vec4(0.0));
  imageStore(normalsOut, pixel, vec4(0.0));
  imageStore(depthOut, pixel, vec4(0.0));
  imageStore(uvOut, pixel, vec4(0.0));
  imageStore(velocityOut, pixel, vec4(0.0));
  imageStore(emissiveOut, pixel, vec4(0.0));
  imageStore(flagsOut, pixel, uvec4(0u));
}

void main() {
  FrameConstants f = FrameBlock(pc.frame).v;
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(pixel), f.resolution))) return;
  float depth = imageLoad(hostDepth, pixel).x;
  if (!isFiniteValue(depth) || !(depth > 0.0)) {
    writeSky(pixel);
    return;
  }
  vec3 dir = pixelRayDirection(f, vec2(pixel) + 0.5);
  // A unit normal on the viewer's side, as `gbuffer` writes it; an unusable one faces the viewer.
  vec3 n = imageLoad(hostNormal, pixel).xyz;
  float length2 = dot(n, n);
  n = isFiniteValue(length2) && length2 > 1e-12 ? n * inversesqrt(length2) : -dir;
  if (dot(n, dir) > 0.0) n = -n;
  vec3 albedo = clamp(imageLoad(hostAlbedo, pixel).rgb, 0.0, 1.0);
  vec2 motion = imageLoad(hostMotion, pixel).xy;
  if (!isFiniteValue(motion.x) || !isFiniteValue(motion.y)) motion = vec2(65504.0);

  imageStore(baseColorOut, pixel, vec4(albedo, GBUFFER_IMPORT_METALLIC));
  vec2 octahedral = encodeOctahedral(n);
  imageStore(normalsOut, pixel, vec4(octahedral, octahedral));
  imageStore(depthOut, pixel, vec4(depth));
  imageStore(uvOut, pixel, vec4(0.0));
  imageStore(velocityOut, pixel, vec4(motion, 0.0, 0.0));
  imageStore(emissiveOut, pixel, vec4(0.0, 0.0, 0.0, GBUFFER_IMPORT_ROUGHNESS));
  imageStore(flagsOut, pixel, uvec4(GBUFFER_FLAG_SURFACE));
}
