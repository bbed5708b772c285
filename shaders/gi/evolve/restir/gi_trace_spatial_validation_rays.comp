// gi-trace-spatial-validation-rays (seed 000): the spatial passes did not test visibility, so
// a neighbour's sample may be occluded from this pixel's x1 (they would blur indirect shadows).
// One shadow ray from x1 to the final sample x2 of gi-restir-spatial-1, only where that sample
// came from a neighbour (the pixel's own temporal sample was found by a ray from x1); W = 0 when
// occluded (the pepper noise gi-restir-patch-reservoir repairs). The outcome (1 visible, 0
// occluded; own samples count as visible) is accumulated into the *spatial occlusion validity*
// mask, an exponential running mean (validityBlend) reprojected with gbuffer.velocity: low where
// spatial reuse keeps failing (contact shadows, under foliage). Next frame's gi-restir-temporal
// and this frame's gi-temporal-denoise read it. Writes the validated sample image (x2, W); the
// reservoir's other parts stay gi-restir-spatial-1's.
#version 460
#include "gi/evolve/restir/restir_gi_visibility.glsl"

layout(local_size_x = RESTIR_GI_GROUP_SIZE, local_size_y = RESTIR_GI_GROUP_SIZE) in;
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

void main() {
  FrameConstants f = FrameBlock(pc.frame).v;
  RestirGiConstants gi = RestirGiBlock(pc.gi).v;
  ivec2 g = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(g), gi.giResolution))) return;
  ivec2 pixel = giRepresentativePixel(f, gi, g);
  PrimaryVertex x1 = makePrimaryVertex(f, pixel, imageLoad(normals, pixel), imageLoad(depths, pixel).x);
  Reservoir r = unpackReservoir(imageLoad(inSample, g), imageLoad(inRadiance, g),
                                imageLoad(inOrigin, g), imageLoad(inNormals, g));
  float visible = 1.0;
  bool reused = any(notEqual(imageLoad(temporalSample, g).xyz, r.samplePosition));
  if (r.M > 0.0 && r.W > 0.0 && reused && !sampleVisible(x1, r)) {
    visible = 0.0;
    r.W = 0.0;
  }
  float validity = mix(previousValidity(gi, pixel), visible, gi.validityBlend);
  imageStore(validityCurrent, g, vec4(r.M > 0.0 ? validity : 1.0));
  imageStore(sampleOut, g, finiteOrZero(vec4(r.samplePosition, r.W)));
  imageStore(estimateOut, g, finiteOrZero(vec4(reservoirEstimate(x1, r), 1.0)));
}
