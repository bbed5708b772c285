// gi-trace-spatial-validation-rays (seed 000): the spatial passes did not test visibility, so
// a neighbour's sample may be occluded from this pixel's x1 (they would blur indirect shadows).
// One shadow ray from x1 to the final sample x2 of gi-restir-spatial-1, only where that sample
// came from a neighbour (the pixel's own temporal sample was found by a ray from x1); W = 0 when
// occluded (the pepper noise gi-restir-patch-reservoir repairs). The outcome (1 visible, 0
// occluded; own samples count as visible) is accumulated into the *spatial occlusion validity*
// mask, an exponential running mean (validityBlend) reprojected with gbuffer.velocity: low where
// spatial reuse keeps failing (contact shadows, under foliage). Next frame's gi-restir-temporal
// and this frame's gi-temporal-denoise read it. Writes the validated sample image (x2, W); the
// reservoir's other parts stay gi-restir-spatial-1's. A workgroup's pixels are handled in the
// order of their rays' directions, those without a ray last (rt/ray_bins.glsl), so that a
// subgroup traces rays of about one direction and none idles beside lanes that trace.
#version 460
#include "gi/evolve/restir/restir_gi_visibility.glsl"
#include "rt/ray_bins.glsl"

layout(local_size_x = RAY_BIN_GROUP_SIDE, local_size_y = RAY_BIN_GROUP_SIDE) in;
layout(push_constant, scalar) uniform Push { RestirGiPassConstants pc; };

layout(set = 1, binding = GI_VALIDATION_BINDING_INPUT + GI_RESERVOIR_SAMPLE, rgba32f) uniform readonly image2D inSample;
layout(set = 1, binding = GI_VALIDATION_BINDING_INPUT + GI_RESERVOIR_RADIANCE, rgba32f) uniform readonly image2D inRadiance;
layout(set = 1, binding = GI_VALIDATION_BINDING_INPUT + GI_RESERVOIR_ORIGIN, rgba32f) uniform readonly image2D inOrigin;
layout(set = 1, binding = GI_VALIDATION_BINDING_INPUT + GI_RESERVOIR_NORMALS, rgba16f) uniform readonly image2D inNormals;
layout(set = 1, binding = GI_VALIDATION_BINDING_TEMPORAL_SAMPLE, rgba32f) uniform readonly image2D temporalSample;
layout(set = 1, binding = GI_VALIDATION_BINDING_NORMALS, rgba16f) uniform readonly image2D normals;
layout(set = 1, binding = GI_VALIDATION_BINDING_DEPTH, r32f) uniform readonly image2D depths;
layout(set = 1, binding = GI_VALIDATION_BINDING_VELOCITY, rg16f) uniform readonly image2D velocities;
layout(set = 1, binding = GI_VALIDATION_BINDING_VALIDITY_PREVIOUS, r16f) uniform readonly image2D validityPrevious;
layout(set = 1, binding = GI_VALIDATION_BINDING_VALIDITY_CURRENT, r16f) uniform writeonly image2D validityCurrent;
layout(set = 1, binding = GI_VALIDATION_BINDING_SAMPLE_OUT, rgba32f) uniform writeonly image2D sampleOut;
layout(set = 1, binding = GI_VALIDATION_BINDING_ESTIMATE, rgba16f) uniform writeonly image2D estimateOut;

// Last frame's validity at this pixel's position (1 = trust spatial reuse when unknown).
float previousValidity(RestirGiConstants gi, ivec2 pixel) {
  if (pc.historyValid == 0u) return 1.0;
  vec2 previousPixel = vec2(pixel) + 0.5 - imageLoad(velocities, pixel).xy;
  ivec2 q = ivec2(floor(previousPixel / float(gi.divisor)));
  if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, ivec2(gi.giResolution)))) return 1.0;
  float v = imageLoad(validityPrevious, q).x;
  return isFiniteValue(v) ? clamp(v, 0.0, 1.0) : 1.0;
}

// Whether GI pixel g's final sample needs a shadow ray from x1: it came from a neighbour.
bool needsRay(ivec2 g, Reservoir r) {
  return r.M > 0.0 && r.W > 0.0 && any(notEqual(imageLoad(temporalSample, g).xyz, r.samplePosition));
}

Reservoir loadReservoir(ivec2 g) {
  return unpackReservoir(imageLoad(inSample, g), imageLoad(inRadiance, g), imageLoad(inOrigin, g),
                         imageLoad(inNormals, g));
}

// The GI pixel this invocation handles (rt/ray_bins.glsl): one of its group's tile, binned by
// the direction of its shadow ray (from the reservoir's x1 to its x2).
ivec2 binnedGiPixel(RestirGiConstants gi) {
  ivec2 tile = ivec2(gl_WorkGroupID.xy * RAY_BIN_GROUP_SIDE);
  ivec2 own = tile + ivec2(gl_LocalInvocationID.xy);
  bool ray = false;
  vec3 direction = vec3(0.0);
  if (all(lessThan(uvec2(own), gi.giResolution))) {
    Reservoir r = loadReservoir(own);
    ray = needsRay(own, r);
    direction = r.samplePosition - r.origin;
  }
  uint handled = binnedInvocation(ray, direction);
  return tile + ivec2(handled % RAY_BIN_GROUP_SIDE, handled / RAY_BIN_GROUP_SIDE);
}

void main() {
  FrameConstants f = FrameBlock(pc.frame).v;
  RestirGiConstants gi = RestirGiBlock(pc.gi).v;
  ivec2 g = binnedGiPixel(gi);
  if (any(greaterThanEqual(uvec2(g), gi.giResolution))) return;
  ivec2 pixel = giRepresentativePixel(f, gi, g);
  PrimaryVertex x1 = makePrimaryVertex(f, pixel, imageLoad(normals, pixel), imageLoad(depths, pixel).x);
  Reservoir r = loadReservoir(g);
  float visible = 1.0;
  if (needsRay(g, r) && !sampleVisible(x1, r)) {
    visible = 0.0;
    r.W = 0.0;
  }
  float validity = mix(previousValidity(gi, pixel), visible, gi.validityBlend);
  imageStore(validityCurrent, g, vec4(r.M > 0.0 ? validity : 1.0));
  imageStore(sampleOut, g, finiteOrZero(vec4(r.samplePosition, r.W)));
  imageStore(estimateOut, g, finiteOrZero(vec4(reservoirEstimate(x1, r), 1.0)));
}
