// gi-trace-resolve-visibility: shadow rays for gi-restir-resolve at the pixels
// gi-resolve-find-occluders listed as beside an occluder (GI_RAY_LIST_RESOLVE), one thread per
// pixel: a ray to each sample the resolve will read there (resolve_samples.glsl picks the same
// ones), the hidden ones marked in gi.resolve-occlusion, which the resolve then counts with
// zero. A pass of its own because traversal code in the resolve slowed that pass everywhere
// (registers), even where it never ran; walking a list because one thread per pixel left most
// lanes idle while a few traced (shared/restir_gi_io.h, "Ray lists").
#version 460
#include "gi/evolve/restir/restir_gi_visibility.glsl"
#include "gi/evolve/restir/ray_list.glsl"

layout(local_size_x = GI_RAY_LIST_GROUP_SIZE) in;
layout(push_constant, scalar) uniform Push { RestirGiPassConstants pc; };

layout(set = 1, binding = GI_RESOLVE_BINDING_RESERVOIR + GI_RESERVOIR_SAMPLE, rgba32f) uniform readonly image2D reservoirSample;
layout(set = 1, binding = GI_RESOLVE_BINDING_RESERVOIR + GI_RESERVOIR_RADIANCE, rgba32f) uniform readonly image2D reservoirRadiance;
layout(set = 1, binding = GI_RESOLVE_BINDING_RESERVOIR + GI_RESERVOIR_ORIGIN, rgba32f) uniform readonly image2D reservoirOrigin;
layout(set = 1, binding = GI_RESOLVE_BINDING_RESERVOIR + GI_RESERVOIR_NORMALS, rgba16f) uniform readonly image2D reservoirNormals;
layout(set = 1, binding = GI_RESOLVE_BINDING_NORMALS, rgba16f) uniform readonly image2D normals;
layout(set = 1, binding = GI_RESOLVE_BINDING_DEPTH, r32f) uniform readonly image2D depths;
layout(set = 1, binding = GI_RESOLVE_VISIBILITY_BINDING_OUTPUT, r32ui) uniform writeonly uimage2D occlusionOut;
#include "gi/evolve/restir/resolve_samples.glsl"

// The resolve's samples hidden from `pixel` (bit i: its i-th sample).
uint hiddenSamples(FrameConstants f, RestirGiConstants gi, ivec2 pixel) {
  PrimaryVertex x = makePrimaryVertex(f, pixel, imageLoad(normals, pixel), imageLoad(depths, pixel).x);
  ivec2 home = homeGiPixel(f, gi, pixel, x);
  uint samples = resolveSampleCount(gi);
  float rotation = resolveRotation(f, pixel);
  uint hidden = 0u;
  for (uint i = 0u; i < samples; ++i) {
    ivec2 q = resolveSampleGiPixel(gi, home, i, samples, rotation);
    Reservoir r = unpackReservoir(imageLoad(reservoirSample, q), imageLoad(reservoirRadiance, q),
                                  imageLoad(reservoirOrigin, q), imageLoad(reservoirNormals, q));
    // Only samples the resolve would use: on this surface, with weight, in x's hemisphere.
    vec3 direction;
    if (r.M <= 0.0 || !(r.W > 0.0) || !sameSurface(gi, x, r.origin, r.originNormal) ||
        sampleCosine(x, r.samplePosition, direction) <= 0.0)
      continue;
    if (!sampleVisible(x, r)) hidden |= 1u << i;
  }
  return hidden;
}

void main() {
  FrameConstants f = FrameBlock(pc.frame).v;
  RestirGiConstants gi = RestirGiBlock(pc.gi).v;
  uint count = rayListCount(pc.rayLists, GI_RAY_LIST_RESOLVE);
  for (uint i = gl_GlobalInvocationID.x; i < count; i += RAY_LIST_STRIDE) {
    ivec2 pixel = rayListPixel(pc.rayLists, GI_RAY_LIST_RESOLVE, gi.giResolution, i);
    imageStore(occlusionOut, pixel, uvec4(RESOLVE_BESIDE_OCCLUDER | hiddenSamples(f, gi, pixel)));
  }
}
