// sky: the radiance of the sky where no surface is seen (the scene's constant sky or the
// daylight model of shaders/common/sky.glsl, driven by the sun), zero over surfaces.
#version 460
#include "passes/hybrid_frame.glsl"

layout(local_size_x = HYBRID_GROUP_SIZE, local_size_y = HYBRID_GROUP_SIZE) in;
layout(push_constant, scalar) uniform Push { HybridPassConstants pc; };

layout(set = 1, binding = SKY_BINDING_FLAGS, r32ui) uniform readonly uimage2D flags;
layout(set = 1, binding = SKY_BINDING_RADIANCE, rgba16f) uniform writeonly image2D radianceOut;

void main() {
  FrameConstants f = FrameBlock(pc.frame).v;
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(pixel), f.resolution))) return;
  bool surface = (imageLoad(flags, pixel).x & GBUFFER_FLAG_SURFACE) != 0u;
  vec3 radiance = surface ? vec3(0.0) : skyRadianceToward(f, pixelRayDirection(f, vec2(pixel) + 0.5));
  imageStore(radianceOut, pixel, vec4(min(radiance, vec3(65000.0)), 1.0));
}
