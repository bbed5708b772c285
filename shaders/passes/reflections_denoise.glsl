// What reflections-denoise-temporal and reflections-denoise-spatial share: the surface a traced
// pixel stands for, how it is kept in reflections.temporal-surface, when two pixels count as the
// same surface, the history length a roughness gets, and the lobe's footprint on screen.
// The including shader declares `pc` (ReflectionDenoiseConstants) first.
#ifndef BOUNCE_PASSES_REFLECTIONS_DENOISE_GLSL
#define BOUNCE_PASSES_REFLECTIONS_DENOISE_GLSL
#include "common/brdf.glsl"
#include "passes/hybrid_frame.glsl"
#include "shared/reflections_denoise_io.h"
#include "shared/specular_io.h"

// The full-res pixel a traced pixel stands for: must match reflections_trace.comp.
ivec2 fullResPixel(FrameConstants f, ivec2 tracedPixel) {
  ivec2 p = tracedPixel * int(pc.divisor) + int(pc.divisor / 2u);
  return min(p, ivec2(f.resolution) - 1);
}

bool insideTraced(ivec2 q) {
  return all(greaterThanEqual(q, ivec2(0))) && all(lessThan(q, ivec2(pc.tracedResolution)));
}

struct DenoiseSurface {
  vec3 position;
  vec3 normal;  // shading normal
  float roughness;  // perceptual; negative: no surface
  float viewDepth;
};

bool hasSurface(DenoiseSurface s) { return s.roughness >= 0.0; }

// reflections.temporal-surface: xy octahedral normal, z roughness (negative: none), w the plane
// offset dot(n, x).
vec4 encodeSurface(DenoiseSurface s) {
  return hasSurface(s) ? vec4(encodeOctahedral(s.normal), s.roughness, dot(s.normal, s.position))
                       : vec4(0.0, 0.0, -1.0, 0.0);
}

// The cosine of the largest normal difference between two pixels whose reflections may be
// mixed: a normal turned by t turns the reflected direction by 2 t, which a lobe of GGX alpha
// (half-angle about 2 atan(alpha)) hides while t <= atan(alpha). So mirrorNormalTolerance plus
// atan(alpha), at most normalTolerance (ReflectionDenoiseSettings).
float normalToleranceCosine(float roughness) {
  float alpha = roughness * roughness;
  return cos(min(pc.mirrorNormalTolerance + atan(alpha), pc.normalTolerance));
}

// Another pixel's surface (its history or its neighbour) counts as this one's when this pixel's
// point lies on its tangent plane (within planeTolerance of view depth) and its normal and
// roughness are close (ReflectionDenoiseSettings).
bool sameSurface(DenoiseSurface here, vec4 other) {
  if (!hasSurface(here) || other.z < 0.0) return false;
  vec3 n = decodeOctahedral(other.xy);
  float planeDistance = abs(dot(n, here.position) - other.w);
  return planeDistance <= pc.planeTolerance * here.viewDepth && dot(n, here.normal) >= normalToleranceCosine(here.roughness) &&
         abs(other.z - here.roughness) <= pc.roughnessTolerance;
}

// History length for a roughness: mirrorHistoryFrames at 0, growing linearly to
// glossyHistoryFrames at glossyHistoryRoughness.
float maxHistoryFrames(float roughness) {
  return mix(pc.mirrorHistoryFrames, pc.glossyHistoryFrames, clamp(roughness / pc.glossyHistoryRoughness, 0.0, 1.0));
}

// Whether a reflection is ever traced for this roughness (reflections_trace.comp's rule).
bool traceable(FrameConstants f, float roughness) {
  return (f.flags & FRAME_FLAG_LAMBERT) == 0u && roughness <= pc.maxTracedRoughness;
}

// Radians one render pixel spans at the image centre (GpuCamera's up is tan(vfov / 2)).
float pixelAngle(FrameConstants f) { return 2.0 * length(f.camera.up) / float(f.resolution.y); }

// The spatial filter's radius in traced pixels: the reflection lobe's footprint on screen. A
// GGX lobe of alpha = roughness^2 spreads reflected directions over a half-angle of about
// 2 atan(alpha) (twice the normals' spread); at hit distance h, seen through a surface at
// distance d, that blur spans an angle of half-angle x parallax from the camera, parallax =
// h / (d + h) (a miss: 1, the whole half-angle). A mirror's footprint is 0.
float lobeFootprintRadius(FrameConstants f, float roughness, float parallax) {
  float alpha = roughness * roughness;
  float halfAngle = 2.0 * atan(alpha);
  float angle = halfAngle * clamp(parallax, 0.0, 1.0);
  float radius = pc.spatialFootprintScale * angle / (pixelAngle(f) * float(pc.divisor));
  return min(radius, pc.spatialMaxRadius);
}

#endif
