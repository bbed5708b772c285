// reflections-resolve: the reused reservoir of each traced pixel as the demodulated reflection
// signal, in reflections.traced's format and meaning (shared/specular_io.h), so that the passes
// after it (denoise, upsample, composite) need no change (shared/reflections_reuse_io.h):
//   L(x2 -> x1) D Vis (n.l) W / (scale + bias)
// which for a fresh sample (W = 1 / pdf) is the trace's L G2/G1(v) / (scale + bias); its
// expectation is the same lobe-weighted mean of incident radiance (unbiased up to the reuse's
// approximate visibility). w: the chosen sample's hit distance (REFLECTION_MISS_DISTANCE for
// the sky). Pixels without reuse (mirrors, roughness below reuseMinRoughness, no sample) get the
// traced signal unchanged, bit for bit.
#version 460
#include "passes/reflections_reuse.glsl"

layout(local_size_x = HYBRID_GROUP_SIZE, local_size_y = HYBRID_GROUP_SIZE) in;
layout(push_constant, scalar) uniform Push { ReflectionReuseConstants pc; };

layout(set = 1, binding = REFLECTIONS_RESOLVE_BINDING_RESERVOIR + GI_RESERVOIR_SAMPLE, rgba32f) uniform readonly image2D reservoirSample;
layout(set = 1, binding = REFLECTIONS_RESOLVE_BINDING_RESERVOIR + GI_RESERVOIR_RADIANCE, rgba32f) uniform readonly image2D reservoirRadiance;
layout(set = 1, binding = REFLECTIONS_RESOLVE_BINDING_RESERVOIR + GI_RESERVOIR_ORIGIN, rgba32f) uniform readonly image2D reservoirOrigin;
layout(set = 1, binding = REFLECTIONS_RESOLVE_BINDING_RESERVOIR + GI_RESERVOIR_NORMALS, rgba16f) uniform readonly image2D reservoirNormals;
layout(set = 1, binding = REFLECTIONS_RESOLVE_BINDING_NORMALS, rgba16f) uniform readonly image2D normals;
layout(set = 1, binding = REFLECTIONS_RESOLVE_BINDING_DEPTH, r32f) uniform readonly image2D depths;
layout(set = 1, binding = REFLECTIONS_RESOLVE_BINDING_EMISSIVE, rgba16f) uniform readonly image2D emissives;
layout(set = 1, binding = REFLECTIONS_RESOLVE_BINDING_TRACED, rgba16f) uniform readonly image2D traced;
layout(set = 1, binding = REFLECTIONS_RESOLVE_BINDING_RESOLVED, rgba16f) uniform writeonly image2D resolved;

vec4 resolvedSignal(FrameConstants f, ivec2 pixel, Reservoir r, vec4 tracedValue) {
  float roughness = imageLoad(emissives, pixel).w;
  ReflectionReceiver p = makeReflectionReceiver(f, pixel, imageLoad(normals, pixel), imageLoad(depths, pixel).x, roughness);
  SpecularAlbedo albedo = specularAlbedo(pc.specularAlbedo, max(p.nDotV, 0.0), p.alpha);
  float meanWeight = albedo.scale + albedo.bias;
  if (r.kind == RESTIR_GI_KIND_NONE || !(r.W > 0.0) || !(meanWeight > 0.0)) return vec4(0.0, 0.0, 0.0, tracedValue.w);
  vec3 l = reflectionSampleDirection(p.x.position, r);
  vec3 value = r.radiance * (glossyBrdfCosine(p, l) * r.W / meanWeight);
  float hitDistance = r.kind == RESTIR_GI_KIND_SKY ? REFLECTION_MISS_DISTANCE : distance(p.x.position, r.samplePosition);
  return vec4(value, hitDistance);
}

void main() {
  FrameConstants f = FrameBlock(pc.frame).v;
  ivec2 g = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(g), pc.tracedResolution))) return;
  ivec2 pixel = reflectionRepresentativePixel(f, pc.divisor, g);
  vec4 tracedValue = imageLoad(traced, g);
  Reservoir r = unpackReservoir(imageLoad(reservoirSample, g), imageLoad(reservoirRadiance, g),
                                imageLoad(reservoirOrigin, g), imageLoad(reservoirNormals, g));
  if (!reflectionReused(pc, f, r, imageLoad(emissives, pixel).w)) {
    imageStore(resolved, g, tracedValue);
    return;
  }
  vec4 value = resolvedSignal(f, pixel, r, tracedValue);
  // Nothing non-finite leaves the pass (as reflections-trace).
  if (any(isnan(value)) || any(isinf(value))) value = vec4(0.0, 0.0, 0.0, REFLECTION_NO_SAMPLE);
  imageStore(resolved, g, vec4(min(value.rgb, vec3(65000.0)), value.w));
}
