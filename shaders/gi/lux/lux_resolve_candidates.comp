// lux-resolve-candidates: the 2nd vertex that gi-trace-diffuse-rays found along lux-candidates'
// direction (its radiance towards x1: emission + the NEE sample where its shadow ray is
// unoccluded + the probe field's irradiance x albedo, ReSTIR GI's cache 2nd vertex) becomes a
// ReSTIR GI candidate reservoir (shared/restir_gi_io.h) of M = 1 with lux-candidates' W. That
// W is an unbiased contribution weight of the direction, so the reservoir enters
// gi-restir-temporal's resampling like Evolve's uniform candidates (W = 2 pi) do (generalized
// RIS, Lin et al. 2022: any input with a valid W). Writes the candidate's own estimate of
// gi.diffuse first (the pass's debug view: the RIS estimate the variance and bias tests read)
// and a neutral reservoir validity (Lux traces no validation rays).
#version 460
#include "gi/evolve/restir/restir_gi_common.glsl"
#include "shared/lux_io.h"

layout(local_size_x = RESTIR_GI_GROUP_SIZE, local_size_y = RESTIR_GI_GROUP_SIZE) in;
layout(push_constant, scalar) uniform Push { LuxPassConstants pc; };

layout(set = 1, binding = LUX_RESOLVE_BINDING_NORMALS, rgba16f) uniform readonly image2D normals;
layout(set = 1, binding = LUX_RESOLVE_BINDING_DEPTH, r32f) uniform readonly image2D depths;
layout(set = 1, binding = LUX_RESOLVE_BINDING_RAYS, rgba32f) uniform readonly image2D rays;
layout(set = 1, binding = LUX_RESOLVE_BINDING_WEIGHT, r32f) uniform readonly image2D weights;
layout(set = 1, binding = LUX_RESOLVE_BINDING_HIT, rgba32f) uniform readonly image2D hits;
layout(set = 1, binding = LUX_RESOLVE_BINDING_HIT_NORMAL, rgba16f) uniform readonly image2D hitNormals;
layout(set = 1, binding = LUX_RESOLVE_BINDING_HIT_RADIANCE, rgba32f) uniform readonly image2D hitRadiance;
layout(set = 1, binding = LUX_RESOLVE_BINDING_NEE_RADIANCE, rgba32f) uniform readonly image2D neeRadiance;
layout(set = 1, binding = LUX_RESOLVE_BINDING_VISIBILITY, r16f) uniform readonly image2D neeVisibility;
layout(set = 1, binding = LUX_RESOLVE_BINDING_ESTIMATE, rgba16f) uniform writeonly image2D estimateOut;
layout(set = 1, binding = LUX_RESOLVE_BINDING_SAMPLE + GI_RESERVOIR_SAMPLE, rgba32f) uniform writeonly image2D sampleOut;
layout(set = 1, binding = LUX_RESOLVE_BINDING_SAMPLE + GI_RESERVOIR_RADIANCE, rgba32f) uniform writeonly image2D radianceOut;
layout(set = 1, binding = LUX_RESOLVE_BINDING_SAMPLE + GI_RESERVOIR_ORIGIN, rgba32f) uniform writeonly image2D originOut;
layout(set = 1, binding = LUX_RESOLVE_BINDING_SAMPLE + GI_RESERVOIR_NORMALS, rgba16f) uniform writeonly image2D normalsOut;
layout(set = 1, binding = LUX_RESOLVE_BINDING_VALIDITY, rgba16f) uniform writeonly image2D validityOut;

void main() {
  FrameConstants f = FrameBlock(pc.frame).v;
  RestirGiConstants gi = RestirGiBlock(pc.gi).v;
  ivec2 g = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(g), gi.giResolution))) return;
  ivec2 pixel = giRepresentativePixel(f, gi, g);
  PrimaryVertex x1 = makePrimaryVertex(f, pixel, imageLoad(normals, pixel), imageLoad(depths, pixel).x);
  Reservoir r = emptyReservoir();
  if (imageLoad(rays, g).w != 0.0) {
    vec4 hit = imageLoad(hits, g);
    r.kind = uint(hit.w + 0.5);
    r.samplePosition = hit.xyz;
    r.sampleNormal = decodeOctahedral(imageLoad(hitNormals, g).xy);
    r.radiance = imageLoad(hitRadiance, g).rgb + imageLoad(neeRadiance, g).rgb * imageLoad(neeVisibility, g).x;
    r.origin = x1.position;
    r.originNormal = x1.shadingNormal;
    r.M = 1.0;
    r.W = targetFunction(x1, r) > 0.0 ? imageLoad(weights, g).x : 0.0;
  }
  imageStore(estimateOut, g, finiteOrZero(vec4(reservoirEstimate(x1, r), 1.0)));
  vec4 a, b, c, d;
  packReservoir(r, a, b, c, d);
  imageStore(sampleOut, g, finiteOrZero(a));
  imageStore(radianceOut, g, finiteOrZero(b));
  imageStore(originOut, g, finiteOrZero(c));
  imageStore(normalsOut, g, d);
  imageStore(validityOut, g, vec4(1.0, 0.0, 0.0, 0.0));
}
