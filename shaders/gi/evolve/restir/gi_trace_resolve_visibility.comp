// gi-trace-resolve-visibility: shadow rays for gi-restir-resolve at the pixels
// gi-resolve-find-occluders listed as beside an occluder (GI_RAY_LIST_RESOLVE): a ray to each
// sample the resolve will read there (resolve_samples.glsl picks the same ones), the hidden ones
// marked in gi.resolve-occlusion (an atomic OR over the RESOLVE_BESIDE_OCCLUDER the list's pass
// wrote), which the resolve then counts with zero. A pass of its own because traversal code in the resolve slowed that pass everywhere
// (registers), even where it never ran; walking a list because one thread per pixel left most
// lanes idle while a few traced (shared/restir_gi_io.h, "Ray lists").
#version 460
#extension GL_EXT_samplerless_texture_functions : require
#include "gi/evolve/restir/restir_gi_visibility.glsl"
#include "gi/evolve/restir/ray_list.glsl"

layout(local_size_x = GI_RAY_LIST_GROUP_SIZE) in;
layout(push_constant, scalar) uniform Push { RestirGiPassConstants pc; };

layout(set = 1, binding = GI_RESOLVE_BINDING_RESERVOIR + GI_RESERVOIR_SAMPLE) uniform texture2D reservoirSample;
layout(set = 1, binding = GI_RESOLVE_BINDING_RESERVOIR + GI_RESERVOIR_RADIANCE) uniform texture2D reservoirRadiance;
layout(set = 1, binding = GI_RESOLVE_BINDING_RESERVOIR + GI_RESERVOIR_ORIGIN) uniform texture2D reservoirOrigin;
layout(set = 1, binding = GI_RESOLVE_BINDING_RESERVOIR + GI_RESERVOIR_NORMALS) uniform texture2D reservoirNormals;
layout(set = 1, binding = GI_RESOLVE_BINDING_NORMALS) uniform texture2D normals;
layout(set = 1, binding = GI_RESOLVE_BINDING_DEPTH) uniform texture2D depths;
layout(set = 1, binding = GI_RESOLVE_VISIBILITY_BINDING_OUTPUT, r32ui) uniform uimage2D occlusion;
#include "gi/evolve/restir/resolve_samples.glsl"

// Whether the resolve's `i`-th sample of `pixel` is hidden from it. Only samples the resolve
// would use are tested: on this surface, with weight, in x's hemisphere.
bool sampleHidden(FrameConstants f, RestirGiConstants gi, ivec2 pixel, uint i) {
  uint samples = resolveSampleCount(gi);
  if (i >= samples) return false;
  PrimaryVertex x = makePrimaryVertex(f, pixel, texelFetch(normals, pixel, 0), texelFetch(depths, pixel, 0).x);
  ivec2 q = resolveSampleGiPixel(gi, homeGiPixel(f, gi, pixel, x), i, samples, resolveRotation(f, pixel));
  Reservoir r = unpackReservoir(texelFetch(reservoirSample, q, 0), texelFetch(reservoirRadiance, q, 0),
                                texelFetch(reservoirOrigin, q, 0), texelFetch(reservoirNormals, q, 0));
  vec3 direction;
  if (r.M <= 0.0 || !(r.W > 0.0) || !sameSurface(gi, x, r.origin, r.originNormal) ||
      sampleCosine(x, r.samplePosition, direction) <= 0.0)
    return false;
  return !sampleVisible(x, r);
}

// RESOLVE_MAX_SAMPLES threads per listed pixel, one sample and at most one ray each, so that a
// pixel's rays run side by side rather than one after the other.
void main() {
  FrameConstants f = FrameBlock(pc.frame).v;
  RestirGiConstants gi = RestirGiBlock(pc.gi).v;
  uint items = rayListCount(pc.rayLists, GI_RAY_LIST_RESOLVE) * RESOLVE_MAX_SAMPLES;
  for (uint t = gl_GlobalInvocationID.x; t < items; t += RAY_LIST_STRIDE) {
    ivec2 pixel = rayListPixel(pc.rayLists, GI_RAY_LIST_RESOLVE, gi.giResolution, t / RESOLVE_MAX_SAMPLES);
    uint i = t % RESOLVE_MAX_SAMPLES;
    if (sampleHidden(f, gi, pixel, i)) imageAtomicOr(occlusion, pixel, 1u << i);
  }
}
