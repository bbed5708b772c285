// gi-restir-patch-reservoir (seed 000): a cheap fix for the reservoirs that
// gi-trace-spatial-validation-rays rejected (W = 0 where x1 has a surface): the first reservoir
// of the pixel's 2x2 patch (GI pixels) whose primary vertex lies on the same surface (depth and
// normal, sameSurface) and whose W is positive, shifted to this x1 with the reconnection
// Jacobian (Ouyang et al. 2021, Eq. 11): W' = W J (zero when x2 does not face x1 or J exceeds
// maxJacobian). Biased, not fed back. Shares gi-restir-spatial's bindings: the input is the
// validated sample with gi-restir-spatial-1's other parts.
#version 460
#extension GL_EXT_samplerless_texture_functions : require
#include "gi/evolve/restir/restir_gi_common.glsl"

layout(local_size_x = RESTIR_GI_GROUP_SIZE, local_size_y = RESTIR_GI_GROUP_SIZE) in;
layout(push_constant, scalar) uniform Push { RestirGiPassConstants pc; };

layout(set = 1, binding = GI_SPATIAL_BINDING_INPUT + GI_RESERVOIR_SAMPLE) uniform texture2D inSample;
layout(set = 1, binding = GI_SPATIAL_BINDING_INPUT + GI_RESERVOIR_RADIANCE) uniform texture2D inRadiance;
layout(set = 1, binding = GI_SPATIAL_BINDING_INPUT + GI_RESERVOIR_ORIGIN) uniform texture2D inOrigin;
layout(set = 1, binding = GI_SPATIAL_BINDING_INPUT + GI_RESERVOIR_NORMALS) uniform texture2D inNormals;
layout(set = 1, binding = GI_SPATIAL_BINDING_OUTPUT + GI_RESERVOIR_SAMPLE, rgba32f) uniform writeonly image2D outSample;
layout(set = 1, binding = GI_SPATIAL_BINDING_OUTPUT + GI_RESERVOIR_RADIANCE, rgba32f) uniform writeonly image2D outRadiance;
layout(set = 1, binding = GI_SPATIAL_BINDING_OUTPUT + GI_RESERVOIR_ORIGIN, rgba32f) uniform writeonly image2D outOrigin;
layout(set = 1, binding = GI_SPATIAL_BINDING_OUTPUT + GI_RESERVOIR_NORMALS, rgba16f) uniform writeonly image2D outNormals;
layout(set = 1, binding = GI_SPATIAL_BINDING_NORMALS) uniform texture2D normals;
layout(set = 1, binding = GI_SPATIAL_BINDING_DEPTH) uniform texture2D depths;
layout(set = 1, binding = GI_SPATIAL_BINDING_ESTIMATE, rgba16f) uniform writeonly image2D estimateOut;

Reservoir loadReservoir(ivec2 q) {
  return unpackReservoir(texelFetch(inSample, q, 0), texelFetch(inRadiance, q, 0), texelFetch(inOrigin, q, 0),
                         texelFetch(inNormals, q, 0));
}

// The first valid reservoir of g's 2x2 patch, shifted to x1; `r` unchanged when none is.
Reservoir patchedReservoir(RestirGiConstants gi, ivec2 g, PrimaryVertex x1, Reservoir r) {
  ivec2 base = g & ~1;
  for (int i = 0; i < 4; ++i) {
    ivec2 q = base + ivec2(i & 1, i >> 1);
    if (q == g || any(greaterThanEqual(q, ivec2(gi.giResolution)))) continue;
    Reservoir n = loadReservoir(q);
    if (n.M <= 0.0 || !(n.W > 0.0) || !sameSurface(gi, x1, n.origin, n.originNormal)) continue;
    float jacobian = reconnectionJacobian(n.origin, x1.position, n);
    if (!(jacobian > 0.0) || jacobian > gi.maxJacobian) continue;
    n.W *= jacobian;
    n.origin = x1.position;
    n.originNormal = x1.shadingNormal;
    return n;
  }
  return r;
}

void main() {
  FrameConstants f = FrameBlock(pc.frame).v;
  RestirGiConstants gi = RestirGiBlock(pc.gi).v;
  ivec2 g = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(g), gi.giResolution))) return;
  ivec2 pixel = giRepresentativePixel(f, gi, g);
  PrimaryVertex x1 = makePrimaryVertex(f, pixel, texelFetch(normals, pixel, 0), texelFetch(depths, pixel, 0).x);
  Reservoir r = loadReservoir(g);
  if (r.M > 0.0 && !(r.W > 0.0)) r = patchedReservoir(gi, g, x1, r);
  vec4 a, b, c, d;
  packReservoir(r, a, b, c, d);
  imageStore(outSample, g, finiteOrZero(a));
  imageStore(outRadiance, g, finiteOrZero(b));
  imageStore(outOrigin, g, finiteOrZero(c));
  imageStore(outNormals, g, d);
  imageStore(estimateOut, g, finiteOrZero(vec4(reservoirEstimate(x1, r), 1.0)));
}
