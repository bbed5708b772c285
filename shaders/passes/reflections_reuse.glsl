// What reflections-temporal, reflections-spatial and reflections-resolve share
// (shared/reflections_reuse_io.h, docs/reflections.md "Reuse"): the receiving pixel, the GGX
// target function, the sample's direction, and the end of a stream. The reservoir encoding,
// the reconnection Jacobian, the streaming and the surface tests are ReSTIR GI's
// (gi/evolve/restir/restir_gi_common.glsl).
#ifndef BOUNCE_PASSES_REFLECTIONS_REUSE_GLSL
#define BOUNCE_PASSES_REFLECTIONS_REUSE_GLSL
#include "gi/evolve/restir/restir_gi_common.glsl"
#include "common/ray_offset.glsl"
#include "lighting/specular_albedo.glsl"
#include "shared/reflections_reuse_io.h"
#include "shared/specular_io.h"

const uint RANDOM_REFLECTION_TEMPORAL = 0x52460010u;
const uint RANDOM_REFLECTION_SPATIAL = 0x52460011u;

// The full-res pixel a traced pixel stands for (reflections-trace's rule).
ivec2 reflectionRepresentativePixel(FrameConstants f, uint divisor, ivec2 tracedPixel) {
  ivec2 p = tracedPixel * int(divisor) + int(divisor / 2u);
  return min(p, ivec2(f.resolution) - 1);
}

// The pixel whose reflection is estimated: x1 (the reflection ray's origin, offset off the
// surface as reflections-trace offsets it), its normals, the direction to the viewer and the lobe.
struct ReflectionReceiver {
  PrimaryVertex x;
  vec3 wo;
  float nDotV;
  float roughness;  // perceptual
  float alpha;      // GGX
};

ReflectionReceiver makeReflectionReceiver(FrameConstants f, ivec2 pixel, vec4 encodedNormals,
                                          float depth, float roughness) {
  ReflectionReceiver p;
  p.x = makePrimaryVertex(f, pixel, encodedNormals, depth);
  p.x.position = offsetRayOrigin(p.x.position, p.x.geometricNormal);
  p.wo = -pixelRayDirection(f, vec2(pixel) + 0.5);
  p.nDotV = dot(p.x.shadingNormal, p.wo);
  p.roughness = roughness;
  p.alpha = makeBrdfMaterial(vec3(1.0), 0.0, roughness, false).alpha;
  return p;
}

// Whether a pixel's sample is reused: a glossy sample was traced (M > 0: not a mirror, not too
// rough, a surface) and the lobe is wide enough (ReflectionSettings::reuseMinRoughness).
bool reflectionReused(ReflectionReuseConstants c, FrameConstants f, Reservoir candidate, float roughness) {
  return candidate.M > 0.0 && roughness >= c.reuseMinRoughness && (f.flags & FRAME_FLAG_LAMBERT) == 0u;
}

// The direction of r's sample seen from `position`: towards x2, or the sky sample's own
// direction (a sample at infinity: the reconnection shift keeps it, Jacobian 1).
vec3 reflectionSampleDirection(vec3 position, Reservoir r) {
  if (r.kind == RESTIR_GI_KIND_SKY) return normalize(r.samplePosition - r.origin);
  return normalize(r.samplePosition - position);
}

// The Fresnel-free GGX BRDF x cos, D Vis (n.l) (common/brdf.glsl), of direction l at p; zero
// below its geometric or shading surface (reflections-trace gives such directions zero light).
float glossyBrdfCosine(ReflectionReceiver p, vec3 l) {
  float nDotL = dot(p.x.shadingNormal, l);
  if (p.nDotV <= 0.0 || nDotL <= 0.0 || dot(l, p.x.geometricNormal) <= 0.0) return 0.0;
  vec3 h = normalize(p.wo + l);
  return ggxDistribution(max(dot(p.x.shadingNormal, h), 0.0), p.alpha) * ggxVisibility(nDotL, p.nDotV, p.alpha) * nDotL;
}

// p_hat at p of r's sample shifted to p: luminance(L) D Vis (n.l).
float reflectionTarget(ReflectionReceiver p, Reservoir r) {
  if (r.kind == RESTIR_GI_KIND_NONE) return 0.0;
  return max(brdfLuminance(r.radiance), 0.0) * glossyBrdfCosine(p, reflectionSampleDirection(p.x.position, r));
}

// Adds r to the stream at p by the reconnection shift (its Jacobian; 1 for the sky).
void streamReflection(inout ReservoirStream s, ReflectionReceiver p, Reservoir r, float u) {
  float jacobian = reconnectionJacobian(r.origin, p.x.position, r);
  streamReservoirWithTarget(s, r, reflectionTarget(p, r), jacobian, REFLECTION_REUSE_MAX_JACOBIAN, u);
}

// The stream's reservoir re-homed at p, W normalised by confidence z (restir_gi_common.glsl); a
// sky sample keeps its direction: it is stored again as a far point from p's x1.
Reservoir endReflectionStream(ReservoirStream s, ReflectionReceiver p, float z) {
  vec3 skyDirection = reflectionSampleDirection(p.x.position, s.chosen);
  Reservoir r = endStreamNormalised(s, p.x, z);
  if (r.kind == RESTIR_GI_KIND_SKY) r.samplePosition = r.origin + skyDirection * RESTIR_GI_SKY_DISTANCE;
  return r;
}

// Whether reservoirs at q and at p count as one surface with one lobe (reuse between them).
bool reflectionReusable(ReflectionReceiver p, Reservoir r, float roughness) {
  return r.M > 0.0 && abs(roughness - p.roughness) <= REFLECTION_REUSE_ROUGHNESS_TOLERANCE &&
         sameSurfaceWithin(p.x, r.origin, r.originNormal, REFLECTION_REUSE_PLANE_TOLERANCE,
                           REFLECTION_REUSE_NORMAL_TOLERANCE);
}

#endif
