// gi-spatial-denoise (seed 000, desktop only): one edge-aware blur of gi-temporal-denoise's
// output at render resolution. A (2 r + 1)^2 box (r = spatialDenoiseRadius pixels) whose taps
// count only where their surface is this pixel's: the plane distance of their position to this
// pixel's tangent plane (relative to view depth) and the shading normals' agreement use the
// same tolerances as reservoir reuse (sameSurface), so no light bleeds across geometric edges;
// weights fall off with distance (Gaussian, sigma = r / 2 + 0.5). Removes the residual
// boiling that temporal accumulation leaves at half-res GI; costs some contact detail. Pixels
// beside an occluder (gi-trace-resolve-visibility) keep their value: the plane they lie on
// continues behind the occluder, where taps may see light this pixel does not.
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
  vec3 sum = centre.rgb;
  float weightSum = 1.0;
  for (int dy = -radius; dy <= radius; ++dy)
    for (int dx = -radius; dx <= radius; ++dx) {
      ivec2 q = pixel + ivec2(dx, dy);
      if ((dx == 0 && dy == 0) || any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, ivec2(f.resolution))))
        continue;
      if ((imageLoad(flags, q).x & GBUFFER_FLAG_SURFACE) == 0u) continue;
      PrimaryVertex y = makePrimaryVertex(f, q, imageLoad(normals, q), imageLoad(depths, q).x);
      if (!sameSurface(gi, x, y.position, y.shadingNormal)) continue;
      float w = exp(-float(dx * dx + dy * dy) / (2.0 * sigma * sigma));
      sum += w * imageLoad(inputImage, q).rgb;
      weightSum += w;
    }
  imageStore(outputImage, pixel, finiteOrZero(vec4(sum / weightSum, 1.0)));
}
