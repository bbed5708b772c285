// gi-restir-resolve: from the GI-resolution reservoirs to gi.diffuse at render resolution
// (irradiance / pi per unit albedo), seed 000 "diffuse-restir-resolve". Each pixel takes its
// own GI pixel's reservoir and up to 3 neighbours on a golden-angle spiral within resolveRadius
// GI pixels (4 samples in all), each shifted to this pixel's primary vertex by reconnection
// (W x Jacobian), keeps those whose primary vertex lies on this pixel's surface, projects their
// radiance into L1 spherical harmonics (their average) and evaluates the SH irradiance with this
// pixel's shading normal: normal-map detail at full resolution from GI-resolution samples, and
// a smoother signal than the samples. With one sample (no reuse; the unbiased configuration)
// the exact estimate L cos / pi W is used instead (L1 SH of one sample is not the cosine).
#version 460
#include "gi/evolve/restir_gi_common.glsl"
#include "common/random.glsl"
#include "common/sh.glsl"

layout(local_size_x = RESTIR_GI_GROUP_SIZE, local_size_y = RESTIR_GI_GROUP_SIZE) in;
layout(push_constant, scalar) uniform Push { RestirGiPassConstants pc; };

layout(set = 1, binding = GI_RESOLVE_BINDING_RESERVOIR + GI_RESERVOIR_SAMPLE, rgba32f) uniform readonly image2D reservoirSample;
layout(set = 1, binding = GI_RESOLVE_BINDING_RESERVOIR + GI_RESERVOIR_RADIANCE, rgba32f) uniform readonly image2D reservoirRadiance;
layout(set = 1, binding = GI_RESOLVE_BINDING_RESERVOIR + GI_RESERVOIR_ORIGIN, rgba32f) uniform readonly image2D reservoirOrigin;
layout(set = 1, binding = GI_RESOLVE_BINDING_RESERVOIR + GI_RESERVOIR_NORMALS, rgba16f) uniform readonly image2D reservoirNormals;
layout(set = 1, binding = GI_RESOLVE_BINDING_NORMALS, rgba16f) uniform readonly image2D normals;
layout(set = 1, binding = GI_RESOLVE_BINDING_DEPTH, r32f) uniform readonly image2D depths;
layout(set = 1, binding = GI_RESOLVE_BINDING_FLAGS, r32ui) uniform readonly uimage2D flags;
layout(set = 1, binding = GI_RESOLVE_BINDING_OUTPUT, rgba16f) uniform writeonly image2D outputImage;

const uint RANDOM_GI_RESOLVE = 0x47490004u;

// L1 spherical harmonics of incoming radiance (common/sh.glsl), one vec4 per colour channel.
struct ShL1 {
  vec4 r, g, b;
};

// Adds a radiance sample L from direction w with weight W (a reservoir's estimate of the
// radiance integral over directions: L W, Ouyang et al. 2021 Eq. 6) to the projection.
void shAdd(inout ShL1 sh, vec3 w, vec3 radianceTimesW) {
  vec4 basis = shBasisL1(w);
  sh.r += radianceTimesW.r * basis;
  sh.g += radianceTimesW.g * basis;
  sh.b += radianceTimesW.b * basis;
}

// Irradiance / pi at normal n, per channel.
vec3 shIrradianceOverPiAt(ShL1 sh, vec3 n) {
  return vec3(shIrradianceOverPi(sh.r, n), shIrradianceOverPi(sh.g, n), shIrradianceOverPi(sh.b, n));
}

// The reservoir r shifted to x (reconnection; its W carries the Jacobian), as radiance x W and
// its direction; false when it does not reach x's hemisphere or the Jacobian is rejected.
bool shiftedSample(RestirGiConstants gi, PrimaryVertex x, Reservoir r, out vec3 direction,
                   out vec3 radianceTimesW) {
  float jacobian = reconnectionJacobian(r.origin, x.position, r);
  float c = sampleCosine(x, r.samplePosition, direction);
  radianceTimesW = r.radiance * (r.W * jacobian);
  return c > 0.0 && jacobian > 0.0 && jacobian <= gi.maxJacobian && r.W > 0.0;
}

void main() {
  FrameConstants f = FrameBlock(pc.frame).v;
  RestirGiConstants gi = RestirGiBlock(pc.gi).v;
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(pixel), f.resolution))) return;
  if ((imageLoad(flags, pixel).x & GBUFFER_FLAG_SURFACE) == 0u) {
    imageStore(outputImage, pixel, vec4(0.0));
    return;
  }
  PrimaryVertex x = makePrimaryVertex(f, pixel, imageLoad(normals, pixel), imageLoad(depths, pixel).x);
  ivec2 home = min(pixel / int(gi.divisor), ivec2(gi.giResolution) - 1);
  bool reuse = (gi.flags & RESTIR_GI_FLAG_RESOLVE_REUSE) != 0u;
  uint samples = reuse ? clamp(gi.resolveSamples, 1u, 4u) : 1u;
  float rotation = 2.0 * PI * random2(uvec2(pixel), f.frameIndex, RANDOM_GI_RESOLVE).x;
  ShL1 sh = ShL1(vec4(0.0), vec4(0.0), vec4(0.0));
  vec3 exact = vec3(0.0);  // the direct estimate L cos / pi W (no reuse: the unbiased path)
  float count = 0.0;
  ShL1 fallback = sh;
  float fallbackDistance = 3.0e38;
  for (uint i = 0u; i < samples; ++i) {
    ivec2 q = home;
    if (i > 0u) {
      vec2 offset = goldenSpiralOffset(i - 1u, samples - 1u, rotation, 0.5 * gi.resolveRadius, gi.resolveRadius);
      q = clamp(home + ivec2(round(offset)), ivec2(0), ivec2(gi.giResolution) - 1);
    }
    Reservoir r = unpackReservoir(imageLoad(reservoirSample, q), imageLoad(reservoirRadiance, q),
                                  imageLoad(reservoirOrigin, q), imageLoad(reservoirNormals, q));
    if (r.M <= 0.0) continue;
    vec3 direction, lw;
    bool valid = shiftedSample(gi, x, r, direction, lw);
    float planeDistance = abs(dot(x.geometricNormal, r.origin - x.position)) / max(x.depth, 1e-6);
    if (sameSurface(gi, x, r.origin, r.originNormal)) {
      count += 1.0;
      if (!valid) continue;
      shAdd(sh, direction, lw);
      exact += lw * (max(dot(direction, x.shadingNormal), 0.0) / PI);
    } else if (planeDistance < fallbackDistance) {
      // No reservoir on this surface (a thin feature at reduced GI resolution): the nearest one.
      fallbackDistance = planeDistance;
      fallback = ShL1(vec4(0.0), vec4(0.0), vec4(0.0));
      if (valid) shAdd(fallback, direction, lw);
    }
  }
  vec3 result;
  if (!reuse) result = count > 0.0 ? exact / count : shIrradianceOverPiAt(fallback, x.shadingNormal);
  else if (count > 0.0) {
    sh.r /= count;
    sh.g /= count;
    sh.b /= count;
    result = shIrradianceOverPiAt(sh, x.shadingNormal);
  } else {
    result = shIrradianceOverPiAt(fallback, x.shadingNormal);
  }
  imageStore(outputImage, pixel, finiteOrZero(vec4(result, 1.0)));
}
