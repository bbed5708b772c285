// gi-prepare-diffuse-rays: one ray per GI pixel from its representative pixel's primary vertex,
// uniformly distributed over the hemisphere of the shading normal (ReSTIR GI, Ouyang et al.
// 2021, §4: the source pdf is 1 / (2 pi)). The directions come from the R2 low-discrepancy
// sequence over frames (Roberts 2018) with a per-pixel Cranley-Patterson rotation
// (reference/integrator.glsl pixelJitter): successive frames of one pixel are well stratified,
// neighbouring pixels independent. (Seed 000 uses blue noise; our own generated blue-noise
// texture is not there yet.) Only the direction is written: x1 is in the GBuffer.
// Every validationPeriod-th frame (seed 000: 3) a pixel whose history reservoir survives
// reprojection re-traces that reservoir's stored direction instead (a validation ray; the
// history's GI pixel is encoded in w, shared/restir_gi_io.h), so that gi-resolve-diffuse-rays
// can check it against moved geometry and changed light; disoccluded pixels, which have no
// history, trace a fresh candidate as on other frames.
#version 460
#include "gi/evolve/restir_gi_common.glsl"
#include "reference/integrator.glsl"

layout(local_size_x = RESTIR_GI_GROUP_SIZE, local_size_y = RESTIR_GI_GROUP_SIZE) in;
layout(push_constant, scalar) uniform Push { RestirGiPassConstants pc; };

layout(set = 1, binding = GI_PREPARE_BINDING_NORMALS, rgba16f) uniform readonly image2D normals;
layout(set = 1, binding = GI_PREPARE_BINDING_DEPTH, r32f) uniform readonly image2D depths;
layout(set = 1, binding = GI_PREPARE_BINDING_FLAGS, r32ui) uniform readonly uimage2D flags;
layout(set = 1, binding = GI_PREPARE_BINDING_RAYS, rgba32f) uniform writeonly image2D raysOut;
layout(set = 1, binding = GI_PREPARE_BINDING_PREVIOUS_SAMPLE, rgba32f) uniform readonly image2D previousSample;
layout(set = 1, binding = GI_PREPARE_BINDING_PREVIOUS_ORIGIN, rgba32f) uniform readonly image2D previousOrigin;
layout(set = 1, binding = GI_PREPARE_BINDING_PREVIOUS_NORMALS, rgba16f) uniform readonly image2D previousNormals;
layout(set = 1, binding = GI_PREPARE_BINDING_VELOCITY, rg16f) uniform readonly image2D velocities;

bool validationFrame(FrameConstants f, RestirGiConstants gi) {
  return pc.historyValid != 0u && (gi.flags & RESTIR_GI_FLAG_VALIDATION) != 0u &&
         (gi.flags & RESTIR_GI_FLAG_TEMPORAL) != 0u && gi.validationPeriod > 0u &&
         f.frameIndex % gi.validationPeriod == 0u;
}

// A validation ray towards the reprojected history reservoir's sample, or w = 0 when there is
// none on this surface (disocclusion).
vec4 validationRay(RestirGiConstants gi, ivec2 pixel, PrimaryVertex x1) {
  ivec2 q = reprojectedGiPixel(gi, pixel, imageLoad(velocities, pixel).xy);
  if (q.x < 0) return vec4(0.0);
  vec4 sampleW = imageLoad(previousSample, q);
  vec4 origin = imageLoad(previousOrigin, q);
  vec3 originNormal = decodeOctahedral(imageLoad(previousNormals, q).xy);
  if (uint(origin.w + 0.5) == RESTIR_GI_KIND_NONE || !(sampleW.w > 0.0) ||
      !sameSurface(gi, x1, origin.xyz, originNormal))
    return vec4(0.0);
  vec3 direction;
  Reservoir h = emptyReservoir();
  h.samplePosition = sampleW.xyz;
  if (sampleCosine(x1, h.samplePosition, direction) <= 0.0) return vec4(0.0);
  return vec4(direction, GI_RAY_VALIDATION + float(q.y * int(gi.giResolution.x) + q.x));
}

vec3 uniformHemisphere(vec3 n, vec2 u) {
  float cosTheta = u.x;
  float sinTheta = sqrt(max(0.0, 1.0 - cosTheta * cosTheta));
  float phi = 2.0 * PI * u.y;
  vec3 t, b;
  orthonormalBasis(n, t, b);
  return normalize(sinTheta * cos(phi) * t + sinTheta * sin(phi) * b + cosTheta * n);
}

void main() {
  FrameConstants f = FrameBlock(pc.frame).v;
  RestirGiConstants gi = RestirGiBlock(pc.gi).v;
  ivec2 g = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(g), gi.giResolution))) return;
  ivec2 pixel = giRepresentativePixel(f, gi, g);
  if ((imageLoad(flags, pixel).x & GBUFFER_FLAG_SURFACE) == 0u) {
    imageStore(raysOut, g, vec4(0.0));
    return;
  }
  PrimaryVertex x1 = makePrimaryVertex(f, pixel, imageLoad(normals, pixel), imageLoad(depths, pixel).x);
  if (validationFrame(f, gi)) {
    vec4 ray = validationRay(gi, pixel, x1);
    if (ray.w != 0.0) {
      imageStore(raysOut, g, ray);
      return;
    }
  }
  vec2 u = pixelJitter(uvec4(g, RANDOM_GI_DIRECTION, 0u), f.frameIndex);
  imageStore(raysOut, g, vec4(uniformHemisphere(x1.shadingNormal, u), GI_RAY_FRESH));
}
