// reflections-trace-mirrors (docs/reflections.md, "Mirrors at render resolution"): a mirror
// pixel (roughness below mirrorRoughness) whose upsampled reflection came from traced rays that
// look elsewhere traces its own mirror ray and writes what it sees into `reflections`, over
// what reflections-upsample put there. A mirror's reflection follows its exact direction, which
// on a curved mirror turns by twice the normal's turn per pixel: one ray per divisor x divisor
// block, upsampled, shows a neighbour's view. On a flat mirror the block's rays are nearly
// parallel and the upsampled (reused, denoised) signal stays. The ray is lit as
// reflections-trace lights its rays (passes/reflection_hit.glsl); its signal is already
// demodulated (a mirror's weight G2/G1 is 1) and goes to composite without reuse or the
// reflection denoiser (TAA averages the hit's light samples).
#version 460
#include "common/random.glsl"
#include "gi/evolve/restir/restir_gi_common.glsl"
#include "passes/hybrid_frame.glsl"
#include "shared/specular_io.h"

layout(local_size_x = HYBRID_GROUP_SIZE, local_size_y = HYBRID_GROUP_SIZE) in;
layout(push_constant, scalar) uniform Push { ReflectionPassConstants pc; };

layout(set = 1, binding = REFLECTIONS_TRACE_MIRRORS_BINDING_NORMALS, rgba16f) uniform readonly image2D normals;
layout(set = 1, binding = REFLECTIONS_TRACE_MIRRORS_BINDING_DEPTH, r32f) uniform readonly image2D depths;
layout(set = 1, binding = REFLECTIONS_TRACE_MIRRORS_BINDING_EMISSIVE, rgba16f) uniform readonly image2D emissives;
layout(set = 1, binding = REFLECTIONS_TRACE_MIRRORS_BINDING_FLAGS, r32ui) uniform readonly uimage2D flags;
layout(set = 1, binding = REFLECTIONS_TRACE_MIRRORS_BINDING_REFLECTIONS, rgba16f) uniform writeonly image2D reflectionsOut;
layout(set = 1, binding = REFLECTIONS_TRACE_MIRRORS_BINDING_TRACED, rgba16f) uniform readonly image2D traced;

// reflections-upsample's test of a traced pixel's surface (its PLANE_TOLERANCE).
const float PLANE_TOLERANCE = 0.01;  // of view depth

const uint RANDOM_REFLECTION_MIRROR_HIT = 0x52460004u;

#include "passes/reflection_hit.glsl"

// Whether the pixel is a mirror (reflections-trace's rule: below mirrorRoughness, not Lambert).
bool isMirror(FrameConstants f, ivec2 pixel) {
  if ((imageLoad(flags, pixel).x & GBUFFER_FLAG_SURFACE) == 0u) return false;
  if ((f.flags & FRAME_FLAG_LAMBERT) != 0u) return false;
  return imageLoad(emissives, pixel).w < pc.mirrorRoughness;
}

// The full-res pixel a traced pixel stands for (reflections_trace.comp's rule).
ivec2 fullResPixel(FrameConstants f, ivec2 tracedPixel) {
  ivec2 p = tracedPixel * int(pc.divisor) + int(pc.divisor / 2u);
  return min(p, ivec2(f.resolution) - 1);
}

vec3 mirrorDirectionAt(FrameConstants f, ivec2 pixel, out vec3 position) {
  vec3 n = decodeOctahedral(imageLoad(normals, pixel).xy);
  position = positionFromDepth(f, vec2(pixel) + 0.5, imageLoad(depths, pixel).x);
  return reflect(pixelRayDirection(f, vec2(pixel) + 0.5), n);
}

// Whether reflections-upsample served this pixel from rays that look where its own would: at
// least one of the four traced pixels it reads is on its surface, and every one of those
// reflects within mirrorDirectionCosine of its mirror direction.
bool upsampledRaysAgree(FrameConstants f, ivec2 pixel) {
  vec3 position;
  vec3 dir = mirrorDirectionAt(f, pixel, position);
  vec3 n = decodeOctahedral(imageLoad(normals, pixel).xy);
  float depth = imageLoad(depths, pixel).x;
  vec2 u = (vec2(pixel) - float(pc.divisor / 2u)) / float(pc.divisor);
  ivec2 base = ivec2(floor(u));
  ivec2 maxTraced = ivec2(pc.tracedResolution) - 1;
  bool anyOnSurface = false;
  for (int k = 0; k < 4; ++k) {
    ivec2 tap = clamp(base + ivec2(k & 1, k >> 1), ivec2(0), maxTraced);
    if (imageLoad(traced, tap).w == REFLECTION_NO_SAMPLE) continue;
    vec3 sourcePosition;
    vec3 sourceDir = mirrorDirectionAt(f, fullResPixel(f, tap), sourcePosition);
    if (abs(dot(n, sourcePosition - position)) > PLANE_TOLERANCE * max(depth, 1e-6)) continue;
    anyOnSurface = true;
    if (dot(dir, sourceDir) < pc.mirrorDirectionCosine) return false;
  }
  return anyOnSurface;
}

// The radiance the pixel's mirror direction sees; zero where that direction leaves through the
// geometric surface (as reflections-trace counts it).
vec3 mirrorRadiance(FrameConstants f, ivec2 pixel) {
  vec4 encodedNormals = imageLoad(normals, pixel);
  vec3 n = decodeOctahedral(encodedNormals.xy);
  vec3 ng = decodeOctahedral(encodedNormals.zw);
  vec3 wo = -pixelRayDirection(f, vec2(pixel) + 0.5);
  vec3 dir = reflect(-wo, n);
  if (dot(n, wo) <= 0.0 || dot(dir, ng) <= 0.0) return vec3(0.0);
  vec3 position = positionFromDepth(f, vec2(pixel) + 0.5, imageLoad(depths, pixel).x);
  float alpha = makeBrdfMaterial(vec3(1.0), 0.0, imageLoad(emissives, pixel).w, false).alpha;
  uint seed = f.frameIndex ^ (pc.seed * 0x9E3779B9u);
  uvec4 key = pcg4d(uvec4(pixel, seed, RANDOM_REFLECTION_MIRROR_HIT));
  // incomingRadiance also describes the hit as a reservoir sample, which only the reuse passes
  // of reflections-trace's rays need.
  float hitDistance;
  Reservoir ignoredSample = emptyReservoir();
  ignoredSample.origin = offsetRayOrigin(position, ng);
  return incomingRadiance(f, ignoredSample.origin, dir, alpha, key, hitDistance, ignoredSample);
}

void main() {
  FrameConstants f = FrameBlock(pc.frame).v;
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(pixel), f.resolution)) || !isMirror(f, pixel) || upsampledRaysAgree(f, pixel)) return;
  lightTables = LightTablesBlock(pc.lights).v;
  vec3 radiance = mirrorRadiance(f, pixel);
  // Nothing non-finite reaches composite.
  if (any(isnan(radiance)) || any(isinf(radiance))) radiance = vec3(0.0);
  imageStore(reflectionsOut, pixel, vec4(min(radiance, vec3(65000.0)), 1.0));
}
