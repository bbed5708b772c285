// shadows-trace: one sun visibility ray per pixel of the (half-res on both presets) shadow
// image, in a direction drawn uniformly from the sun's disc (its angular diameter), so that
// accumulating frames gives the soft penumbra; shadows-denoise accumulates and upsamples.
// Each shadow pixel traces from the full-res GBuffer pixel nearest its centre.
#version 460
#include "common/random.glsl"
#include "common/ray_offset.glsl"
#include "common/sampling.glsl"
#include "passes/hybrid_frame.glsl"
#include "rt/trace.glsl"

layout(local_size_x = HYBRID_GROUP_SIZE, local_size_y = HYBRID_GROUP_SIZE) in;
layout(push_constant, scalar) uniform Push { HybridPassConstants pc; };

layout(set = 1, binding = SHADOWS_TRACE_BINDING_NORMALS, rgba16f) uniform readonly image2D normals;
layout(set = 1, binding = SHADOWS_TRACE_BINDING_DEPTH, r32f) uniform readonly image2D depths;
layout(set = 1, binding = SHADOWS_TRACE_BINDING_FLAGS, r32ui) uniform readonly uimage2D flags;
layout(set = 1, binding = SHADOWS_TRACE_BINDING_RAW, rg16f) uniform writeonly image2D rawOut;

// The full-res pixel a shadow pixel stands for (shadows-denoise uses the same rule).
ivec2 fullResPixel(FrameConstants f, ivec2 shadowPixel) {
  ivec2 p = shadowPixel * int(f.shadowDivisor) + int(f.shadowDivisor / 2u);
  return min(p, ivec2(f.resolution) - 1);
}

// Whether instance i stands elsewhere than last frame (FrameConstants::previousInstances).
bool instanceMoved(FrameConstants f, uint i) {
  GpuInstance now = sceneInstance(i);
  GpuInstance before = InstanceArray(f.previousInstances).v[i];
  return any(notEqual(now.objectToWorld[0], before.objectToWorld[0])) ||
         any(notEqual(now.objectToWorld[1], before.objectToWorld[1])) ||
         any(notEqual(now.objectToWorld[2], before.objectToWorld[2]));
}

// The sun's visibility (0 or 1) and whether what blocks it moved this frame (1: its shadow may
// be moving over pixels that stand still; shadows-denoise then follows it).
vec2 sunVisibility(FrameConstants f, ivec2 pixel) {
  if ((imageLoad(flags, pixel).x & GBUFFER_FLAG_SURFACE) == 0u) return vec2(1.0, 0.0);
  vec3 geometricNormal = decodeOctahedral(imageLoad(normals, pixel).zw);
  vec3 dir = sampleCone(f.towardSun, f.sunCosHalfAngle, random2(uvec2(pixel), f.frameIndex, RANDOM_SUN_CONE));
  if (dot(geometricNormal, dir) <= 0.0) return vec2(0.0);  // the sun is behind the surface
  vec3 position = positionFromDepth(f, vec2(pixel) + 0.5, imageLoad(depths, pixel).x);
  vec3 origin = offsetRayOrigin(position, geometricNormal);
  TraceHit blocker = traceAnyHit(origin, dir, 0.0, 3.0e38, true);
  if (!traceHitFound(blocker)) return vec2(1.0, 0.0);
  bool moved = (f.flags & FRAME_FLAG_SCENE_MOVED) != 0u && instanceMoved(f, blocker.instance);
  return vec2(0.0, moved ? 1.0 : 0.0);
}

void main() {
  FrameConstants f = FrameBlock(pc.frame).v;
  ivec2 shadowPixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(shadowPixel), f.shadowResolution))) return;
  vec2 visibility = all(equal(f.sunIrradiance, vec3(0.0))) ? vec2(0.0)
                                                            : sunVisibility(f, fullResPixel(f, shadowPixel));
  imageStore(rawOut, shadowPixel, vec4(visibility, 0.0, 0.0));
}
