// gi10-interpolate-screen-probes (§1.2 #21, §1.3 "upsample"): irradiance / pi per pixel from the
// SH of the four probe tiles around it, each weighted by ((1 - |dz| / z) max(n . n_p, 0))^8
// (dz: the view depths' difference) and the bilinear weight of its tile centre, and not at all
// when the probe lies farther than one 8-pixel footprint from the pixel's plane. If no probe
// fits, the valid ones count equally and alpha (the denoiser's hint) is 0.
#version 460
#include "gi/gi10/gi10_common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(push_constant, scalar) uniform Push { Gi10PassConstants pc; };
layout(set = 1, binding = GI10_INTERPOLATE_BINDING_NORMALS, rgba16f) uniform readonly image2D normals;
layout(set = 1, binding = GI10_INTERPOLATE_BINDING_DEPTH, r32f) uniform readonly image2D depths;
layout(set = 1, binding = GI10_INTERPOLATE_BINDING_OUTPUT, rgba16f) uniform writeonly image2D outputImage;

void main() {
  FrameConstants f = FrameBlock(pc.frame).v;
  Gi10Constants k = Gi10ConstantsRef(pc.gi10).v;
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(pixel), f.resolution))) return;
  float depth = imageLoad(depths, pixel).x;
  if (!(depth > 0.0)) {
    imageStore(outputImage, pixel, vec4(0.0));
    return;
  }
  vec4 packedNormals = imageLoad(normals, pixel);
  vec3 n = decodeOctahedral(packedNormals.zw);
  vec3 shading = decodeOctahedral(packedNormals.xy);
  vec3 x = positionFromDepth(f, vec2(pixel) + 0.5, depth);
  float cell = gi10Footprint(k, depth, float(GI10_PROBE_SIZE));
  vec2 t = (vec2(pixel) + 0.5) / float(GI10_PROBE_SIZE) - 0.5;
  ivec2 base = ivec2(floor(t));
  vec2 fraction = t - vec2(base);
  Gi10ProbesRef probes = Gi10ProbesRef(k.probes);
  Gi10ShRef sh = Gi10ShRef(k.sh);
  vec3 weighted = vec3(0.0), fallback = vec3(0.0);
  float weightSum = 0.0, fallbackCount = 0.0;
  for (uint i = 0u; i < 4u; ++i) {
    ivec2 offset = ivec2(i & 1u, i >> 1u);
    ivec2 tile = clamp(base + offset, ivec2(0), ivec2(k.probeGrid) - 1);
    uint tileIndex = uint(tile.y) * k.probeGrid.x + uint(tile.x);
    Gi10Probe p = probes.v[tileIndex];
    if ((p.flags & GI10_PROBE_VALID) == 0u) continue;
    vec3 e = gi10ShIrradianceOverPi(sh, tileIndex, shading);
    fallback += e;
    fallbackCount += 1.0;
    if (abs(dot(p.position - x, n)) > cell) continue;
    float w = max(1.0 - abs(p.depth - depth) / depth, 0.0) * max(dot(n, p.normal), 0.0);
    w *= w;
    w *= w;
    w *= w;
    vec2 bilinear = mix(1.0 - fraction, fraction, vec2(offset));
    w *= bilinear.x * bilinear.y;
    weighted += w * e;
    weightSum += w;
  }
  vec4 result = vec4(0.0);
  if (weightSum > 1e-6) result = vec4(weighted / weightSum, 1.0);
  else if (fallbackCount > 0.0) result = vec4(fallback / fallbackCount, 0.0);
  imageStore(outputImage, pixel, result);
}
