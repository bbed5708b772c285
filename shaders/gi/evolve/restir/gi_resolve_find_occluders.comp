// gi-resolve-find-occluders: which render-resolution pixels lie beside an occluder, where
// gi-trace-resolve-visibility then tests the resolve's samples for visibility. The chain tests a
// sample's visibility only from the primary vertex that found or reused it
// (gi-trace-spatial-validation-rays), at GI resolution; the resolve hands each reservoir to the
// render-resolution pixels around it. Where geometry stands in front of a pixel's tangent plane
// within a GI pixel (besideOccluder: a gap behind a cabinet, an overhang, the inside of a
// corner), a sample visible from the neighbour's vertex may be hidden from this one: on the
// wall inside a 5 cm gap, half-resolution GI has no sample of its own and showed the light of
// the wall outside, where the reference is dark. This pass writes every pixel's
// gi.resolve-occlusion (0, or RESOLVE_BESIDE_OCCLUDER: gi-spatial-denoise does not blur it)
// after eight GBuffer reads and lists the pixels beside an occluder (GI_RAY_LIST_RESOLVE).
#version 460
#extension GL_EXT_samplerless_texture_functions : require
#include "gi/evolve/restir/restir_gi_common.glsl"
#include "gi/evolve/restir/ray_list.glsl"

layout(local_size_x = RESTIR_GI_GROUP_SIZE, local_size_y = RESTIR_GI_GROUP_SIZE) in;
layout(push_constant, scalar) uniform Push { RestirGiPassConstants pc; };

layout(set = 1, binding = GI_RESOLVE_BINDING_NORMALS) uniform texture2D normals;
layout(set = 1, binding = GI_RESOLVE_BINDING_DEPTH) uniform texture2D depths;
layout(set = 1, binding = GI_RESOLVE_BINDING_FLAGS) uniform utexture2D flags;
layout(set = 1, binding = GI_RESOLVE_VISIBILITY_BINDING_OUTPUT, r32ui) uniform writeonly uimage2D occlusionOut;

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
      float depth = texelFetch(depths, q, 0).x;
      if ((dx == 0 && dy == 0) || !(depth > 0.0)) continue;  // sky: view depth 0
      vec3 p = positionFromDepth(f, vec2(q) + 0.5, depth);
      if (dot(x.geometricNormal, p - x.position) > gi.planeTolerance * x.depth) return true;
    }
  return false;
}

void main() {
  FrameConstants f = FrameBlock(pc.frame).v;
  RestirGiConstants gi = RestirGiBlock(pc.gi).v;
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(pixel), f.resolution))) return;
  bool beside = false;
  if ((texelFetch(flags, pixel, 0).x & GBUFFER_FLAG_SURFACE) != 0u) {
    PrimaryVertex x = makePrimaryVertex(f, pixel, texelFetch(normals, pixel, 0), texelFetch(depths, pixel, 0).x);
    beside = besideOccluder(f, gi, pixel, x);
  }
  imageStore(occlusionOut, pixel, uvec4(beside ? RESOLVE_BESIDE_OCCLUDER : 0u));
  if (beside) rayListAppend(pc.rayLists, GI_RAY_LIST_RESOLVE, gi.giResolution, pixel, RESOLVE_MAX_SAMPLES);
}
