// reflections-denoise-temporal (DESIGN.md §4 step 6; docs/reflections.md): a running mean of the
// demodulated reflection signal at the traced resolution.
//   - Reprojection. A reflection seen in a smooth surface moves on screen like its virtual
//     image point, camera + view ray x (surface distance + hit distance), which lies behind the
//     mirror, not like the surface (the parallax of a reflection: Frostbite's and NRD ReBLUR's
//     "virtual motion"). Below virtualRoughnessLimit a share 1 - roughness / limit of the
//     history is read where that point was last frame (previousViewProjection, plus the
//     surface's own object motion from gbuffer.velocity); the rest where the surface was
//     (gbuffer.velocity). A wide lobe's hit distance says little about what it sees, so rough
//     surfaces use the surface alone. Each lookup is bilinear over the four traced pixels around
//     the point, each counted only where the surface it kept (reflections.temporal-surface)
//     agrees with this pixel's in plane, normal and roughness; where none does, history
//     restarts (disocclusion).
//   - Length. At most maxHistoryFrames(roughness) frames: short for mirrors, long for glossy.
//   - Lag. A fast history (at most fastHistoryFrames) is kept beside the slow one; where the
//     neighbours' slow histories differ from their fast ones beyond their noise, this pixel's
//     slow history restarts from its fast one (slowHistoryLags); where the history was
//     reprojected from elsewhere, it is clamped into the neighbourhood's fast range.
//   - Ghosts. History is cut to responsiveFrames where the 8 neighbours' fresh samples differ
//     from the 8 neighbours' histories by more than ghostSigma standard errors: what the
//     reflection shows has changed. The pixel's own sample and history take no part in the
//     test, so the decision is independent of them and the running mean stays unbiased.
//   - Reflection-space disocclusion. Where the view moved, a history pixel counts only if it
//     reflects what the pixel's neighbours reflect now, at the same parallax
//     (reflectsTheSameDepth).
//   - Nothing non-finite enters history: NaN/Inf samples count as no sample, non-finite history
//     as no history.
#version 460
#extension GL_EXT_samplerless_texture_functions : require
#include "passes/hybrid_frame.glsl"
#include "shared/reflections_denoise_io.h"

layout(local_size_x = HYBRID_GROUP_SIZE, local_size_y = HYBRID_GROUP_SIZE) in;
layout(push_constant, scalar) uniform Push { ReflectionDenoiseConstants pc; };

#include "passes/reflections_denoise.glsl"
#include "passes/reflection_parallax.glsl"

layout(set = 1, binding = REFLECTIONS_DENOISE_TEMPORAL_BINDING_TRACED) uniform texture2D traced;
layout(set = 1, binding = REFLECTIONS_DENOISE_TEMPORAL_BINDING_NORMALS) uniform texture2D normals;
layout(set = 1, binding = REFLECTIONS_DENOISE_TEMPORAL_BINDING_DEPTH) uniform texture2D depths;
layout(set = 1, binding = REFLECTIONS_DENOISE_TEMPORAL_BINDING_EMISSIVE) uniform texture2D emissives;
layout(set = 1, binding = REFLECTIONS_DENOISE_TEMPORAL_BINDING_FLAGS) uniform utexture2D flags;
layout(set = 1, binding = REFLECTIONS_DENOISE_TEMPORAL_BINDING_VELOCITY) uniform texture2D velocities;
layout(set = 1, binding = REFLECTIONS_DENOISE_TEMPORAL_BINDING_PREVIOUS) uniform texture2D previous;
layout(set = 1, binding = REFLECTIONS_DENOISE_TEMPORAL_BINDING_PREVIOUS_MOMENTS) uniform texture2D previousMoments;
layout(set = 1, binding = REFLECTIONS_DENOISE_TEMPORAL_BINDING_PREVIOUS_SURFACE) uniform texture2D previousSurface;
layout(set = 1, binding = REFLECTIONS_DENOISE_TEMPORAL_BINDING_CURRENT, rgba16f) uniform writeonly image2D current;
layout(set = 1, binding = REFLECTIONS_DENOISE_TEMPORAL_BINDING_CURRENT_MOMENTS, rgba32f) uniform writeonly image2D currentMoments;
layout(set = 1, binding = REFLECTIONS_DENOISE_TEMPORAL_BINDING_CURRENT_SURFACE, rgba32f) uniform writeonly image2D currentSurface;
layout(set = 1, binding = REFLECTIONS_DENOISE_TEMPORAL_BINDING_PREVIOUS_FAST) uniform texture2D previousFast;
layout(set = 1, binding = REFLECTIONS_DENOISE_TEMPORAL_BINDING_CURRENT_FAST, rgba16f) uniform writeonly image2D currentFast;
layout(set = 1, binding = REFLECTIONS_DENOISE_TEMPORAL_BINDING_CANDIDATE_SAMPLE) uniform texture2D candidateSample;
layout(set = 1, binding = REFLECTIONS_DENOISE_TEMPORAL_BINDING_CANDIDATE_ORIGIN) uniform texture2D candidateOrigin;

// The surface a traced pixel stands for (its full-res GBuffer pixel).
DenoiseSurface loadSurface(FrameConstants f, ivec2 tracedPixel) {
  ivec2 p = fullResPixel(f, tracedPixel);
  DenoiseSurface s;
  s.roughness = -1.0;
  s.viewDepth = texelFetch(depths, p, 0).x;
  s.normal = decodeOctahedral(texelFetch(normals, p, 0).xy);
  s.position = positionFromDepth(f, vec2(p) + 0.5, s.viewDepth);
  if ((texelFetch(flags, p, 0).x & GBUFFER_FLAG_SURFACE) != 0u && s.viewDepth > 0.0)
    s.roughness = clamp(texelFetch(emissives, p, 0).w, 0.0, 1.0);
  return s;
}

bool isFiniteVec(vec4 v) { return isFiniteValue(v.x) && isFiniteValue(v.y) && isFiniteValue(v.z) && isFiniteValue(v.w); }

// Tests only (REFLECTION_DENOISE_FLAG_POISON_INPUT): every 5th sample NaN or Inf, by turns in
// the signal and in the hit distance.
vec4 poisoned(FrameConstants f, ivec2 q, vec4 value) {
  uint index = uint(q.x) + uint(q.y) * pc.tracedResolution.x + f.frameIndex;
  if (index % REFLECTION_DENOISE_POISON_PERIOD != 0u) return value;
  float nan = uintBitsToFloat(0x7fc00000u), inf = uintBitsToFloat(0x7f800000u);
  switch ((index / REFLECTION_DENOISE_POISON_PERIOD) % 3u) {
    case 0u: return vec4(nan, value.gb, value.w);
    case 1u: return vec4(value.r, inf, value.b, value.w);
    default: return vec4(value.rgb, nan);
  }
}

// This frame's sample at traced pixel q; false where there is none (no ray, or a non-finite
// value: sanitized here, so nothing non-finite goes further).
bool freshSample(FrameConstants f, ivec2 q, out vec4 value) {
  value = texelFetch(traced, q, 0);
  if ((pc.flags & REFLECTION_DENOISE_FLAG_POISON_INPUT) != 0u) value = poisoned(f, q, value);
  if (!isFiniteVec(value) || value.w == REFLECTION_NO_SAMPLE || value.w < 0.0) return false;
  value.rgb = max(value.rgb, vec3(0.0));
  return true;
}

struct History {
  vec3 signal;
  vec3 fast;  // the fast history's running mean (fastHistoryFrames)
  float hitDistance;
  float secondMoment;  // of luminance
  float parallax;      // hit distance / (surface distance + hit distance); a miss: 1
  float frames;
  float weight;  // 0: no history
};

History noHistory() { return History(vec3(0.0), vec3(0.0), 0.0, 0.0, 0.0, 0.0, 0.0); }

// Last frame's history at traced pixel q if it belongs to `here`'s surface (weight 1), else
// none.
History historyAt(DenoiseSurface here, ivec2 q) {
  if (!insideTraced(q) || !sameSurface(here, texelFetch(previousSurface, q, 0))) return noHistory();
  vec4 value = texelFetch(previous, q, 0);
  vec4 moments = texelFetch(previousMoments, q, 0);
  vec4 fast = texelFetch(previousFast, q, 0);
  if (!isFiniteVec(value) || !isFiniteVec(moments) || !isFiniteVec(fast) || moments.y <= 0.0 || value.w < 0.0) return noHistory();
  return History(max(value.rgb, vec3(0.0)), max(fast.rgb, vec3(0.0)), value.w, max(moments.x, 0.0), clamp(moments.z, 0.0, 1.0), moments.y, 1.0);
}

void addHistory(inout History sum, History h, float weight) {
  sum.signal += weight * h.signal;
  sum.fast += weight * h.fast;
  sum.hitDistance += weight * h.hitDistance;
  sum.secondMoment += weight * h.secondMoment;
  sum.parallax += weight * h.parallax;
  sum.frames += weight * h.frames;
  sum.weight += weight;
}

History normalized(History sum) {
  if (sum.weight <= 1e-4) return noHistory();
  float w = sum.weight;
  return History(sum.signal / w, sum.fast / w, sum.hitDistance / w, sum.secondMoment / w, sum.parallax / w, sum.frames / w, 1.0);
}

// Whether history h reflected what this frame's rays around the pixel reflect, whose mean
// parallax is `parallax` (negative: not tested). On a flat glossy floor every pixel passes the
// surface tests, so next to the edge of an object's reflection the reprojection lands on history
// that saw something else, at another depth: a disocclusion in the reflected scene. Tested only
// where the view moved (on a still view it would cut the histories of pixels whose rays hit at
// two depths, for nothing), and not against a 1-frame history, itself a single sample.
bool reflectsTheSameDepth(History h, float parallax) {
  if (parallax < 0.0 || pc.motionParallaxTolerance <= 0.0 || h.frames < 2.0) return true;
  return abs(parallax - h.parallax) <= pc.motionParallaxTolerance;
}

// Continuous traced-pixel coordinates of a full-res screen position (pixel centres at + 0.5):
// traced pixel t stands for full-res pixel t d + d / 2.
vec2 tracedCoordinates(vec2 screen) { return (screen - 0.5 - float(pc.divisor / 2u)) / float(pc.divisor); }

// History at a full-res screen position of last frame: bilinear over the four traced pixels
// around it, renormalised over those on this surface that reflect the same depth.
History bilinearHistory(DenoiseSurface here, vec2 screen, float parallax) {
  vec2 u = tracedCoordinates(screen);
  ivec2 base = ivec2(floor(u));
  vec2 t = u - vec2(base);
  History sum = noHistory();
  for (int k = 0; k < 4; ++k) {
    ivec2 offset = ivec2(k & 1, k >> 1);
    float bilinear = (offset.x == 1 ? t.x : 1.0 - t.x) * (offset.y == 1 ? t.y : 1.0 - t.y);
    History h = historyAt(here, base + offset);
    if (h.weight > 0.0 && reflectsTheSameDepth(h, parallax)) addHistory(sum, h, bilinear + 1e-3);
  }
  return normalized(sum);
}

// Where a world point was on last frame's screen (full-res pixels, centres at + 0.5), false
// behind the camera.
bool previousScreenPosition(FrameConstants f, vec3 x, out vec2 screen) {
  vec4 clip = f.previousViewProjection * vec4(x, 1.0);
  screen = (clip.xy / max(clip.w, 1e-6) * 0.5 + 0.5) * vec2(f.resolution);
  return clip.w > 0.0;
}

// The two reprojections: where the surface was (gbuffer.velocity: camera and object motion) and
// where the reflected virtual image point was (its camera motion through
// previousViewProjection, plus the surface's object motion: a moving mirror carries its
// reflection along). `hasVirtual` is false without a hit distance.
struct Reprojection {
  vec2 surface;
  vec2 virtualPoint;
  bool hasVirtual;
};

// The surface's curvature 1 / radius (positive convex, as a ball seen from outside; negative
// concave), the mean of dot(n' - n, x' - x) / |x' - x|^2 over the four neighbours on a similar
// surface: exactly 1 / R on a sphere of radius R, 0 on a plane.
float surfaceCurvature(FrameConstants f, ivec2 tracedPixel, DenoiseSurface here) {
  float sum = 0.0, count = 0.0;
  for (int k = 0; k < 4; ++k) {
    ivec2 q = tracedPixel + ivec2(k == 0 ? 1 : (k == 1 ? -1 : 0), k == 2 ? 1 : (k == 3 ? -1 : 0));
    if (!insideTraced(q)) continue;
    DenoiseSurface s = loadSurface(f, q);
    vec3 dx = s.position - here.position;
    float d2 = dot(dx, dx);
    if (!hasSurface(s) || abs(s.roughness - here.roughness) > pc.roughnessTolerance || dot(s.normal, here.normal) < 0.5 ||
        d2 > pow(0.1 * here.viewDepth, 2.0) || d2 <= 0.0)
      continue;
    sum += dot(s.normal - here.normal, dx) / d2;
    count += 1.0;
  }
  return count > 0.0 ? sum / count : 0.0;
}

// How far behind the surface the reflection's virtual image lies. A plane mirror images a point
// at hit distance h at h behind it; a curved one (focal length R / 2) by the mirror equation
// 1 / s_o + 1 / s_i = 2 / R at h / (1 + 2 h / R) for a ball (curvature 1 / R > 0: at most R / 2
// behind the surface, however far the hit) and further for a concave mirror, whose image of a
// point beyond its focus is real and in front: there the surface's motion is the better guess
// (NRD ReBLUR's "thin lens" correction of virtual motion does the same).
float virtualImageDistance(float hitDistance, float curvature) {
  float denominator = 1.0 + 2.0 * curvature * hitDistance;
  return denominator > 0.05 ? hitDistance / denominator : 0.0;
}

Reprojection reproject(FrameConstants f, ivec2 tracedPixel, DenoiseSurface here, float hitDistance) {
  ivec2 p = fullResPixel(f, tracedPixel);
  Reprojection r;
  r.surface = vec2(p) + 0.5 - texelFetch(velocities, p, 0).xy;
  r.hasVirtual = false;
  r.virtualPoint = r.surface;
  vec2 cameraOnly;
  if (hitDistance < 0.0 || !previousScreenPosition(f, here.position, cameraOnly)) return r;
  vec3 toSurface = here.position - f.camera.position;
  float surfaceDistance = length(toSurface);
  float behind = virtualImageDistance(hitDistance, surfaceCurvature(f, tracedPixel, here));
  vec3 virtualPoint = f.camera.position + toSurface / max(surfaceDistance, 1e-9) * (surfaceDistance + behind);
  vec2 virtualScreen;
  if (!previousScreenPosition(f, virtualPoint, virtualScreen)) return r;
  r.virtualPoint = virtualScreen + (r.surface - cameraOnly);
  r.hasVirtual = true;
  return r;
}

// The virtual image point's share of the history (ReflectionDenoiseSettings::
// virtualRoughnessLimit).
float virtualShare(float roughness) {
  return pc.virtualRoughnessLimit > 0.0 ? clamp(1.0 - roughness / pc.virtualRoughnessLimit, 0.0, 1.0) : 0.0;
}

// Last frame's history for this pixel: the virtual and the surface lookups blended by the
// virtual share, renormalised over those that found this surface. `parallax`: the neighbours'
// rays' where the view moved, else negative (reflectsTheSameDepth).
History reprojectedHistory(DenoiseSurface here, Reprojection r, float parallax) {
  History surface = bilinearHistory(here, r.surface, parallax);
  float share = r.hasVirtual ? virtualShare(here.roughness) : 0.0;
  History virtualHistory = share > 0.0 ? bilinearHistory(here, r.virtualPoint, parallax) : noHistory();
  History sum = noHistory();
  if (virtualHistory.weight > 0.0) addHistory(sum, virtualHistory, share);
  if (surface.weight > 0.0) addHistory(sum, surface, 1.0 - share);
  return normalized(sum);
}

// The ghost test: has what the neighbourhood reflects changed? Each of the 8 neighbours q with
// a fresh sample is paired with last frame's history at the same offset around `screen` (where
// this pixel was), when that history belongs to q's surface; the mean of fresh - history over
// the pairs is zero for a static signal, with variance sum(v (1 + 1 / N)) / n^2, v each
// history's per-sample variance (second moment - mean^2: it has seen the rare fireflies that 8
// fresh samples miss) and N its length. Pairing the same pixels cancels what varies across the
// neighbourhood (a curved mirror's reflection), which a comparison with this pixel's own value
// would take for change. A mean difference beyond ghostSigma of its standard error, and beyond
// 1 % of the signal (fp16 round-off), cuts.
bool neighbourhoodChanged(FrameConstants f, ivec2 tracedPixel, vec2 screen) {
  if (pc.ghostSigma <= 0.0) return false;
  ivec2 centre = ivec2(floor(tracedCoordinates(screen) + 0.5));
  float difference = 0.0, variance = 0.0, level = 0.0, n = 0.0;
  for (int k = 0; k < 9; ++k) {
    ivec2 d = ivec2(k % 3 - 1, k / 3 - 1);
    ivec2 q = tracedPixel + d;
    vec4 value;
    if (d == ivec2(0) || !insideTraced(q) || !freshSample(f, q, value)) continue;
    History h = historyAt(loadSurface(f, q), centre + d);
    if (h.weight <= 0.0) continue;
    float fresh = brdfLuminance(value.rgb), history = brdfLuminance(h.signal);
    difference += fresh - history;
    variance += max(h.secondMoment - history * history, 0.0) * (1.0 + 1.0 / max(h.frames, 1.0));
    level += max(fresh, history);
    n += 1.0;
  }
  if (n < 3.0) return false;
  difference = abs(difference) / n;
  float standardError = sqrt(variance) / n;
  return difference > pc.ghostSigma * standardError && difference > 0.01 * level / n;
}

// The lag test: does the slow history trail what the reflection shows now? The fast history
// (a running mean of at most fastHistoryFrames frames) follows a change within a few frames;
// the slow one keeps stale light for up to glossyHistoryFrames. Each of the 8 neighbours, at
// its offset around where this pixel was last frame and on its own surface, gives the paired
// difference slow - fast of its histories: zero in expectation on a static view, whatever
// varies across the neighbourhood. A Student-t test of their mean against their spread (7
// degrees of freedom: all 8 must be on their surfaces; the curved small mirrors, whose
// neighbourhoods are split, keep the ghost cut only) beyond lagSigma says the neighbourhood's
// slow histories lag. The pixel's own histories take no part, so the decision is independent
// of them and its running mean stays unbiased. NRD ReBLUR and gi-temporal-denoise keep a fast
// history for the same reason (there as a clamp).
bool slowHistoryLags(FrameConstants f, ivec2 tracedPixel, vec2 screen) {
  if (pc.lagSigma <= 0.0) return false;
  ivec2 centre = ivec2(floor(tracedCoordinates(screen) + 0.5));
  float sum = 0.0, squares = 0.0, level = 0.0, n = 0.0;
  for (int k = 0; k < 9; ++k) {
    ivec2 d = ivec2(k % 3 - 1, k / 3 - 1);
    ivec2 q = tracedPixel + d;
    if (d == ivec2(0) || !insideTraced(q)) continue;
    History h = historyAt(loadSurface(f, q), centre + d);
    if (h.weight <= 0.0 || h.frames <= pc.fastHistoryFrames) continue;
    float slow = brdfLuminance(h.signal), fast = brdfLuminance(h.fast);
    sum += slow - fast;
    squares += (slow - fast) * (slow - fast);
    level += max(slow, fast);
    n += 1.0;
  }
  if (n < 8.0) return false;
  float mean = sum / n;
  float spread = sqrt(max(squares - n * mean * mean, 0.0) / (n - 1.0));
  return abs(mean) > pc.lagSigma * spread / sqrt(n) && abs(mean) > 0.01 * level / n;
}

// Where the view or the surface moved (the history was reprojected), the slow history's
// luminance is clamped into the range of the 3 x 3 neighbourhood's fast histories around where
// it was: reprojection under motion misplaces a little light every frame, which a long running
// mean collects into a trail that the lag test's noise hides; the fast histories forget it
// within a few frames (NRD ReBLUR's fast-history clamp). A static view is never clamped, so its
// running mean stays unbiased.
vec3 clampedToFastNeighbourhood(FrameConstants f, ivec2 tracedPixel, vec2 screen, History h) {
  ivec2 centre = ivec2(floor(tracedCoordinates(screen) + 0.5));
  float lo = 1e30, hi = 0.0;
  for (int k = 0; k < 9; ++k) {
    ivec2 d = ivec2(k % 3 - 1, k / 3 - 1);
    ivec2 q = tracedPixel + d;
    if (!insideTraced(q)) continue;
    History n = historyAt(loadSurface(f, q), centre + d);
    if (n.weight <= 0.0) continue;
    float fast = brdfLuminance(n.fast);
    lo = min(lo, fast);
    hi = max(hi, fast);
  }
  float l = brdfLuminance(h.signal);
  if (lo > hi || l <= 0.0) return h.signal;
  return h.signal * (clamp(l, lo, hi) / l);
}

// The mean parallax of this frame's traced rays at the 8 neighbours on this pixel's surface
// (negative where fewer than 3 have one), read from reflections.candidate.*, before any reuse.
// The pixel's own ray takes no part, as in the ghost and lag tests: a decision that depends on
// the sample the history is then merged with keeps or drops it by that sample's value. The
// reused samples would bring that back, since spatial reuse shares samples between neighbours:
// decided on them, small bright reflections came out darker under motion (the dolly's last
// frame against static runs, mean squared z, 5.7 against 3.0 on the raw rays). The neighbours'
// rays also say more than one ray does: 8 frames after the dolly stops, its trail measured 1.1x
// the static error against 2.0x with the pixel's own sample, means of 8 runs
// (docs/reflections.md, "Motion").
float neighboursParallax(FrameConstants f, ivec2 tracedPixel, DenoiseSurface here) {
  float sum = 0.0, n = 0.0;
  for (int k = 0; k < 9; ++k) {
    ivec2 d = ivec2(k % 3 - 1, k / 3 - 1);
    ivec2 q = tracedPixel + d;
    if (d == ivec2(0) || !insideTraced(q)) continue;
    float parallax = candidateParallax(f.camera.position, texelFetch(candidateSample, q, 0), texelFetch(candidateOrigin, q, 0));
    if (parallax < 0.0 || !sameSurface(here, encodeSurface(loadSurface(f, q)))) continue;
    sum += parallax;
    n += 1.0;
  }
  return n >= 3.0 ? sum / n : -1.0;
}

struct Accumulated {
  vec4 value;    // reflections.temporal
  vec4 moments;  // reflections.temporal-moments
  vec4 fast;     // reflections.temporal-fast
};

Accumulated accumulate(FrameConstants f, ivec2 tracedPixel, DenoiseSurface here) {
  Accumulated a = Accumulated(vec4(0.0, 0.0, 0.0, REFLECTION_NO_SAMPLE), vec4(0.0), vec4(0.0));
  if (!hasSurface(here) || !traceable(f, here.roughness)) return a;
  vec4 fresh;
  bool hasFresh = freshSample(f, tracedPixel, fresh);
  History h = noHistory();
  if (pc.historyValid != 0u) {
    Reprojection r = reproject(f, tracedPixel, here, hasFresh ? fresh.w : -1.0);
    vec2 centre = vec2(fullResPixel(f, tracedPixel)) + 0.5;
    bool viewMoved = max(distance(r.surface, centre), distance(r.virtualPoint, centre)) > REFLECTION_STILL_PIXELS;
    bool tested = viewMoved && pc.motionParallaxTolerance > 0.0;
    h = reprojectedHistory(here, r, tested ? neighboursParallax(f, tracedPixel, here) : -1.0);
    bool virtualFirst = r.hasVirtual && virtualShare(here.roughness) >= 0.5;
    vec2 previous = virtualFirst ? r.virtualPoint : r.surface;
    if (h.weight > 0.0 && h.frames > pc.fastHistoryFrames && slowHistoryLags(f, tracedPixel, previous)) {
      // Stale: restart from the fast history, which holds the last few frames only.
      h.signal = h.fast;
      h.frames = min(h.frames, pc.fastHistoryFrames);
    }
    bool moved = distance(previous, centre) > 0.01;
    if (h.weight > 0.0 && moved) h.signal = clampedToFastNeighbourhood(f, tracedPixel, previous, h);
    if (h.weight > 0.0 && neighbourhoodChanged(f, tracedPixel, previous))
      h.frames = min(h.frames, pc.responsiveFrames - 1.0);
  }
  float maxFrames = maxHistoryFrames(here.roughness);
  if (!hasFresh) {
    // No sample this frame: the history as it stands, if any.
    if (h.weight <= 0.0 || h.frames <= 0.0) return a;
    a.value = vec4(h.signal, h.hitDistance);
    a.moments = vec4(h.secondMoment, min(h.frames, maxFrames), h.parallax, 0.0);
    a.fast = vec4(h.fast, 0.0);
    return a;
  }
  float frames = h.weight > 0.0 ? min(h.frames + 1.0, maxFrames) : 1.0;
  float blend = 1.0 / frames;
  float l = brdfLuminance(fresh.rgb);
  a.value = vec4(mix(h.signal, fresh.rgb, blend), mix(h.hitDistance, min(fresh.w, REFLECTION_MISS_DISTANCE), blend));
  a.fast = vec4(mix(h.fast, fresh.rgb, 1.0 / min(frames, pc.fastHistoryFrames)), 0.0);
  // The parallax, not the hit distance, is what the spatial filter's footprint needs, and it
  // averages sensibly: a pixel whose rays mostly hit something near and sometimes miss gets a
  // small mean parallax, where its mean hit distance would be dominated by the misses.
  float parallax = rayParallax(distance(here.position, f.camera.position), fresh.w);
  a.moments = vec4(mix(h.secondMoment, l * l, blend), frames, mix(h.parallax, parallax, blend), 0.0);
  return a;
}

void main() {
  FrameConstants f = FrameBlock(pc.frame).v;
  ivec2 tracedPixel = ivec2(gl_GlobalInvocationID.xy);
  if (!insideTraced(tracedPixel)) return;
  DenoiseSurface here = loadSurface(f, tracedPixel);
  Accumulated a = accumulate(f, tracedPixel, here);
  // The last guard: whatever went wrong above, history stays finite.
  if (!isFiniteVec(a.value) || !isFiniteVec(a.moments) || !isFiniteVec(a.fast)) {
    a.value = vec4(0.0, 0.0, 0.0, REFLECTION_NO_SAMPLE);
    a.moments = vec4(0.0);
    a.fast = vec4(0.0);
  }
  imageStore(current, tracedPixel, vec4(min(a.value.rgb, vec3(65000.0)), a.value.w));
  imageStore(currentMoments, tracedPixel, a.moments);
  imageStore(currentSurface, tracedPixel, encodeSurface(here));
  imageStore(currentFast, tracedPixel, vec4(min(a.fast.rgb, vec3(65000.0)), 0.0));
}
