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
// samples concentrate exactly there. So the SH (of luminance) only supplies the variation with the normal:
// the result is the exact estimate at the geometric normal (the mean of L cos / pi W) times
// SH(shading normal) / SH(geometric normal), which is the exact estimate on surfaces without a
// normal map. With one sample (no reuse; the unbiased configuration) the exact estimate at the
// shading normal is used.
// The own reservoir is the one of the GI pixel under this pixel or, when that one lies on
// another surface (an edge at reduced GI resolution), of the nearest GI pixel towards this pixel
// that lies on this one (homeGiPixel), so that edges are not left to the fallback.
// At pixels beside an occluder, samples that gi-trace-resolve-visibility found hidden from this
// pixel's vertex count with zero (see that pass: light leaking into gaps).
// With RESTIR_GI_FLAG_CANONICAL_RESOLVE the home reservoir is the canonical one of a
// combination whose weights sum to one over the reservoirs that can produce each sample
// (Wyman et al. 2023, §5.3, the canonical reservoir taking the remainder): it reaches this
// pixel by a direction shift (homeSample), never refused; a neighbour's accepted sample
// weighs 1/n (n: the reservoirs on this surface) and the home's sample 1 - k/n, k the
// neighbours whose shift of it would be accepted (couldProduce, one Jacobian each: no target
// is evaluated). Without it the mean of the reservoirs whose shift is accepted (Lux): a refused
// shift counted as zero until session 27, which darkened by the share of refused shifts (Lux's
// cap of 2: 17 %; docs/gi/lux.md, "Measurements").
#version 460
#extension GL_EXT_samplerless_texture_functions : require
#include "gi/evolve/restir/restir_gi_common.glsl"
#include "common/random.glsl"
#include "common/sh.glsl"

layout(local_size_x = RESTIR_GI_GROUP_SIZE, local_size_y = RESTIR_GI_GROUP_SIZE) in;
layout(push_constant, scalar) uniform Push { RestirGiPassConstants pc; };

layout(set = 1, binding = GI_RESOLVE_BINDING_RESERVOIR + GI_RESERVOIR_SAMPLE) uniform texture2D reservoirSample;
layout(set = 1, binding = GI_RESOLVE_BINDING_RESERVOIR + GI_RESERVOIR_RADIANCE) uniform texture2D reservoirRadiance;
layout(set = 1, binding = GI_RESOLVE_BINDING_RESERVOIR + GI_RESERVOIR_ORIGIN) uniform texture2D reservoirOrigin;
layout(set = 1, binding = GI_RESOLVE_BINDING_RESERVOIR + GI_RESERVOIR_NORMALS) uniform texture2D reservoirNormals;
layout(set = 1, binding = GI_RESOLVE_BINDING_NORMALS) uniform texture2D normals;
layout(set = 1, binding = GI_RESOLVE_BINDING_DEPTH) uniform texture2D depths;
layout(set = 1, binding = GI_RESOLVE_BINDING_FLAGS) uniform utexture2D flags;
layout(set = 1, binding = GI_RESOLVE_BINDING_OUTPUT, rgba16f) uniform writeonly image2D outputImage;
layout(set = 1, binding = GI_RESOLVE_BINDING_OCCLUSION) uniform utexture2D resolveOcclusion;
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

// SH irradiance at x's shading normal over that at its geometric normal, bounded; 1 where the
// SH gives nothing at the geometric normal. Of luminance: the ratio is taken of luminances, so
// the SH of the samples' luminance is all it needs (a third of the registers and arithmetic of
// the colour SH; the two differ only where L1 rings below zero in some channels, which the
// clamp cuts per channel).
float normalVariation(vec4 shLuminance, PrimaryVertex x) {
  float atGeometric = shIrradianceOverPi(shLuminance, x.geometricNormal);
  if (!(atGeometric > 1e-8)) return 1.0;
  float atShading = shIrradianceOverPi(shLuminance, x.shadingNormal);
  return clamp(atShading / atGeometric, 0.0, NORMAL_VARIATION_LIMIT);
}

// The reservoir r shifted to x (reconnection; its W carries the Jacobian), as radiance x W and
// its direction; false when it does not reach x's hemisphere or the Jacobian is rejected.
bool shiftedSample(PrimaryVertex x, Reservoir r, float maxJacobian, out vec3 direction,
                   out vec3 radianceTimesW) {
  float jacobian = reconnectionJacobian(r.origin, x.position, r);
  float c = sampleCosine(x, r.samplePosition, direction);
  radianceTimesW = r.radiance * (r.W * jacobian);
  return c > 0.0 && jacobian > 0.0 && jacobian <= maxJacobian;
}

// The home reservoir's sample at x by a direction shift (the direction from its own vertex
// replayed at x, Jacobian 1; Lin et al. 2022's random replay for one vertex): x lies within
// the GI pixel whose vertex traced it, so the radiance along that direction is the same except
// where the hit is about as close as x is to that vertex. The reconnection shift there has a
// Jacobian that grows without bound ((distance from the home vertex / distance from x)^2 near
// contact, the other wall of a corner): refused above maxJacobian, those samples were lost to
// every pixel but the GI pixel's own; accepted, they are fireflies whose mean a finite number
// of frames undershoots and that the anti-firefly clamp cut (docs/gi/restir-gi.md, "Energy").
bool homeSample(PrimaryVertex x, Reservoir r, out vec3 direction, out vec3 radianceTimesW) {
  direction = normalize(r.samplePosition - r.origin);
  radianceTimesW = r.radiance * r.W;
  return dot(direction, x.geometricNormal) > 0.0 && dot(direction, x.shadingNormal) > 0.0;
}

void main() {
  FrameConstants f = FrameBlock(pc.frame).v;
  RestirGiConstants gi = RestirGiBlock(pc.gi).v;
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(pixel), f.resolution))) return;
  if ((texelFetch(flags, pixel, 0).x & GBUFFER_FLAG_SURFACE) == 0u) {
    imageStore(outputImage, pixel, vec4(0.0));
    return;
  }
  PrimaryVertex x = makePrimaryVertex(f, pixel, texelFetch(normals, pixel, 0), texelFetch(depths, pixel, 0).x);
  ivec2 homePixel = homeGiPixel(f, gi, pixel, x);
  bool reuse = (gi.flags & RESTIR_GI_FLAG_RESOLVE_REUSE) != 0u;
  uint samples = resolveSampleCount(gi);
  float rotation = resolveRotation(f, pixel);
  bool occlusionKnown = (gi.flags & RESTIR_GI_FLAG_OCCLUDER_VISIBILITY) != 0u;
  uint hidden = occlusionKnown ? texelFetch(resolveOcclusion, pixel, 0).x : 0u;
  bool canonical = (gi.flags & RESTIR_GI_FLAG_CANONICAL_RESOLVE) != 0u;
  vec4 shLuminance = vec4(0.0);  // L1 SH of the samples' luminance (normalVariation)
  vec3 exact = vec3(0.0);           // the direct estimate L cos / pi W at the shading normal
  vec3 exactGeometric = vec3(0.0);  // ... and at the geometric normal
  float count = 0.0;                // reservoirs on this surface
  // The home reservoir as the canonical one: its sample (added last, weighted) and the number
  // of neighbours that could produce it.
  Reservoir home = emptyReservoir();
  vec3 homeDirection = vec3(0.0), homeLw = vec3(0.0);
  bool homeContributes = false;
  float homeProducers = 0.0;
  // The nearest reservoir off this surface, one sample (kept as such, not as SH: registers).
  vec3 fallbackDirection = vec3(0.0), fallbackLw = vec3(0.0);
  float fallbackDistance = 3.0e38;
  for (uint i = 0u; i < samples; ++i) {
    ivec2 q = resolveSampleGiPixel(gi, homePixel, i, samples, rotation);
    Reservoir r = unpackReservoir(texelFetch(reservoirSample, q, 0), texelFetch(reservoirRadiance, q, 0),
                                  texelFetch(reservoirOrigin, q, 0), texelFetch(reservoirNormals, q, 0));
    if (r.M <= 0.0) continue;
    bool same = sameSurface(gi, x, r.origin, r.originNormal);
    vec3 direction, lw;
    if (i == 0u && same && canonical) {
      home = r;
      count += 1.0;
      homeContributes = homeSample(x, r, homeDirection, homeLw) && r.W > 0.0 && (hidden & 1u) == 0u;
      continue;
    }
    bool valid = shiftedSample(x, r, gi.maxJacobian, direction, lw);
    float planeDistance = abs(dot(x.geometricNormal, r.origin - x.position)) / max(x.depth, 1e-6);
    if (same) {
      // Canonical: n counts every reservoir on this surface. Otherwise the mean is over the
      // reservoirs whose shift is accepted: a refused shift leaves it rather than counting as zero.
      if (canonical || valid) count += 1.0;
      if (home.M > 0.0 && couldProduce(r.origin, r.originNormal, x, home, gi.maxJacobian))
        homeProducers += 1.0;
      if (!valid || !(r.W > 0.0) || (hidden & (1u << i)) != 0u) continue;
      shLuminance += brdfLuminance(lw) * shBasisL1(direction);
      exact += lw * (max(dot(direction, x.shadingNormal), 0.0) / PI);
      exactGeometric += lw * (max(dot(direction, x.geometricNormal), 0.0) / PI);
    } else if (planeDistance < fallbackDistance) {
      // No reservoir on this surface (a thin feature at reduced GI resolution): the nearest one.
      fallbackDistance = planeDistance;
      fallbackDirection = direction;
      fallbackLw = valid ? lw : vec3(0.0);
    }
  }
  if (homeContributes) {
    // The neighbours enter with 1/count each (the division below), the home with 1 - k/count.
    vec3 lw = homeLw * (count - homeProducers);
    shLuminance += brdfLuminance(lw) * shBasisL1(homeDirection);
    exact += lw * (max(dot(homeDirection, x.shadingNormal), 0.0) / PI);
    exactGeometric += lw * (max(dot(homeDirection, x.geometricNormal), 0.0) / PI);
  }
  vec3 result;
  if (!(count > 0.0)) {
    ShL1 fallback = ShL1(vec4(0.0), vec4(0.0), vec4(0.0));
    shAdd(fallback, fallbackDirection, fallbackLw);
    result = shIrradianceOverPiAt(fallback, x.shadingNormal);
  }
  else if (!reuse) result = exact / count;
  else result = (exactGeometric / count) * normalVariation(shLuminance, x);
  imageStore(outputImage, pixel, finiteOrZero(vec4(result, 1.0)));
}
