// gi-temporal-denoise: a running mean of gi-restir-resolve's output over up to
// denoiseMaxHistory frames, TAA-style: the pixel's position last frame (gbuffer.velocity) is
// looked up in last frame's result where the surface agrees (view depth), and that history is
// clipped so that lighting changes get through within a few frames (seed 000: "reprojection
// with colour clipping").
// What it is clipped to matters: ReSTIR's output is skewed (most pixels a little below the
// mean, a few far above), so a box of mean +- sigma of this frame's neighbourhood sits below
// the converged value, and clipping to it pulls the history down. So, after
// ReLAX's history clamping (NVIDIA NRD): a second, *fast* history of at most FAST_FRAMES
// frames is kept beside the slow one, and the slow history is clipped to the box of the fast
// history's neighbourhood, mean +- denoiseClipSigma standard deviations (variance clipping,
// Salvi 2016): a few frames' mean is far less skewed, and it still follows a change within
// FAST_FRAMES frames. The neighbourhood is 3x3 samples one GI
// pixel apart: adjacent render pixels share reservoirs, so a 3x3 block of them sees about two
// independent values.
// The history length shrinks with the reservoir validity (gi-resolve-diffuse-rays) and grows
// where the spatial occlusion validity is low (gi-trace-spatial-validation-rays). Writes
// gi.diffuse. Nothing non-finite enters history. Outliers are clamped first, their excess shared
// out among their ring (withoutFirefly).
// While the light settles after a reset or a lighting cut (pc.historyScale < 1) the history
// keeps its full length, since a shorter one measured far noisier frames, and the anti-lag
// follows the new light instead: a two-frame fast history and a threshold of the fast
// neighbourhood mean's standard error rather than its spread (docs/gi/restir-gi.md).
#version 460
#extension GL_EXT_samplerless_texture_functions : require
#include "gi/evolve/restir/restir_gi_common.glsl"

layout(local_size_x = RESTIR_GI_GROUP_SIZE, local_size_y = RESTIR_GI_GROUP_SIZE) in;
layout(push_constant, scalar) uniform Push { RestirGiPassConstants pc; };

layout(set = 1, binding = GI_DENOISE_BINDING_INPUT) uniform texture2D inputImage;
layout(set = 1, binding = GI_DENOISE_BINDING_NORMALS, rgba16f) uniform readonly image2D normals;
layout(set = 1, binding = GI_DENOISE_BINDING_DEPTH, r32f) uniform readonly image2D depths;
layout(set = 1, binding = GI_DENOISE_BINDING_PREVIOUS_DEPTH, r32f) uniform readonly image2D previousDepths;
layout(set = 1, binding = GI_DENOISE_BINDING_FLAGS, r32ui) uniform readonly uimage2D flags;
layout(set = 1, binding = GI_DENOISE_BINDING_VELOCITY, rg16f) uniform readonly image2D velocities;
layout(set = 1, binding = GI_DENOISE_BINDING_PREVIOUS) uniform texture2D previous;
layout(set = 1, binding = GI_DENOISE_BINDING_CURRENT, rgba16f) uniform writeonly image2D current;
layout(set = 1, binding = GI_DENOISE_BINDING_OUTPUT, rgba16f) uniform writeonly image2D outputImage;
layout(set = 1, binding = GI_DENOISE_BINDING_VALIDITY, rgba16f) uniform readonly image2D reservoirValidity;
layout(set = 1, binding = GI_DENOISE_BINDING_OCCLUSION_VALIDITY, r16f) uniform readonly image2D occlusionValidity;
layout(set = 1, binding = GI_DENOISE_BINDING_PREVIOUS_FAST) uniform texture2D previousFast;
layout(set = 1, binding = GI_DENOISE_BINDING_CURRENT_FAST, rgba16f) uniform writeonly image2D currentFast;

const float HISTORY_DEPTH_TOLERANCE = 0.03;
const float FAST_FRAMES = 4.0;
// While settling: the fast history's length, and how many times more sensitive the anti-lag is
// (the fast mean's standard error over 3x3 samples is sigma / 3; ReBLUR's anti-lag sensitivity
// is 3 as well, gi10_lux_denoisers.md section 3.2).
const float SETTLE_FAST_FRAMES = 2.0;
const float SETTLE_LAG_SENSITIVITY = 3.0;

DEFINE_NEIGHBOURHOOD_LUMINANCES(reservoirValidity)

// Last frame's pixel under `pixel` when its surface agrees (view depth), else (-1, -1).
ivec2 historyPixel(FrameConstants f, ivec2 pixel) {
  vec2 previousPosition = vec2(pixel) + 0.5 - imageLoad(velocities, pixel).xy;
  ivec2 p = ivec2(floor(previousPosition));
  if (any(lessThan(p, ivec2(0))) || any(greaterThanEqual(p, ivec2(f.resolution)))) return ivec2(-1);
  vec3 position = positionFromDepth(f, vec2(pixel) + 0.5, imageLoad(depths, pixel).x);
  float expectedDepth = (f.previousViewProjection * vec4(position, 1.0)).w;
  float previousDepth = imageLoad(previousDepths, p).x;
  return abs(previousDepth - expectedDepth) <= HISTORY_DEPTH_TOLERANCE * expectedDepth ? p : ivec2(-1);
}

// The anti-firefly clamp (RestirGiSettings::fireflyRatio): a pixel whose luminance exceeds
// fireflyRatio x the brightest of its ring (the 8 values two GI pixels away: far enough that
// one reservoir's sample, which the resolve spreads over a few pixels, is not in its own ring)
// is clamped to that limit, and what the clamp cuts is shared out among that ring's pixels,
// so that the clamp moves energy instead of removing it. The samples it cuts (reconnection
// shifts with a large Jacobian along concave edges) are a real part of the mean: cutting them
// darkened the white furnace by 2-4 % (docs/gi/restir-gi.md, "Energy").
// Ring members are the pixels inside the image with a positive value (surfaces: the resolve
// writes 0 elsewhere); a pixel p receives from each ring pixel q that was clamped (q's ring
// holds p, so only q brighter than fireflyRatio x p can be; only those rings are read) an equal
// share of q's excess.
const int RING = 8;

ivec2 ringOffset(int k) {
  int i = k < 4 ? k : k + 1;  // the 3x3 block without its centre
  return ivec2(i % 3 - 1, i / 3 - 1);
}

bool insideImage(FrameConstants f, ivec2 q) {
  return all(greaterThanEqual(q, ivec2(0))) && all(lessThan(q, ivec2(f.resolution)));
}

vec3 inputAt(FrameConstants f, ivec2 q) {
  return insideImage(f, q) ? finiteOrZero(texelFetch(inputImage, q, 0)).rgb : vec3(0.0);
}

// q's clamp: its excess colour over fireflyRatio x the brightest of its ring, and the number
// of members of that ring.
vec3 excessOf(FrameConstants f, RestirGiConstants gi, ivec2 q, vec3 value, int stride,
              out float members) {
  float brightest = 0.0;
  members = 0.0;
  for (int k = 0; k < RING; ++k) {
    ivec2 r = q + stride * ringOffset(k);
    if (!insideImage(f, r)) continue;
    float l = brdfLuminance(inputAt(f, r));
    brightest = max(brightest, l);
    members += l > 0.0 ? 1.0 : 0.0;
  }
  float luminance = brdfLuminance(value);
  float limit = gi.fireflyRatio * brightest;
  return luminance > limit && brightest > 0.0 ? value * (1.0 - limit / luminance) : vec3(0.0);
}

vec3 withoutFirefly(FrameConstants f, RestirGiConstants gi, ivec2 pixel, vec3 value) {
  if (!(gi.fireflyRatio > 1.0)) return value;
  int stride = 2 * int(gi.divisor);
  // The ring's luminances, read once: this pixel's own clamp and the test of which ring pixels
  // were clamped (brighter than fireflyRatio x this one) both use them.
  float ring[RING];
  float brightest = 0.0;
  for (int k = 0; k < RING; ++k) {
    ring[k] = brdfLuminance(inputAt(f, pixel + stride * ringOffset(k)));
    brightest = max(brightest, ring[k]);
  }
  float own = brdfLuminance(value);
  float limit = gi.fireflyRatio * brightest;
  vec3 result = own > limit && brightest > 0.0 ? value * (limit / own) : value;
  if (!(own > 0.0) || !(brightest > gi.fireflyRatio * own)) return result;
  // Rare: a ring pixel bright enough to have been clamped; its ring is read again. Not unrolled,
  // so that its eight copies do not cost every pixel registers.
  [[dont_unroll]] for (int k = 0; k < RING; ++k) {
    if (!(ring[k] > gi.fireflyRatio * own)) continue;  // q's ring holds this pixel
    ivec2 q = pixel + stride * ringOffset(k);
    float members;
    vec3 excess = excessOf(f, gi, q, inputAt(f, q), stride, members);
    if (members > 0.0) result += excess / members;
  }
  return result;
}

struct ClipBox {
  vec3 low, high;
  vec3 sigma;  // of the fast history's neighbourhood
};

// The box of the fast history around last frame's pixel p (stride: one GI pixel), with this
// frame's fast value `centre` in it.
ClipBox fastHistoryBox(FrameConstants f, RestirGiConstants gi, ivec2 p, vec3 centre) {
  vec3 mean = centre, meanSq = centre * centre;
  float n = 1.0;
  int stride = int(gi.divisor);
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      if (dx == 0 && dy == 0) continue;
      ivec2 q = p + stride * ivec2(dx, dy);
      if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, ivec2(f.resolution)))) continue;
      vec4 c = finiteOrZero(texelFetch(previousFast, q, 0));
      if (!(c.a > 0.0)) continue;  // no history there (sky, disocclusion)
      mean += c.rgb;
      meanSq += c.rgb * c.rgb;
      n += 1.0;
    }
  mean /= n;
  vec3 sigma = sqrt(max(meanSq / n - mean * mean, vec3(0.0)));
  return ClipBox(mean - gi.denoiseClipSigma * sigma, mean + gi.denoiseClipSigma * sigma, sigma);
}

void main() {
  FrameConstants f = FrameBlock(pc.frame).v;
  RestirGiConstants gi = RestirGiBlock(pc.gi).v;
  bool settling = pc.historyScale < 1.0;  // after a reset or a lighting cut
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(pixel), f.resolution))) return;
  if ((imageLoad(flags, pixel).x & GBUFFER_FLAG_SURFACE) == 0u) {
    imageStore(current, pixel, vec4(0.0));
    imageStore(currentFast, pixel, vec4(0.0));
    imageStore(outputImage, pixel, vec4(0.0));
    return;
  }
  vec3 value = withoutFirefly(f, gi, pixel, finiteOrZero(texelFetch(inputImage, pixel, 0)).rgb);
  vec4 history = vec4(0.0), fastHistory = vec4(0.0);
  ivec2 p = ivec2(-1);
  if (pc.historyValid != 0u && (gi.flags & RESTIR_GI_FLAG_DENOISE) != 0u) p = historyPixel(f, pixel);
  if (p.x >= 0) {
    history = finiteOrZero(texelFetch(previous, p, 0));
    fastHistory = finiteOrZero(texelFetch(previousFast, p, 0));
  }
  float fastFrames = min(fastHistory.a + 1.0, settling ? SETTLE_FAST_FRAMES : FAST_FRAMES);
  vec3 fast = mix(fastHistory.rgb, value, 1.0 / fastFrames);
  imageStore(currentFast, pixel, finiteOrZero(vec4(fast, fastFrames)));
  vec3 clipped = history.rgb;
  float lag = 0.0;  // how far the slow history is from the fast one, in fast standard deviations
  if (p.x >= 0) {
    ClipBox box = fastHistoryBox(f, gi, p, fast);
    clipped = clamp(history.rgb, box.low, box.high);
    float sensitivity = settling ? SETTLE_LAG_SENSITIVITY : 1.0;
    float drift = abs(brdfLuminance(history.rgb - fast));
    lag = sensitivity * drift / max(brdfLuminance(box.sigma), 1e-4);
  }
  // Less accumulation where the reservoir validity is low (seed 000): a validation ray found
  // moved geometry or changed light there, so history is stale.
  ivec2 g = min(pixel / int(gi.divisor), ivec2(gi.giResolution) - 1);
  vec4 validation = imageLoad(reservoirValidity, g);
  float validity = clamp(validation.x, 0.0, 1.0);
  if (validation.y > 0.5) {  // a validated pixel: also the neighbourhood's radiance change
    vec2 sums = neighbourhoodLuminances(gi, g);
    validity *= radianceValidity(gi, sums.x, sums.y);
  }
  float maxFrames = max(gi.denoiseMaxHistory * (isFiniteValue(validity) ? validity : 1.0), 1.0);
  // More accumulation where the spatial occlusion validity is low (seed 000): there spatial
  // reuse keeps failing its visibility test, the validated reservoirs boil (pepper noise that
  // gi-restir-patch-reservoir only partly repairs); up to twice the history. Not while settling:
  // there the history must follow the light.
  if ((gi.flags & RESTIR_GI_FLAG_SPATIAL_VALIDATION) != 0u && !settling) {
    float occlusion = clamp(imageLoad(occlusionValidity, g).x, 0.0, 1.0);
    if (isFiniteValue(occlusion)) maxFrames *= 2.0 - occlusion;
  }
  // Anti-lag (after ReLAX): where the slow history has drifted from the fast one by more than
  // the fast neighbourhood's noise, the light changed: the slow history shortens in proportion.
  if (lag > 1.0) maxFrames = max(maxFrames / (lag * lag), min(FAST_FRAMES, maxFrames));
  float frames = min(history.a + 1.0, maxFrames);
  vec4 result = finiteOrZero(vec4(mix(clipped, value, 1.0 / frames), frames));
  imageStore(current, pixel, result);
  imageStore(outputImage, pixel, vec4(result.rgb, 1.0));
}
