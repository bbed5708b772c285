// gi-prepare-diffuse-rays: one ray per GI pixel from its representative pixel's primary vertex,
// uniformly distributed over the hemisphere of the shading normal (ReSTIR GI, Ouyang et al.
// 2021, §4: the source pdf is 1 / (2 pi)), from blue noise as in seed 000 (see
// blueNoiseSample). Only the direction is written: x1 is in the GBuffer.
// Every validationPeriod-th frame (seed 000: 3) a pixel whose history reservoir survives
// reprojection re-traces that reservoir's stored direction instead (a validation ray; the
// history's GI pixel is encoded in w, shared/restir_gi_io.h), so that gi-resolve-diffuse-rays
// can check it against moved geometry and changed light; disoccluded pixels, which have no
// history, trace a fresh candidate as on other frames.
#version 460
#include "gi/evolve/restir/restir_gi_common.glsl"
#include "lighting/path_vertex.glsl"

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
  if (reservoirKind(origin.w) == RESTIR_GI_KIND_NONE || !(sampleW.w > 0.0) ||
      !sameSurface(gi, x1, origin.xyz, originNormal))
    return vec4(0.0);
  vec3 direction;
  Reservoir h = emptyReservoir();
  h.samplePosition = sampleW.xyz;
  if (sampleCosine(x1, h.samplePosition, direction) <= 0.0) return vec4(0.0);
  return vec4(direction, GI_RAY_VALIDATION + float(q.y * int(gi.giResolution.x) + q.x));
}

layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer BlueNoiseMap {
  uint ranks[];
};

// Spatio-temporal blue noise for the direction of GI pixel g: our void-and-cluster map
// (src/core/blue_noise.h, two channels) tiled over the GI pixels, every value shifted each
// frame by the R2 sequence (Roberts 2018) modulo 1, a Cranley-Patterson rotation shared by all
// pixels. Within a frame the directions of neighbouring pixels are then spread evenly over the
// hemisphere (blue: the spatial passes and denoisers, which average neighbours, see less
// low-frequency error); over frames each pixel walks an R2 sequence from its own start, well
// stratified in time, and equidistributed, so every direction stays equally likely (the
// source pdf is unchanged). Fixed point: ranks of 12 bits become the top bits of 32-bit
// numbers, and the R2 step wraps around exactly.
vec2 blueNoiseSample(RestirGiConstants gi, ivec2 g, uint frame) {
  const uint side = RESTIR_GI_BLUE_NOISE_SIDE;
  const uint rankBits = 12u;  // log2(side * side)
  uvec2 t = uvec2(g) % side;
  uint packed = BlueNoiseMap(gi.blueNoise).ranks[t.y * side + t.x];
  uvec2 rank = uvec2(packed & 0xFFFFu, packed >> 16u);
  uvec2 start = (rank << (32u - rankBits)) + (1u << (31u - rankBits));  // rank + 0.5
  const uvec2 r2Step = uvec2(3242174889u, 2447445413u);  // (1/g, 1/g^2) * 2^32
  return vec2((start + frame * r2Step) >> 8u) * (1.0 / 16777216.0);
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
  // Without the map (RestirGiSettings::blueNoise off): white noise across pixels, the same R2
  // sequence over frames from a hashed start per pixel.
  vec2 u = gi.blueNoise != 0ul ? blueNoiseSample(gi, g, f.frameIndex)
                               : pixelJitter(uvec4(g, RANDOM_GI_DIRECTION, 0u), f.frameIndex);
  imageStore(raysOut, g, vec4(uniformHemisphere(x1.shadingNormal, u), GI_RAY_FRESH));
}
