// reflections-upsample: brings reflections.traced to render resolution with a joint bilateral
// upsample (Kopf et al. 2007), as shadows-denoise does for the sun's visibility: the four
// nearest traced pixels, bilinear weights times how well each one's surface agrees with this
// pixel's (distance to this pixel's tangent plane, shading-normal similarity; reflections
// change with the normal far faster than shadows do, hence the sharper normal power). Traced
// pixels without a sample (sky, too rough) are skipped; where no neighbour shares the surface,
// the most similar one with a sample stands in, and with none at all w = 0 tells composite to
// fall back to the diffuse light.
#version 460
#include "passes/hybrid_frame.glsl"
#include "shared/specular_io.h"

layout(local_size_x = HYBRID_GROUP_SIZE, local_size_y = HYBRID_GROUP_SIZE) in;
layout(push_constant, scalar) uniform Push { ReflectionPassConstants pc; };

layout(set = 1, binding = REFLECTIONS_UPSAMPLE_BINDING_TRACED, rgba16f) uniform readonly image2D traced;
layout(set = 1, binding = REFLECTIONS_UPSAMPLE_BINDING_NORMALS, rgba16f) uniform readonly image2D normals;
layout(set = 1, binding = REFLECTIONS_UPSAMPLE_BINDING_DEPTH, r32f) uniform readonly image2D depths;
layout(set = 1, binding = REFLECTIONS_UPSAMPLE_BINDING_FLAGS, r32ui) uniform readonly uimage2D flags;
layout(set = 1, binding = REFLECTIONS_UPSAMPLE_BINDING_OUTPUT, rgba16f) uniform writeonly image2D reflectionsOut;

const float PLANE_TOLERANCE = 0.01;  // of view depth
const float NORMAL_POWER = 32.0;

// Must match reflections_trace.comp.
ivec2 fullResPixel(FrameConstants f, ivec2 tracedPixel) {
  ivec2 p = tracedPixel * int(pc.divisor) + int(pc.divisor / 2u);
  return min(p, ivec2(f.resolution) - 1);
}

vec4 upsampled(FrameConstants f, ivec2 pixel) {
  float depth = imageLoad(depths, pixel).x;
  vec3 position = positionFromDepth(f, vec2(pixel) + 0.5, depth);
  vec3 normal = decodeOctahedral(imageLoad(normals, pixel).xy);
  float d = float(pc.divisor);
  vec2 u = (vec2(pixel) - float(pc.divisor / 2u)) / d;
  ivec2 base = ivec2(floor(u));
  vec2 t = u - vec2(base);
  ivec2 maxTraced = ivec2(pc.tracedResolution) - 1;
  vec3 sum = vec3(0.0);
  float weightSum = 0.0;
  vec3 nearest = vec3(0.0);
  float nearestScore = -1.0;
  for (int k = 0; k < 4; ++k) {
    ivec2 offset = ivec2(k & 1, k >> 1);
    ivec2 tap = clamp(base + offset, ivec2(0), maxTraced);
    vec4 value = imageLoad(traced, tap);
    if (value.w == REFLECTION_NO_SAMPLE) continue;
    ivec2 source = fullResPixel(f, tap);
    float sourceDepth = imageLoad(depths, source).x;
    vec3 sourcePosition = positionFromDepth(f, vec2(source) + 0.5, sourceDepth);
    vec3 sourceNormal = decodeOctahedral(imageLoad(normals, source).xy);
    float planeDistance = abs(dot(normal, sourcePosition - position)) / max(depth, 1e-6);
    float similarity = exp(-planeDistance / PLANE_TOLERANCE) * pow(max(dot(normal, sourceNormal), 0.0), NORMAL_POWER);
    float bilinear = (offset.x == 1 ? t.x : 1.0 - t.x) * (offset.y == 1 ? t.y : 1.0 - t.y);
    sum += bilinear * similarity * value.rgb;
    weightSum += bilinear * similarity;
    if (similarity > nearestScore) {
      nearestScore = similarity;
      nearest = value.rgb;
    }
  }
  if (weightSum > 1e-4) return vec4(sum / weightSum, 1.0);
  return nearestScore >= 0.0 ? vec4(nearest, 1.0) : vec4(0.0);
}

void main() {
  FrameConstants f = FrameBlock(pc.frame).v;
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(pixel), f.resolution))) return;
  bool surface = (imageLoad(flags, pixel).x & GBUFFER_FLAG_SURFACE) != 0u;
  imageStore(reflectionsOut, pixel, surface ? upsampled(f, pixel) : vec4(0.0));
}
