// taa: temporal anti-aliasing of the composite (Karis 2014, "High Quality Temporal
// Supersampling", SIGGRAPH course; Salvi 2016, "An Excursion in Temporal Supersampling", GDC).
// Each frame's primary visibility is shifted by a Halton sub-pixel jitter (pixelRayDirection,
// the raster pass's jittered matrix), so the history, blended over frames, averages the pixel's
// footprint: a box filter, as `bounce reference` integrates each pixel. The history is read
// where gbuffer.velocity (unjittered motion) says the surface was, with a Catmull-Rom filter
// (exact at a zero velocity, so a static view does not blur), clipped towards the current 3x3
// neighbourhood in a perceptual space (so what the history holds from a surface no longer seen
// cannot trail), and blended in linear radiance (so a flat region keeps its mean). No
// sharpening.
#version 460
#extension GL_EXT_samplerless_texture_functions : require
#include "passes/auto_exposure.glsl"
#include "passes/hybrid_frame.glsl"
#include "shared/taa_io.h"

layout(local_size_x = HYBRID_GROUP_SIZE, local_size_y = HYBRID_GROUP_SIZE) in;
layout(push_constant, scalar) uniform Push { TaaConstants pc; };

layout(set = 1, binding = TAA_BINDING_HDR) uniform texture2D hdr;
layout(set = 1, binding = TAA_BINDING_VELOCITY) uniform texture2D velocities;
layout(set = 1, binding = TAA_BINDING_DEPTH) uniform texture2D depths;
layout(set = 1, binding = TAA_BINDING_PREVIOUS) uniform texture2D previous;
layout(set = 1, binding = TAA_BINDING_CURRENT, rgba16f) uniform writeonly image2D current;

bool isFiniteColor(vec3 c) {
  return isFiniteValue(c.r) && isFiniteValue(c.g) && isFiniteValue(c.b);
}

bool inside(FrameConstants f, ivec2 p) {
  return all(greaterThanEqual(p, ivec2(0))) && all(lessThan(p, ivec2(f.resolution)));
}

// ---- the perceptual space ----------------------------------------------------------------------
// The exposed colour through Karis's reversible tone curve x / (1 + Y) (so that one bright
// pixel does not widen its neighbours' clip box to everything), then YCoCg (Malvar & Sullivan
// 2003), whose axes (luma and two chroma differences) fit a neighbourhood's colours in a tighter
// box than RGB's. Y is YCoCg's own luma, so Y < 1 after the curve and the curve inverts.

vec3 rgbToYCoCg(vec3 c) {
  return vec3(0.25 * c.r + 0.5 * c.g + 0.25 * c.b, 0.5 * c.r - 0.5 * c.b,
              -0.25 * c.r + 0.5 * c.g - 0.25 * c.b);
}

vec3 yCoCgToRgb(vec3 c) {
  return vec3(c.x + c.y - c.z, c.x + c.z, c.x - c.y - c.z);
}

vec3 toPerceptual(vec3 radiance, float exposure) {
  vec3 x = max(radiance, vec3(0.0)) * exposure;
  vec3 p = rgbToYCoCg(x);
  return p / (1.0 + p.x);
}

vec3 fromPerceptual(vec3 p, float exposure) {
  p.x = min(p.x, 0.999);
  return max(yCoCgToRgb(p / (1.0 - p.x)), vec3(0.0)) / exposure;
}

float frameExposure(FrameConstants f) {
  float e = pc.exposureState == 0ul ? f.exposure : ExposureStateRef(pc.exposureState).v.exposure;
  return e > 0.0 && isFiniteValue(e) ? e : 1.0;
}

// ---- this frame ----------------------------------------------------------------------------------

struct Neighbourhood {
  vec3 centre;  // this pixel's radiance (0 when not finite)
  vec3 low, high;  // the clip box, perceptual
};

// Variance clipping (Salvi 2016): the box mean +- clipSigma standard deviations of the 3x3
// neighbourhood in the perceptual space, stretched to take in the means of the four 2x2 quads
// around the pixel (averaged in linear radiance, then mapped). Why the stretch: a converged
// history is the linear average of the pixel's footprint, which at an edge lies within the
// range of those quads' averages; at the edge of a bright emitter the curve maps it next to the
// emitter's own value, far above a box of mapped samples, and the clip cut it every frame
// (Cornell: the lamp's ring lost a third of its light, 4 % of the image's; docs/frame.md). Not
// intersected with the min/max box (Karis 2014): on the noisy composite that clips a converged
// history whenever nine samples happen to lie on one side of their mean.
Neighbourhood neighbourhood(FrameConstants f, ivec2 pixel, float exposure) {
  Neighbourhood n;
  n.centre = vec3(0.0);
  vec3 sum = vec3(0.0), sumSq = vec3(0.0);
  vec4 samples[9];  // linear radiance, w 1 where the sample counts
  float count = 0.0;
  for (int k = 0; k < 9; ++k) {
    ivec2 q = pixel + ivec2(k % 3, k / 3) - 1;
    vec3 c = inside(f, q) ? texelFetch(hdr, q, 0).rgb : vec3(0.0);
    bool valid = inside(f, q) && isFiniteColor(c);
    samples[k] = valid ? vec4(c, 1.0) : vec4(0.0);
    if (!valid) continue;
    if (k == 4) n.centre = c;
    vec3 p = toPerceptual(c, exposure);
    sum += p;
    sumSq += p * p;
    count += 1.0;
  }
  if (count == 0.0) {
    n.low = n.high = vec3(0.0);
    return n;
  }
  vec3 mean = sum / count;
  vec3 sigma = sqrt(max(sumSq / count - mean * mean, vec3(0.0)));
  n.low = mean - pc.clipSigma * sigma;
  n.high = mean + pc.clipSigma * sigma;
  for (int corner = 0; corner < 4; ++corner) {  // the quad's top-left sample: 0, 1, 3, 4
    int k = corner + corner / 2;
    vec4 quad = samples[k] + samples[k + 1] + samples[k + 3] + samples[k + 4];
    if (quad.w == 0.0) continue;
    vec3 p = toPerceptual(quad.rgb / quad.w, exposure);
    n.low = min(n.low, p);
    n.high = max(n.high, p);
  }
  return n;
}

// The screen motion of the pixel: gbuffer.velocity of the nearest surface in the 3x3
// neighbourhood (Karis 2014: an edge of a moving object then moves with the object, whose
// history it shows, rather than with the background), or, where only sky is seen, the motion of
// the sky direction through the camera's turn (the GBuffer's sky velocity is zero).
vec2 dilatedVelocity(FrameConstants f, ivec2 pixel) {
  float nearest = 3.0e38;
  ivec2 nearestPixel = ivec2(-1);
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      ivec2 q = pixel + ivec2(dx, dy);
      if (!inside(f, q)) continue;
      float depth = texelFetch(depths, q, 0).x;
      if (depth > 0.0 && depth < nearest) {
        nearest = depth;
        nearestPixel = q;
      }
    }
  if (nearestPixel.x >= 0) return texelFetch(velocities, nearestPixel, 0).xy;
  // A direction is a point at infinity (w = 0): only the camera's rotation moves it.
  vec2 centre = vec2(pixel) + 0.5;
  vec4 clip = f.previousViewProjection * vec4(pixelRayDirection(f, centre), 0.0);
  if (clip.w <= 0.0) return vec2(65504.0);
  return centre - (clip.xy / clip.w * 0.5 + 0.5) * vec2(f.resolution);
}

// ---- the history ---------------------------------------------------------------------------------

// Catmull-Rom weights of the four texels at offsets -1, 0, 1, 2 from the one below the sample
// point, t its fraction (Keys 1981 with a = -0.5): (0, 1, 0, 0) at t = 0.
vec4 catmullRomWeights(float t) {
  return vec4(t * (-0.5 + t * (1.0 - 0.5 * t)), 1.0 + t * t * (-2.5 + 1.5 * t),
              t * (0.5 + t * (2.0 - 1.5 * t)), t * t * (-0.5 + 0.5 * t));
}

// Last frame's anti-aliased radiance at screen position `position` (pixel centres at + 0.5)
// and the frames it averages (w); w = 0 where the position is off screen or the history is not
// finite.
vec4 historyAt(FrameConstants f, vec2 position) {
  ivec2 nearest = ivec2(floor(position));
  if (!inside(f, nearest)) return vec4(0.0);
  vec2 texel = position - 0.5;
  ivec2 base = ivec2(floor(texel));
  vec2 t = texel - vec2(base);
  vec4 wx = catmullRomWeights(t.x), wy = catmullRomWeights(t.y);
  vec3 sum = vec3(0.0);
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) {
      float w = wx[i] * wy[j];
      if (w == 0.0) continue;
      ivec2 q = clamp(base + ivec2(i - 1, j - 1), ivec2(0), ivec2(f.resolution) - 1);
      sum += w * texelFetch(previous, q, 0).rgb;
    }
  float frames = texelFetch(previous, nearest, 0).a;
  if (!isFiniteColor(sum) || !isFiniteValue(frames)) return vec4(0.0);
  return vec4(max(sum, vec3(0.0)), frames);
}

// `h` moved towards the box centre until it is inside the box (Karis 2014's clip, which keeps
// the history's hue better than a per-axis clamp). `distance`: how far out h was, in box
// half-widths along its way to the centre (<= 1: inside).
vec3 clipToBox(vec3 h, vec3 low, vec3 high, out float distance) {
  vec3 centre = 0.5 * (low + high);
  vec3 extent = 0.5 * (high - low) + 1e-6;
  vec3 d = h - centre;
  vec3 ratio = abs(d) / extent;
  distance = max(ratio.x, max(ratio.y, ratio.z));
  return distance > 1.0 ? centre + d / distance : h;
}

void main() {
  FrameConstants f = FrameBlock(pc.frame).v;
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(pixel), f.resolution))) return;
  float exposure = frameExposure(f);
  Neighbourhood n = neighbourhood(f, pixel, exposure);
  vec4 history = pc.historyValid != 0u
                     ? historyAt(f, vec2(pixel) + 0.5 - dilatedVelocity(f, pixel))
                     : vec4(0.0);
  if (history.w < 1.0) {
    imageStore(current, pixel, vec4(n.centre, 1.0));
    return;
  }
  vec3 perceptual = toPerceptual(history.rgb, exposure);
  float distance;
  vec3 inBox = clipToBox(perceptual, n.low, n.high, distance);
  vec3 clipped = inBox == perceptual ? history.rgb : fromPerceptual(inBox, exposure);
  // The first frames of a history average uniformly (1 / frames), then exponentially with
  // weight `blend` (an effective 2 / blend - 1 frames).
  float frames = min(history.w + 1.0, 1.0 / pc.blend);
  // A history far outside the box held another surface or another light (a disocclusion, a
  // ghost): clipped, it is still only near the box's edge, and would fade at `blend` a frame.
  // It is shortened by the square of the distance, as the GI denoiser's anti-lag does.
  if (distance > 1.0) frames = max(min(frames, 1.0 / (pc.blend * distance * distance)), 1.0);
  vec3 blended = mix(clipped, n.centre, 1.0 / frames);
  imageStore(current, pixel, vec4(blended, frames));
}
