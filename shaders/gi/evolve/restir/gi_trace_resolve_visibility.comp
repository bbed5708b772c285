// gi-trace-resolve-visibility: shadow rays for gi-restir-resolve at pixels beside an occluder.
// The chain tests a sample's visibility only from the primary vertex that found or reused it
// (gi-trace-spatial-validation-rays), at GI resolution; the resolve hands each reservoir to the
// render-resolution pixels around it. Where geometry stands in front of a pixel's tangent plane
// within a GI pixel (besideOccluder: a gap behind a cabinet, an overhang, the inside of a
// corner), a sample visible from the neighbour's vertex may be hidden from this one: on the
// wall inside a 5 cm gap, half-resolution GI has no sample of its own and showed the light of
// the wall outside, where the reference is dark. There this pass traces a ray to each
// sample the resolve will read (resolve_samples.glsl picks the same ones) and marks the hidden
// ones, which the resolve then counts with zero; gi-spatial-denoise does not blur the pixel.
// Elsewhere it writes 0 after eight GBuffer reads. A pass of its own because traversal code in
// the resolve slowed that pass everywhere (registers), even where it never ran.
#version 460
#include "gi/evolve/restir/restir_gi_visibility.glsl"

layout(local_size_x = RESTIR_GI_GROUP_SIZE, local_size_y = RESTIR_GI_GROUP_SIZE) in;
layout(push_constant, scalar) uniform Push { RestirGiPassConstants pc; };

layout(set = 1, binding = GI_RESOLVE_BINDING_RESERVOIR + GI_RESERVOIR_SAMPLE, rgba32f) uniform readonly image2D reservoirSample;
layout(set = 1, binding = GI_RESOLVE_BINDING_RESERVOIR + GI_RESERVOIR_RADIANCE, rgba32f) uniform readonly image2D reservoirRadiance;
layout(set = 1, binding = GI_RESOLVE_BINDING_RESERVOIR + GI_RESERVOIR_ORIGIN, rgba32f) uniform readonly image2D reservoirOrigin;
layout(set = 1, binding = GI_RESOLVE_BINDING_RESERVOIR + GI_RESERVOIR_NORMALS, rgba16f) uniform readonly image2D reservoirNormals;
layout(set = 1, binding = GI_RESOLVE_BINDING_NORMALS, rgba16f) uniform readonly image2D normals;
layout(set = 1, binding = GI_RESOLVE_BINDING_DEPTH, r32f) uniform readonly image2D depths;
layout(set = 1, binding = GI_RESOLVE_BINDING_FLAGS, r32ui) uniform readonly uimage2D flags;
layout(set = 1, binding = GI_RESOLVE_VISIBILITY_BINDING_OUTPUT, r32ui) uniform writeonly uimage2D occlusionOut;
#include "gi/evolve/restir/resolve_samples.glsl"

// Whether a GBuffer point one GI pixel away (8 directions) lies in front of x's tangent plane by
// more than the same-surface tolerance: then something may hide from x what its GI pixel's
// neighbours see (x is behind it: a gap, an overhang, the inside of a corner). In corners the
// test has a price: it zeroes the neighbours' samples x cannot see but never adds those only
// x can see, so corners get a little darker (the error against the reference still falls).
// Keeping only occluders parallel to x's plane spared the corners but missed the
// gap too: looking into a gap one sees the side of the object in front, across the plane.
bool besideOccluder(FrameConstants f, RestirGiConstants gi, ivec2 pixel, PrimaryVertex x) {
  if ((gi.flags & RESTIR_GI_FLAG_OCCLUDER_VISIBILITY) == 0u) return false;
  int step = int(gi.divisor);
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      ivec2 q = clamp(pixel + ivec2(dx, dy) * step, ivec2(0), ivec2(f.resolution) - 1);
      if ((dx == 0 && dy == 0) || (imageLoad(flags, q).x & GBUFFER_FLAG_SURFACE) == 0u) continue;
      vec3 p = positionFromDepth(f, vec2(q) + 0.5, imageLoad(depths, q).x);
      if (dot(x.geometricNormal, p - x.position) > gi.planeTolerance * x.depth) return true;
    }
  return false;
}

void main() {
  FrameConstants f = FrameBlock(pc.frame).v;
  RestirGiConstants gi = RestirGiBlock(pc.gi).v;
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(pixel), f.resolution))) return;
  if ((imageLoad(flags, pixel).x & GBUFFER_FLAG_SURFACE) == 0u) {
    imageStore(occlusionOut, pixel, uvec4(0u));
    return;
  }
  PrimaryVertex x = makePrimaryVertex(f, pixel, imageLoad(normals, pixel), imageLoad(depths, pixel).x);
  if (!besideOccluder(f, gi, pixel, x)) {
    imageStore(occlusionOut, pixel, uvec4(0u));
    return;
  }
  uint occlusion = RESOLVE_BESIDE_OCCLUDER;
  ivec2 home = homeGiPixel(f, gi, pixel, x);
  uint samples = resolveSampleCount(gi);
  float rotation = resolveRotation(f, pixel);
  for (uint i = 0u; i < samples; ++i) {
    ivec2 q = resolveSampleGiPixel(gi, home, i, samples, rotation);
    Reservoir r = unpackReservoir(imageLoad(reservoirSample, q), imageLoad(reservoirRadiance, q),
                                  imageLoad(reservoirOrigin, q), imageLoad(reservoirNormals, q));
    // Only samples the resolve would use: on this surface, with weight, in x's hemisphere.
    vec3 direction;
    if (r.M <= 0.0 || !(r.W > 0.0) || !sameSurface(gi, x, r.origin, r.originNormal) ||
        sampleCosine(x, r.samplePosition, direction) <= 0.0)
      continue;
    if (!sampleVisible(x, r)) occlusion |= 1u << i;
  }
  imageStore(occlusionOut, pixel, uvec4(occlusion));
}
