// gi-spatial-denoise (seed 000, desktop only): one edge-aware blur of gi-temporal-denoise's
// output at render resolution. A (2 r + 1)^2 Gaussian (r = spatialDenoiseRadius pixels,
// sigma = r / 2 + 0.5) whose taps count only where their surface is this pixel's: the plane
// distance of their position to this pixel's tangent plane (relative to view depth) and the
// shading normals' agreement use the same tolerances as reservoir reuse (sameSurface), so no
// light bleeds across geometric edges. Removes the residual boiling that temporal accumulation
// leaves at half-res GI; costs some contact detail. Pixels beside an occluder
// (gi-trace-resolve-visibility) keep their value: the plane they lie on continues behind the
// occluder, where taps may see light this pixel does not.
// Separable, as the Gaussian is: pc.variant GI_SPATIAL_DENOISE_ROWS blurs across the row
// (gi-spatial-denoise-rows), GI_SPATIAL_DENOISE_COLUMNS then down the column of those results
// (gi-spatial-denoise), 2 x 2 r taps instead of (2 r + 1)^2 - 1. The surface test of the second
// pass is against the column's taps, each already a blur of its own surface: on a plane that is
// the 2-D filter; at an edge a tap of the row may differ (the cross-bilateral approximation of
// Pham and van Vliet 2005). Measured against the 2-D filter in docs/benchmarks.md.
#version 460
#include "gi/evolve/restir/restir_gi_common.glsl"

layout(local_size_x = RESTIR_GI_GROUP_SIZE, local_size_y = RESTIR_GI_GROUP_SIZE) in;
layout(push_constant, scalar) uniform Push { RestirGiPassConstants pc; };

layout(set = 1, binding = GI_SPATIAL_DENOISE_BINDING_INPUT, rgba16f) uniform readonly image2D inputImage;
layout(set = 1, binding = GI_SPATIAL_DENOISE_BINDING_NORMALS, rgba16f) uniform readonly image2D normals;
layout(set = 1, binding = GI_SPATIAL_DENOISE_BINDING_DEPTH, r32f) uniform readonly image2D depths;
layout(set = 1, binding = GI_SPATIAL_DENOISE_BINDING_FLAGS, r32ui) uniform readonly uimage2D flags;
layout(set = 1, binding = GI_SPATIAL_DENOISE_BINDING_OUTPUT, rgba16f) uniform writeonly image2D outputImage;
layout(set = 1, binding = GI_SPATIAL_DENOISE_BINDING_OCCLUSION, r32ui) uniform readonly uimage2D resolveOcclusion;

void main() {
  FrameConstants f = FrameBlock(pc.frame).v;
  RestirGiConstants gi = RestirGiBlock(pc.gi).v;
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(pixel), f.resolution))) return;
  vec4 centre = imageLoad(inputImage, pixel);
  bool occlusionKnown = (gi.flags & RESTIR_GI_FLAG_OCCLUDER_VISIBILITY) != 0u;
  if ((imageLoad(flags, pixel).x & GBUFFER_FLAG_SURFACE) == 0u ||
      (occlusionKnown && (imageLoad(resolveOcclusion, pixel).x & RESOLVE_BESIDE_OCCLUDER) != 0u)) {
    imageStore(outputImage, pixel, centre);
    return;
  }
  PrimaryVertex x = makePrimaryVertex(f, pixel, imageLoad(normals, pixel), imageLoad(depths, pixel).x);
  int radius = int(gi.spatialDenoiseRadius);
  float sigma = 0.5 * float(radius) + 0.5;
  ivec2 axis = pc.variant == GI_SPATIAL_DENOISE_ROWS ? ivec2(1, 0) : ivec2(0, 1);
  vec3 sum = centre.rgb;
  float weightSum = 1.0;
  for (int d = -radius; d <= radius; ++d) {
    ivec2 q = pixel + d * axis;
    if (d == 0 || any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, ivec2(f.resolution)))) continue;
    float depth = imageLoad(depths, q).x;
    if (!(depth > 0.0)) continue;  // sky (view depth 0), as GBUFFER_FLAG_SURFACE says
    vec3 position = positionFromDepth(f, vec2(q) + 0.5, depth);
    vec3 shadingNormal = decodeOctahedral(imageLoad(normals, q).xy);
    if (!sameSurface(gi, x, position, shadingNormal)) continue;
    float w = exp(-float(d * d) / (2.0 * sigma * sigma));
    sum += w * imageLoad(inputImage, q).rgb;
    weightSum += w;
  }
  imageStore(outputImage, pixel, finiteOrZero(vec4(sum / weightSum, 1.0)));
}
