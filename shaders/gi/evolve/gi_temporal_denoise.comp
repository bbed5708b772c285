// gi-temporal-denoise: a running mean of gi-restir-resolve's output over up to
// denoiseMaxHistory frames, TAA-style: the pixel's position last frame (gbuffer.velocity) is
// looked up in last frame's result where the surface agrees (view depth), and that history is
// clipped to this frame's 3x3 neighbourhood, mean +- denoiseClipSigma standard deviations
// (variance clipping, Salvi 2016), so that lighting changes get through within a few frames.
// The history length shrinks with the reservoir validity (gi-resolve-diffuse-rays) and grows
// where the spatial occlusion validity is low (gi-trace-spatial-validation-rays). Writes
// gi.diffuse. Nothing non-finite enters history.
#version 460
#include "gi/evolve/restir_gi_common.glsl"

layout(local_size_x = RESTIR_GI_GROUP_SIZE, local_size_y = RESTIR_GI_GROUP_SIZE) in;
layout(push_constant, scalar) uniform Push { RestirGiPassConstants pc; };

layout(set = 1, binding = GI_DENOISE_BINDING_INPUT, rgba16f) uniform readonly image2D inputImage;
layout(set = 1, binding = GI_DENOISE_BINDING_NORMALS, rgba16f) uniform readonly image2D normals;
layout(set = 1, binding = GI_DENOISE_BINDING_DEPTH, r32f) uniform readonly image2D depths;
layout(set = 1, binding = GI_DENOISE_BINDING_PREVIOUS_DEPTH, r32f) uniform readonly image2D previousDepths;
layout(set = 1, binding = GI_DENOISE_BINDING_FLAGS, r32ui) uniform readonly uimage2D flags;
layout(set = 1, binding = GI_DENOISE_BINDING_VELOCITY, rg16f) uniform readonly image2D velocities;
layout(set = 1, binding = GI_DENOISE_BINDING_PREVIOUS, rgba16f) uniform readonly image2D previous;
layout(set = 1, binding = GI_DENOISE_BINDING_CURRENT, rgba16f) uniform writeonly image2D current;
layout(set = 1, binding = GI_DENOISE_BINDING_OUTPUT, rgba16f) uniform writeonly image2D outputImage;
layout(set = 1, binding = GI_DENOISE_BINDING_VALIDITY, rg16f) uniform readonly image2D reservoirValidity;
layout(set = 1, binding = GI_DENOISE_BINDING_OCCLUSION_VALIDITY, r16f) uniform readonly image2D occlusionValidity;

const float HISTORY_DEPTH_TOLERANCE = 0.03;

void main() {
  FrameConstants f = FrameBlock(pc.frame).v;
  RestirGiConstants gi = RestirGiBlock(pc.gi).v;
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(pixel), f.resolution))) return;
  if ((imageLoad(flags, pixel).x & GBUFFER_FLAG_SURFACE) == 0u) {
    imageStore(current, pixel, vec4(0.0));
    imageStore(outputImage, pixel, vec4(0.0));
    return;
  }
  vec3 value = imageLoad(inputImage, pixel).rgb;
  // Neighbourhood statistics over surface pixels.
  vec3 mean = vec3(0.0), meanSq = vec3(0.0);
  float n = 0.0;
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      ivec2 q = clamp(pixel + ivec2(dx, dy), ivec2(0), ivec2(f.resolution) - 1);
      if ((imageLoad(flags, q).x & GBUFFER_FLAG_SURFACE) == 0u) continue;
      vec3 c = imageLoad(inputImage, q).rgb;
      mean += c;
      meanSq += c * c;
      n += 1.0;
    }
  mean /= n;
  vec3 sigma = sqrt(max(meanSq / n - mean * mean, vec3(0.0)));

  vec4 history = vec4(0.0);
  if (pc.historyValid != 0u && (gi.flags & RESTIR_GI_FLAG_DENOISE) != 0u) {
    vec2 previousPosition = vec2(pixel) + 0.5 - imageLoad(velocities, pixel).xy;
    ivec2 p = ivec2(floor(previousPosition));
    if (all(greaterThanEqual(p, ivec2(0))) && all(lessThan(p, ivec2(f.resolution)))) {
      vec3 position = positionFromDepth(f, vec2(pixel) + 0.5, imageLoad(depths, pixel).x);
      float expectedDepth = (f.previousViewProjection * vec4(position, 1.0)).w;
      float previousDepth = imageLoad(previousDepths, p).x;
      if (abs(previousDepth - expectedDepth) <= HISTORY_DEPTH_TOLERANCE * expectedDepth)
        history = finiteOrZero(imageLoad(previous, p));
    }
  }
  vec3 clipped = clamp(history.rgb, mean - gi.denoiseClipSigma * sigma, mean + gi.denoiseClipSigma * sigma);
  // Less accumulation where the reservoir validity is low (seed 000): a validation ray found
  // moved geometry or changed light there, so history is stale.
  ivec2 g = min(pixel / int(gi.divisor), ivec2(gi.giResolution) - 1);
  float validity = clamp(imageLoad(reservoirValidity, g).x, 0.0, 1.0);
  float maxFrames = max(gi.denoiseMaxHistory * (isFiniteValue(validity) ? validity : 1.0), 1.0);
  // More accumulation where the spatial occlusion validity is low (seed 000): there spatial
  // reuse keeps failing its visibility test, the validated reservoirs boil (pepper noise that
  // gi-restir-patch-reservoir only partly repairs); up to twice the history.
  if ((gi.flags & RESTIR_GI_FLAG_SPATIAL_VALIDATION) != 0u) {
    float occlusion = clamp(imageLoad(occlusionValidity, g).x, 0.0, 1.0);
    if (isFiniteValue(occlusion)) maxFrames *= 2.0 - occlusion;
  }
  float frames = min(history.a + 1.0, maxFrames);
  vec4 result = finiteOrZero(vec4(mix(clipped, value, 1.0 / frames), frames));
  imageStore(current, pixel, result);
  imageStore(outputImage, pixel, vec4(result.rgb, 1.0));
}
