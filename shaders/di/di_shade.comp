// di-shade: the direct light of every sampled light at each pixel (DESIGN.md §4 step 3): the
// chain's last reservoir's sample y, its unshadowed integrand with the full glTF BRDF (diffuse
// and specular lobes, common/brdf.glsl) and the emitter's exact (textured, alpha-tested)
// emission, where the targets took its mean (di_common.glsl), times its contribution weight W, times one final shadow
// ray (RTXDI's final visibility). Writes di.radiance, which composite adds (or the DI
// denoiser's output, di/di_denoise.h), di.reservoir-info for the debug views, and
// di.reflectance, what the denoiser divides the radiance by. It also writes di-temporal's next
// history, di.reservoir-final: di-temporal's reservoir, with W = 0 where its sample is the one
// shaded and the final shadow ray found it blocked (RTXDI stores the final visibility in the
// reservoir and discards invisible samples). So no later frame reuses a light this pixel was
// seen not to see, even where the candidates had no shadow ray of their own
// (DiSettings::candidateVisibility). Where the ray found it visible, the history notes so
// (the reservoir's visibility age, 0), and for finalVisibilityMaxAge frames di-shade takes that
// sample as visible without a ray (RTXDI's reuseFinalVisibility); a shadow cast by a moving
// object on a kept sample then lags by up to that many frames. W V(y) is an unbiased contribution weight of the
// visible integrand whenever it is applied. The spatial output is not what is fed back: its
// "basic" bias correction would then compound frame over frame (docs/di.md).
#version 460
#include "di/di_common.glsl"
#include "lighting/specular_albedo.glsl"

layout(local_size_x = DI_GROUP_SIZE, local_size_y = DI_GROUP_SIZE) in;

layout(set = 1, binding = DI_SHADE_BINDING_RESERVOIR, rgba32ui) uniform readonly uimage2D reservoirs;
layout(set = 1, binding = DI_SHADE_BINDING_RADIANCE, rgba16f) uniform writeonly image2D radianceOut;
// (chosen light index, or -1; M; W; visibility 0/1, or -1 where nothing was traced)
layout(set = 1, binding = DI_SHADE_BINDING_INFO, rgba32f) uniform writeonly image2D infoOut;
layout(set = 1, binding = DI_SHADE_BINDING_REFLECTANCE, rgba16f) uniform writeonly image2D reflectanceOut;
layout(set = 1, binding = DI_SHADE_BINDING_FINAL_RESERVOIR, rgba32ui) uniform writeonly uimage2D finalReservoirOut;
layout(set = 1, binding = DI_SHADE_BINDING_TEMPORAL_RESERVOIR, rgba32ui) uniform readonly uimage2D temporalReservoirs;

// What the surface reflects of uniform light, both lobes (the split-sum directional albedo,
// lighting/specular_albedo.glsl, as composite weighs indirect light): the DI denoiser filters
// di.radiance / this, so that it blurs light and not texture (RTXDI and NRD demodulate the same
// way; one signal for both lobes, docs/di.md "The denoiser"). 1 where there is no surface.
vec3 reflectance(FrameConstants f, DiSurface s) {
  if (!s.valid) return vec3(1.0);
  SpecularAlbedo a = specularAlbedo(f.specularAlbedo, max(dot(s.normal, s.wo), 0.0), s.brdf.alpha);
  return diffuseReflectance(a, s.brdf) + specularReflectance(a, s.brdf);
}

void main() {
  FrameConstants f = FrameBlock(pc.frame).v;
  DiConstants di = DiBlock(pc.di).v;
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(pixel), f.resolution))) return;
  lightTables = LightTablesBlock(di.lights).v;
  DiSurface s = loadDiSurface(f, pixel);
  uvec4 shaded = imageLoad(reservoirs, pixel);
  DiReservoir r = unpackDiReservoir(shaded);
  vec3 radiance = vec3(0.0);
  float visibility = -1.0;
  bool traced = false;
  if (s.valid && r.W > 0.0) {
    DiLight l = evaluateDiLightExact(s, r.light, r.u);
    if (any(greaterThan(l.contribution, vec3(0.0)))) {
      // RTXDI's final visibility reuse: a sample this pixel's own ray found visible fewer than
      // finalVisibilityMaxAge frames ago is taken as visible (a hidden one was dropped then).
      bool known = r.visibleAge < di.finalVisibilityMaxAge;
      traced = !known;
      bool visible = known || diVisible(s, l);
      visibility = visible ? 1.0 : 0.0;
      radiance = visible ? l.contribution * r.W : vec3(0.0);
    }
  }
  // The same light and u are the same point y, whichever pixel's reservoir it came through.
  uvec4 continued = imageLoad(temporalReservoirs, pixel);
  DiReservoir history = unpackDiReservoir(continued);
  if (traced && packedDiSample(continued) == packedDiSample(shaded)) {
    if (visibility == 0.0) history.W = 0.0;
    else history.visibleAge = 0u;
  }
  imageStore(finalReservoirOut, pixel, packDiReservoir(history));
  // Nothing non-finite leaves the pass (composite and later temporal passes read it).
  if (any(isnan(radiance)) || any(isinf(radiance))) radiance = vec3(0.0);
  imageStore(radianceOut, pixel, vec4(min(radiance, vec3(65000.0)), 1.0));
  float light = r.light == DI_NO_LIGHT ? -1.0 : float(r.light & ~DI_LIGHT_DISTANT);
  imageStore(infoOut, pixel, vec4(light, r.M, r.W, visibility));
  imageStore(reflectanceOut, pixel, vec4(reflectance(f, s), 1.0));
}
