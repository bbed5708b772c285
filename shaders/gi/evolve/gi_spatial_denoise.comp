// gi-spatial-denoise (seed 000, desktop only): one edge-aware blur of gi-temporal-denoise's
// output at render resolution. A (2 r + 1)^2 box (r = spatialDenoiseRadius pixels) whose taps
// count only where their surface is this pixel's: the plane distance of their position to this
// pixel's tangent plane (relative to view depth) and the shading normals' agreement use the
// same tolerances as reservoir reuse (sameSurface), so no light bleeds across geometric edges;
// weights fall off with distance (Gaussian, sigma = r / 2 + 0.5). Removes the residual
// boiling that temporal accumulation leaves at half-res GI; costs some contact detail. Pixels
// beside an occluder (beside_occluder.glsl) are not blurred.
// Every tap needs its neighbour's position, normal and value; a group first stages its tile
// and a border of the largest radius in shared memory (4 loads per thread instead of up to 81
// taps x 3 loads from the images).
#version 460
#include "gi/evolve/restir_gi_common.glsl"

layout(local_size_x = RESTIR_GI_GROUP_SIZE, local_size_y = RESTIR_GI_GROUP_SIZE) in;
layout(push_constant, scalar) uniform Push { RestirGiPassConstants pc; };

layout(set = 1, binding = GI_SPATIAL_DENOISE_BINDING_INPUT, rgba16f) uniform readonly image2D inputImage;
layout(set = 1, binding = GI_SPATIAL_DENOISE_BINDING_NORMALS, rgba16f) uniform readonly image2D normals;
layout(set = 1, binding = GI_SPATIAL_DENOISE_BINDING_DEPTH, r32f) uniform readonly image2D depths;
layout(set = 1, binding = GI_SPATIAL_DENOISE_BINDING_FLAGS, r32ui) uniform readonly uimage2D flags;
layout(set = 1, binding = GI_SPATIAL_DENOISE_BINDING_OUTPUT, rgba16f) uniform writeonly image2D outputImage;
#include "gi/evolve/beside_occluder.glsl"

// The tile: the group's pixels and a border of GI_SPATIAL_DENOISE_MAX_RADIUS on every side.
const int TILE_BORDER = int(GI_SPATIAL_DENOISE_MAX_RADIUS);
const int TILE_SIDE = int(RESTIR_GI_GROUP_SIZE) + 2 * TILE_BORDER;
shared vec4 tilePosition[TILE_SIDE * TILE_SIDE];  // xyz, w = 1 on a surface (0: sky, off screen)
shared vec3 tileNormal[TILE_SIDE * TILE_SIDE];    // shading normal
shared vec3 tileValue[TILE_SIDE * TILE_SIDE];

void stageTile(FrameConstants f, ivec2 tileOrigin) {
  const int threads = int(RESTIR_GI_GROUP_SIZE * RESTIR_GI_GROUP_SIZE);
  for (int i = int(gl_LocalInvocationIndex); i < TILE_SIDE * TILE_SIDE; i += threads) {
    ivec2 q = tileOrigin + ivec2(i % TILE_SIDE, i / TILE_SIDE);
    bool inside = all(greaterThanEqual(q, ivec2(0))) && all(lessThan(q, ivec2(f.resolution)));
    if (!inside || (imageLoad(flags, q).x & GBUFFER_FLAG_SURFACE) == 0u) {
      tilePosition[i] = vec4(0.0);
      continue;
    }
    vec4 n = imageLoad(normals, q);
    tilePosition[i] = vec4(positionFromDepth(f, vec2(q) + 0.5, imageLoad(depths, q).x), 1.0);
    tileNormal[i] = decodeOctahedral(n.xy);
    tileValue[i] = imageLoad(inputImage, q).rgb;
  }
}

void main() {
  FrameConstants f = FrameBlock(pc.frame).v;
  RestirGiConstants gi = RestirGiBlock(pc.gi).v;
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  ivec2 tileOrigin = ivec2(gl_WorkGroupID.xy) * int(RESTIR_GI_GROUP_SIZE) - TILE_BORDER;
  stageTile(f, tileOrigin);
  barrier();
  if (any(greaterThanEqual(uvec2(pixel), f.resolution))) return;
  vec4 centre = imageLoad(inputImage, pixel);
  if ((imageLoad(flags, pixel).x & GBUFFER_FLAG_SURFACE) == 0u) {
    imageStore(outputImage, pixel, centre);
    return;
  }
  PrimaryVertex x = makePrimaryVertex(f, pixel, imageLoad(normals, pixel), imageLoad(depths, pixel).x);
  // Beside an occluder the same plane continues behind it: taps there may see light this pixel
  // does not (gi-restir-resolve tested its samples' visibility), so it keeps its own value.
  int radius = besideOccluder(f, gi, pixel, x) ? 0 : int(gi.spatialDenoiseRadius);
  float sigma = 0.5 * float(radius) + 0.5;
  vec3 sum = centre.rgb;
  float weightSum = 1.0;
  ivec2 local = pixel - tileOrigin;
  for (int dy = -radius; dy <= radius; ++dy)
    for (int dx = -radius; dx <= radius; ++dx) {
      int t = (local.y + dy) * TILE_SIDE + local.x + dx;
      if ((dx == 0 && dy == 0) || tilePosition[t].w == 0.0) continue;
      if (!sameSurface(gi, x, tilePosition[t].xyz, tileNormal[t])) continue;
      float w = exp(-float(dx * dx + dy * dy) / (2.0 * sigma * sigma));
      sum += w * tileValue[t];
      weightSum += w;
    }
  imageStore(outputImage, pixel, finiteOrZero(vec4(sum / weightSum, 1.0)));
}
