// shadows-denoise: brings the shadow pixels to full resolution and averages them over time.
//   1. Joint bilateral upsample (Kopf et al. 2007, "Joint Bilateral Upsampling"): the four
//      nearest shadow pixels, bilinear weights times how well each one's surface agrees with
//      this pixel's (distance to this pixel's tangent plane, normal similarity), so shadows do
//      not bleed across depth or orientation edges.
//   2. Temporal accumulation: the pixel's position last frame (velocity) is looked up in last
//      frame's result, bilinearly over the four texels there that saw the same surface (view
//      depth agrees); the new value joins a running mean of up to shadowMaxHistory frames, or
//      the history restarts where no texel agrees.
//      Where the view moved, the history is first clamped to the range of this frame's
//      upsampled visibility in the 3x3 pixels around (a workgroup's tile of it in shared
//      memory): reprojection resamples a point-sampled shadow edge, and over a long history
//      the error piled up into a trail of old light beside every edge (sunroom, a 48-frame
//      dolly: 28x the error of no accumulation; docs/frame.md). The same where a moving
//      object's shadow crosses pixels that stand still (docs/frame.md, "Moving casters"): near
//      a shadow sample whose blocker moved this frame (shadows-trace's flag), and where objects
//      moved and the history lies more than SCENE_MOTION_MARGIN outside the range (a shadow
//      that left). Otherwise a still view is not clamped, so a noisy soft penumbra keeps its
//      running mean. Nothing non-finite is ever stored.
#version 460
#extension GL_EXT_samplerless_texture_functions : require
#include "passes/hybrid_frame.glsl"

layout(local_size_x = HYBRID_GROUP_SIZE, local_size_y = HYBRID_GROUP_SIZE) in;
layout(push_constant, scalar) uniform Push { HybridPassConstants pc; };

layout(set = 1, binding = SHADOWS_DENOISE_BINDING_RAW) uniform texture2D raw;
layout(set = 1, binding = SHADOWS_DENOISE_BINDING_NORMALS) uniform texture2D normals;
layout(set = 1, binding = SHADOWS_DENOISE_BINDING_DEPTH) uniform texture2D depths;
layout(set = 1, binding = SHADOWS_DENOISE_BINDING_FLAGS) uniform utexture2D flags;
layout(set = 1, binding = SHADOWS_DENOISE_BINDING_VELOCITY) uniform texture2D velocities;
layout(set = 1, binding = SHADOWS_DENOISE_BINDING_PREVIOUS_DEPTH) uniform texture2D previousDepths;
layout(set = 1, binding = SHADOWS_DENOISE_BINDING_PREVIOUS) uniform texture2D previous;
layout(set = 1, binding = SHADOWS_DENOISE_BINDING_CURRENT, rg16f) uniform writeonly image2D current;

// How far (relative to view depth) a neighbour may sit off this pixel's tangent plane, and how
// far last frame's depth may differ, before they count as another surface.
const float PLANE_TOLERANCE = 0.01;
const float HISTORY_DEPTH_TOLERANCE = 0.03;
const float NORMAL_POWER = 8.0;
// Below this screen motion (pixels a frame) the view counts as still: no motion clamp.
const float STILL_PIXELS = 0.01;
// Where objects moved but this pixel did not: how far outside this frame's 3x3 range the history
// must lie to be clamped without a moved blocker near (nine samples of a soft penumbra often
// agree; clamping to them darkened foliage's soft shadows: docs/frame.md).
const float SCENE_MOTION_MARGIN = 0.5;

struct GSample {
  vec3 position;
  vec3 normal;
  float depth;
  bool surface;
};

GSample loadGSample(FrameConstants f, ivec2 pixel) {
  GSample s;
  s.surface = (texelFetch(flags, pixel, 0).x & GBUFFER_FLAG_SURFACE) != 0u;
  s.depth = texelFetch(depths, pixel, 0).x;
  s.normal = decodeOctahedral(texelFetch(normals, pixel, 0).zw);
  s.position = positionFromDepth(f, vec2(pixel) + 0.5, s.depth);
  return s;
}

// Must match shadows_trace.comp.
ivec2 fullResPixel(FrameConstants f, ivec2 shadowPixel) {
  ivec2 p = shadowPixel * int(f.shadowDivisor) + int(f.shadowDivisor / 2u);
  return min(p, ivec2(f.resolution) - 1);
}

// The joint bilateral upsample of the visibility (x) and whether any of its four shadow samples
// has a moved blocker (y).
vec2 upsampledVisibility(FrameConstants f, ivec2 pixel, GSample here) {
  float d = float(f.shadowDivisor);
  vec2 u = (vec2(pixel) - float(f.shadowDivisor / 2u)) / d;
  ivec2 base = ivec2(floor(u));
  vec2 t = u - vec2(base);
  ivec2 maxShadow = ivec2(f.shadowResolution) - 1;
  float sum = 0.0, weightSum = 0.0;
  float nearestValue = 1.0, nearestDistance = 3.0e38, movedBlocker = 0.0;
  for (int k = 0; k < 4; ++k) {
    ivec2 offset = ivec2(k & 1, k >> 1);
    ivec2 tap = clamp(base + offset, ivec2(0), maxShadow);
    GSample s = loadGSample(f, fullResPixel(f, tap));
    if (!s.surface) continue;
    vec2 sampled = texelFetch(raw, tap, 0).xy;
    float value = sampled.x;
    movedBlocker = max(movedBlocker, sampled.y);
    float planeDistance = abs(dot(here.normal, s.position - here.position)) / max(here.depth, 1e-6);
    float bilinear = (offset.x == 1 ? t.x : 1.0 - t.x) * (offset.y == 1 ? t.y : 1.0 - t.y);
    float w = bilinear * exp(-planeDistance / PLANE_TOLERANCE) *
              pow(max(dot(here.normal, s.normal), 0.0), NORMAL_POWER);
    sum += w * value;
    weightSum += w;
    if (planeDistance < nearestDistance) {
      nearestDistance = planeDistance;
      nearestValue = value;
    }
  }
  // No neighbour shares this surface (a thin feature): the most similar one is the best guess.
  return vec2(weightSum > 1e-4 ? sum / weightSum : nearestValue, movedBlocker);
}

// Last frame's (visibility, frames) where it saw this surface, else (0, 0): bilinear over the
// four texels around the reprojected position whose view depth agrees, renormalised.
vec2 reprojectedHistory(FrameConstants f, ivec2 pixel, GSample here) {
  if (pc.historyValid == 0u) return vec2(0.0);
  vec2 base = vec2(pixel) - texelFetch(velocities, pixel, 0).xy;  // the position minus half a texel
  float expectedDepth = (f.previousViewProjection * vec4(here.position, 1.0)).w;
  ivec2 p0 = ivec2(floor(base));
  vec2 t = base - vec2(p0);
  vec2 sum = vec2(0.0);
  float weightSum = 0.0;
  for (int k = 0; k < 4; ++k) {
    ivec2 offset = ivec2(k & 1, k >> 1);
    ivec2 p = p0 + offset;
    float w = (offset.x == 1 ? t.x : 1.0 - t.x) * (offset.y == 1 ? t.y : 1.0 - t.y);
    if (w <= 0.0 || any(lessThan(p, ivec2(0))) || any(greaterThanEqual(p, ivec2(f.resolution)))) continue;
    float previousDepth = texelFetch(previousDepths, p, 0).x;
    if (abs(previousDepth - expectedDepth) > HISTORY_DEPTH_TOLERANCE * expectedDepth) continue;
    vec2 history = texelFetch(previous, p, 0).xy;
    if (!isFiniteValue(history.x) || !isFiniteValue(history.y)) continue;
    sum += w * history;
    weightSum += w;
  }
  return weightSum > 1e-3 ? sum / weightSum : vec2(0.0);
}

// This frame's upsampled visibility of the workgroup's 8x8 pixels and a 1-pixel apron (-1: no
// surface or outside the image), for the motion clamp.
const int TILE = int(HYBRID_GROUP_SIZE) + 2;
shared float tileVisibility[TILE * TILE];
shared bool tileMovedBlocker[TILE * TILE];

// Every invocation of the workgroup calls this (it ends in a barrier), before any return.
void upsampleTile(FrameConstants f) {
  ivec2 origin = ivec2(gl_WorkGroupID.xy) * int(HYBRID_GROUP_SIZE) - 1;
  for (uint i = gl_LocalInvocationIndex; i < uint(TILE * TILE); i += HYBRID_GROUP_SIZE * HYBRID_GROUP_SIZE) {
    ivec2 q = origin + ivec2(int(i) % TILE, int(i) / TILE);
    vec2 v = vec2(-1.0, 0.0);
    if (all(greaterThanEqual(q, ivec2(0))) && all(lessThan(q, ivec2(f.resolution)))) {
      GSample s = loadGSample(f, q);
      if (s.surface) v = upsampledVisibility(f, q, s);
      if (!isFiniteValue(v.x)) v.x = 0.0;
    }
    tileVisibility[i] = v.x;
    tileMovedBlocker[i] = v.y > 0.0;
  }
  barrier();
}

// The range of the tile's visibility in the 3x3 pixels around this one (surfaces only), and
// whether a shadow sample under them has a moved blocker.
vec2 neighbourhoodRange(out bool movedBlocker) {
  ivec2 local = ivec2(gl_LocalInvocationID.xy) + 1;
  vec2 range = vec2(1.0, 0.0);
  movedBlocker = false;
  for (int k = 0; k < 9; ++k) {
    int i = (local.y + k / 3 - 1) * TILE + local.x + k % 3 - 1;
    float v = tileVisibility[i];
    if (v >= 0.0) range = vec2(min(range.x, v), max(range.y, v));
    movedBlocker = movedBlocker || tileMovedBlocker[i];
  }
  return range;
}

void main() {
  FrameConstants f = FrameBlock(pc.frame).v;
  upsampleTile(f);
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(pixel), f.resolution))) return;
  GSample here = loadGSample(f, pixel);
  if (!here.surface) {
    imageStore(current, pixel, vec4(1.0, 0.0, 0.0, 0.0));
    return;
  }
  ivec2 local = ivec2(gl_LocalInvocationID.xy) + 1;
  float visibility = tileVisibility[local.y * TILE + local.x];
  vec2 history = reprojectedHistory(f, pixel, here);
  bool viewMoved = length(texelFetch(velocities, pixel, 0).xy) > STILL_PIXELS;
  bool sceneMoved = (f.flags & FRAME_FLAG_SCENE_MOVED) != 0u;
  if (viewMoved || sceneMoved) {
    bool movedBlocker;
    vec2 range = neighbourhoodRange(movedBlocker);
    float clamped = clamp(history.x, range.x, range.y);
    if (viewMoved || movedBlocker || abs(clamped - history.x) > SCENE_MOTION_MARGIN) history.x = clamped;
  }
  float frames = min(history.y + 1.0, max(f.shadowMaxHistory, 1.0));
  float accumulated = mix(history.x, visibility, 1.0 / frames);
  imageStore(current, pixel, vec4(clamp(accumulated, 0.0, 1.0), frames, 0.0, 0.0));
}
