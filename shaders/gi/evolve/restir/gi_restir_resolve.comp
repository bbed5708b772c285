// gi-restir-resolve: from the GI-resolution reservoirs to gi.diffuse at render resolution
// (irradiance / pi per unit albedo), seed 000 "diffuse-restir-resolve". Each pixel takes its
// own GI pixel's reservoir and up to 3 neighbours on a golden-angle spiral within resolveRadius
// GI pixels (4 samples in all), each shifted to this pixel's primary vertex by reconnection
// (W x Jacobian), keeps those whose primary vertex lies on this pixel's surface, projects their
// radiance into L1 spherical harmonics (their average) and evaluates the SH irradiance with this
// pixel's shading normal: normal-map detail at full resolution from GI-resolution samples.
// L1 SH irradiance drops the clamped cosine's higher orders (Ramamoorthi & Hanrahan 2001): for
// light from a small solid angle it gives 1/4 + cos/2 instead of cos, up to 25 % dark where a
// bright patch faces the surface (sunroom's ceiling above the sunlit floor), and ReSTIR's
// samples concentrate exactly there. So the SH only supplies the variation with the normal:
// the result is the exact estimate at the geometric normal (the mean of L cos / pi W) times
// SH(shading normal) / SH(geometric normal), which is the exact estimate on surfaces without a
// normal map. With one sample (no reuse; the unbiased configuration) the exact estimate at the
// shading normal is used.
// The own reservoir is the one of the GI pixel under this pixel or, when that one lies on
// another surface (an edge at reduced GI resolution), of the nearest GI pixel towards this pixel
// that lies on this one (homeGiPixel), so that edges are not left to the fallback.
// At pixels beside an occluder, samples that gi-trace-resolve-visibility found hidden from this
// pixel's vertex count with zero (see that pass: light leaking into gaps).
#version 460
#include "gi/evolve/restir/restir_gi_common.glsl"
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
layout(set = 1, binding = GI_RESOLVE_BINDING_OCCLUSION, r32ui) uniform readonly uimage2D resolveOcclusion;
#include "gi/evolve/restir/resolve_samples.glsl"

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

const float NORMAL_VARIATION_LIMIT = 4.0;

// SH irradiance at x's shading normal over that at its geometric normal (luminance), bounded;
// 1 where the SH gives nothing at the geometric normal.
float normalVariation(ShL1 sh, PrimaryVertex x) {
  float atGeometric = brdfLuminance(shIrradianceOverPiAt(sh, x.geometricNormal));
  if (!(atGeometric > 1e-8)) return 1.0;
  float atShading = brdfLuminance(shIrradianceOverPiAt(sh, x.shadingNormal));
  return clamp(atShading / atGeometric, 0.0, NORMAL_VARIATION_LIMIT);
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
  ivec2 home = homeGiPixel(f, gi, pixel, x);
  bool reuse = (gi.flags & RESTIR_GI_FLAG_RESOLVE_REUSE) != 0u;
  uint samples = resolveSampleCount(gi);
  float rotation = resolveRotation(f, pixel);
  bool occlusionKnown = (gi.flags & RESTIR_GI_FLAG_OCCLUDER_VISIBILITY) != 0u;
  uint hidden = occlusionKnown ? imageLoad(resolveOcclusion, pixel).x : 0u;
  ShL1 sh = ShL1(vec4(0.0), vec4(0.0), vec4(0.0));
  vec3 exact = vec3(0.0);           // the direct estimate L cos / pi W at the shading normal
  vec3 exactGeometric = vec3(0.0);  // ... and at the geometric normal
  float count = 0.0;
  ShL1 fallback = sh;
  float fallbackDistance = 3.0e38;
  for (uint i = 0u; i < samples; ++i) {
    ivec2 q = resolveSampleGiPixel(gi, home, i, samples, rotation);
    Reservoir r = unpackReservoir(imageLoad(reservoirSample, q), imageLoad(reservoirRadiance, q),
                                  imageLoad(reservoirOrigin, q), imageLoad(reservoirNormals, q));
    if (r.M <= 0.0) continue;
    vec3 direction, lw;
    bool valid = shiftedSample(gi, x, r, direction, lw);
    float planeDistance = abs(dot(x.geometricNormal, r.origin - x.position)) / max(x.depth, 1e-6);
    if (sameSurface(gi, x, r.origin, r.originNormal)) {
      count += 1.0;
      if (!valid || (hidden & (1u << i)) != 0u) continue;
      shAdd(sh, direction, lw);
      exact += lw * (max(dot(direction, x.shadingNormal), 0.0) / PI);
      exactGeometric += lw * (max(dot(direction, x.geometricNormal), 0.0) / PI);
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
    result = (exactGeometric / count) * normalVariation(sh, x);
  } else {
    result = shIrradianceOverPiAt(fallback, x.shadingNormal);
  }
  imageStore(outputImage, pixel, finiteOrZero(vec4(result, 1.0)));
}
