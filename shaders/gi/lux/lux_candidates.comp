// lux-candidates (seed 002's "ReSTIR Indirect"; gi10_lux_denoisers.md §2.3(c)): per GI pixel,
// M = LuxSettings::candidates directions drawn from the cosine distribution about x1's shading
// normal, resampled (RIS; Talbot 2005, Bitterli et al. 2020 Eq. 5-6) with the probe field's
// incoming radiance as the target:
//   p_hat(w) = (max(0, lum L_probe(x1, w)) + targetFloor * mean lum L_probe) * cos(w)
// where L_probe is the L1 SH of x1's probe (lux_probe_field.glsl). Source pdf cos / pi, so each
// candidate's weight is p_hat / pdf = pi (max(0, lum L) + floor); W of the chosen one is
// (1 / p_hat(w)) (1 / M) sum of the weights. The floor keeps p_hat > 0 wherever the integrand
// can be (L1 rings negative opposite a bright direction, and the probe lags the light): the
// estimator stays unbiased for the traced radiance, whatever the probe says. No probe yet
// (cache cell without SH): p_hat = cos, i.e. plain cosine sampling, W = pi / cos.
// Writes the chosen direction to gi.rays for gi-trace-diffuse-rays (the one ray per final
// sample: the radiance at its hit is the integrand) and W to lux.weight. Directions below x1's
// geometric surface get p_hat = 0: their integrand is zero (gi-trace-diffuse-rays drops them).
#version 460
#include "gi/lux/lux_probe_field.glsl"
#include "gi/evolve/restir/restir_gi_common.glsl"
#include "shared/lux_io.h"

layout(local_size_x = RESTIR_GI_GROUP_SIZE, local_size_y = RESTIR_GI_GROUP_SIZE) in;
layout(push_constant, scalar) uniform Push { LuxPassConstants pc; };

layout(set = 1, binding = LUX_CANDIDATES_BINDING_NORMALS, rgba16f) uniform readonly image2D normals;
layout(set = 1, binding = LUX_CANDIDATES_BINDING_DEPTH, r32f) uniform readonly image2D depths;
layout(set = 1, binding = LUX_CANDIDATES_BINDING_FLAGS, r32ui) uniform readonly uimage2D flags;
layout(set = 1, binding = LUX_CANDIDATES_BINDING_TARGET, rgba16f) uniform writeonly image2D targetOut;
layout(set = 1, binding = LUX_CANDIDATES_BINDING_RAYS, rgba32f) uniform writeonly image2D raysOut;
layout(set = 1, binding = LUX_CANDIDATES_BINDING_WEIGHT, r32f) uniform writeonly image2D weightOut;

const uint RANDOM_LUX_CANDIDATE = 0x4C550001u;
const uint RANDOM_LUX_PROBE = 0x4C550002u;
const uint RANDOM_LUX_PICK = 0x4C550003u;

// p_hat / cos at direction w (the cosine cancels against the source pdf; see the top).
float radianceTarget(PrimaryVertex x1, bool haveProbe, ProbeSh sh, float floorLuminance, vec3 w) {
  if (dot(w, x1.geometricNormal) <= 0.0) return 0.0;
  if (!haveProbe) return 1.0;
  return max(luxProbeLuminance(sh, w), 0.0) + floorLuminance;
}

void main() {
  FrameConstants f = FrameBlock(pc.frame).v;
  RestirGiConstants gi = RestirGiBlock(pc.gi).v;
  ivec2 g = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(g), gi.giResolution))) return;
  ivec2 pixel = giRepresentativePixel(f, gi, g);
  if ((imageLoad(flags, pixel).x & GBUFFER_FLAG_SURFACE) == 0u) {
    imageStore(targetOut, g, vec4(0.0));
    imageStore(raysOut, g, vec4(0.0));
    imageStore(weightOut, g, vec4(0.0));
    return;
  }
  PrimaryVertex x1 = makePrimaryVertex(f, pixel, imageLoad(normals, pixel), imageLoad(depths, pixel).x);
  ClipmapCacheView cache = clipmapCacheView(gi.cache);
  ProbeSh sh;
  uint probeSeed = pcg4d(uvec4(g, f.frameIndex, RANDOM_LUX_PROBE)).x;
  bool haveProbe = luxProbeSh(cache, x1.position, x1.shadingNormal, probeSeed, sh);
  float mean = haveProbe ? max(luxProbeMeanLuminance(sh), 0.0) : 0.0;
  // An all-black probe has no shape to follow: cosine sampling.
  haveProbe = haveProbe && mean > 0.0;
  float floorLuminance = pc.targetFloor * mean;

  // Streaming RIS over the candidates (weights pi * target; the pi cancels in W).
  float weightSum = 0.0;
  float chosenTarget = 0.0;
  vec3 chosen = x1.shadingNormal;
  float pick = uniformFromHash(pcg4d(uvec4(g, f.frameIndex, RANDOM_LUX_PICK))).x;
  for (uint i = 0u; i < pc.candidates; ++i) {
    vec2 u = uniformFromHash(pcg4d(uvec4(g, f.frameIndex * pc.candidates + i, RANDOM_LUX_CANDIDATE))).xy;
    vec3 w = sampleCosineHemisphere(x1.shadingNormal, u);
    float t = radianceTarget(x1, haveProbe, sh, floorLuminance, w);
    if (!(t > 0.0)) continue;
    weightSum += t;
    // Sequential selection with one random number: keep w with probability t / weightSum.
    if (pick * weightSum < t) {
      chosen = w;
      chosenTarget = t;
      pick = pick * weightSum / t;
    } else {
      pick = (pick * weightSum - t) / (weightSum - t);
    }
  }
  float cosine = max(dot(chosen, x1.shadingNormal), 0.0);
  // W = (1 / p_hat) (1 / M) sum (p_hat_i / pdf_i), p_hat = target * cos, pdf = cos / pi.
  float W = chosenTarget > 0.0 && cosine > 0.0
                ? PI * weightSum / (float(pc.candidates) * chosenTarget * cosine)
                : 0.0;
  vec3 probe = haveProbe ? luxProbeIrradianceOverPi(sh, x1.shadingNormal) : vec3(0.0);
  imageStore(targetOut, g, finiteOrZero(vec4(min(probe, vec3(60000.0)), min(W, 60000.0))));
  imageStore(raysOut, g, W > 0.0 && isFiniteValue(W) ? vec4(chosen, GI_RAY_FRESH) : vec4(0.0));
  imageStore(weightOut, g, vec4(isFiniteValue(W) ? W : 0.0));
}
