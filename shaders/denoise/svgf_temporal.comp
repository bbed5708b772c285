// svgf-temporal (Schied et al. 2017 §4.1; Falcor SVGFPass "Reprojection"): the running mean of
// the (albedo-demodulated) signal and of its first two luminance moments over a reprojected
// history.
//   - Reprojection: last frame's position is pixel + 0.5 - motion; the four last-frame pixels
//     around it are read bilinearly, each only where its surface (svgf.surface) agrees with this
//     pixel's: view depth within depthTolerance (relative) plus twice the surface's own slope
//     over a pixel, normals within normalTolerance (cosine). Where none of the four agrees, the
//     3x3 block around it is tried with equal weights (Falcor's fallback); else the history
//     restarts (a disocclusion).
//   - Blend: exponential moving average with weight max(alpha, 1 / history length), so the first
//     frames of a history are a plain mean (Schied §4.1) and later ones an EMA of ~2/alpha - 1
//     frames. The colour history is svgf-atrous-0's output of last frame (Schied's feedback),
//     the moments' history svgf.moments.
//   - Nothing non-finite enters history (a NaN/Inf sample counts as 0).
//   - The variance: where the history is long enough (varianceHistoryFrames) the temporal one,
//     mu2 - mu1^2, written to svgf.filtered-moments here; the 8x8 tiles holding a shorter one
//     are listed in svgf.variance-tiles for svgf-variance's spatial estimate.
// Pixels without a surface pass the signal through and restart their history.
#version 460
#include "denoise/svgf_common.glsl"

layout(local_size_x = SVGF_GROUP_SIZE, local_size_y = SVGF_GROUP_SIZE) in;

layout(set = 1, binding = SVGF_TEMPORAL_BINDING_NOISY, rgba16f) uniform readonly image2D noisyImage;
layout(set = 1, binding = SVGF_TEMPORAL_BINDING_DEPTH, r32f) uniform readonly image2D depths;
layout(set = 1, binding = SVGF_TEMPORAL_BINDING_NORMALS, rgba16f) uniform readonly image2D normals;
layout(set = 1, binding = SVGF_TEMPORAL_BINDING_MOTION, rg16f) uniform readonly image2D motions;
layout(set = 1, binding = SVGF_TEMPORAL_BINDING_ALBEDO, rgba16f) uniform readonly image2D albedos;
layout(set = 1, binding = SVGF_TEMPORAL_BINDING_PREVIOUS_SURFACE, rg32ui) uniform readonly uimage2D previousSurface;
layout(set = 1, binding = SVGF_TEMPORAL_BINDING_PREVIOUS_MOMENTS, rgba32f) uniform readonly image2D previousMoments;
layout(set = 1, binding = SVGF_TEMPORAL_BINDING_PREVIOUS_ILLUMINATION, rgba16f) uniform readonly image2D previousIllumination;
layout(set = 1, binding = SVGF_TEMPORAL_BINDING_SURFACE, rg32ui) uniform writeonly uimage2D surfaceOut;
layout(set = 1, binding = SVGF_TEMPORAL_BINDING_MOMENTS, rgba32f) uniform writeonly image2D momentsOut;
layout(set = 1, binding = SVGF_TEMPORAL_BINDING_ACCUMULATED, rgba16f) uniform writeonly image2D accumulatedOut;
layout(set = 1, binding = SVGF_TEMPORAL_BINDING_SLOPE, r32f) uniform writeonly image2D slopeOut;
layout(set = 1, binding = SVGF_TEMPORAL_BINDING_FILTERED, rgba16f) uniform writeonly image2D filteredOut;

shared bool tileNeedsSpatialVariance;

float currentDepth(ivec2 q) { return imageLoad(depths, q).x; }
DEFINE_DEPTH_GRADIENT(currentDepth)

vec3 loadNormal(ivec2 pixel) {
  vec4 n = imageLoad(normals, pixel);
  return (pc.flags & SVGF_FLAG_OCTAHEDRAL_NORMALS) != 0u ? decodeOctahedralNormal(n.xy) : normalize(n.xyz);
}

// Whether last frame's pixel q saw this pixel's surface.
bool consistent(ivec2 q, float z, float slope, vec3 n) {
  if (!inImage(q)) return false;
  vec4 s = unpackSurface(imageLoad(previousSurface, q).xy);
  if (!hasSurface(s.w)) return false;
  return abs(s.w - z) <= pc.depthTolerance * z + 2.0 * slope && dot(s.xyz, n) >= pc.normalTolerance;
}

struct History {
  vec3 colour;
  vec2 moments;
  float frames;  // history length; 0: none
};

History addTap(History h, ivec2 q, float w) {
  vec4 m = imageLoad(previousMoments, q);
  h.colour += w * finiteOrZero(imageLoad(previousIllumination, q).rgb);
  h.moments += w * finiteOrZero(m.xyz).xy;
  h.frames += w * m.z;
  return h;
}

// Last frame's colour, moments and history length at this pixel's surface (length 0: none).
History reproject(ivec2 pixel, float z, float slope, vec3 n) {
  History none = History(vec3(0.0), vec2(0.0), 0.0);
  if (pc.historyValid == 0u) return none;
  vec2 previous = vec2(pixel) + 0.5 - imageLoad(motions, pixel).xy;
  if (!isFiniteValue(previous.x) || !isFiniteValue(previous.y)) return none;
  vec2 base = previous - 0.5;
  ivec2 p0 = ivec2(floor(base));
  vec2 f = base - vec2(p0);
  History h = none;
  float weightSum = 0.0;
  for (int i = 0; i < 4; ++i) {
    ivec2 o = ivec2(i & 1, i >> 1);
    float w = (o.x == 1 ? f.x : 1.0 - f.x) * (o.y == 1 ? f.y : 1.0 - f.y);
    if (w <= 0.0 || !consistent(p0 + o, z, slope, n)) continue;
    h = addTap(h, p0 + o, w);
    weightSum += w;
  }
  if (weightSum < 1e-3) {  // Falcor's fallback: any agreeing pixel of the 3x3 block
    h = none;
    weightSum = 0.0;
    ivec2 centre = ivec2(floor(previous));
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx)
        if (consistent(centre + ivec2(dx, dy), z, slope, n)) {
          h = addTap(h, centre + ivec2(dx, dy), 1.0);
          weightSum += 1.0;
        }
  }
  if (weightSum <= 0.0) return none;
  h.colour /= weightSum;
  h.moments /= weightSum;
  h.frames = round(h.frames / weightSum);
  return h;
}

// The pass for one pixel; returns whether its variance needs svgf-variance's spatial estimate.
bool accumulate(ivec2 pixel) {
  vec3 noisy = finiteOrZero(imageLoad(noisyImage, pixel).rgb);
  float z = imageLoad(depths, pixel).x;
  if (!hasSurface(z)) {
    imageStore(surfaceOut, pixel, uvec4(0u));
    imageStore(momentsOut, pixel, vec4(0.0));
    imageStore(accumulatedOut, pixel, vec4(noisy, 0.0));
    imageStore(slopeOut, pixel, vec4(0.0));
    imageStore(filteredOut, pixel, vec4(noisy, SVGF_NO_SURFACE_VARIANCE));
    return false;
  }
  vec3 n = loadNormal(pixel);
  imageStore(surfaceOut, pixel, uvec4(packSurface(n, z), 0u, 0u));
  // The à-trous iterations read the slope from here: 4 bytes a pixel instead of 4 neighbours'
  // 8-byte surfaces in each iteration.
  float slope = depthSlope(pixel, z);
  imageStore(slopeOut, pixel, vec4(slope));
  vec3 signal = noisy;
  if ((pc.flags & SVGF_FLAG_ALBEDO) != 0u) signal /= safeAlbedo(imageLoad(albedos, pixel).rgb);
  float l = svgfLuminance(signal);
  History h = reproject(pixel, z, slope, n);
  float frames = min(h.frames + 1.0, pc.maxHistory);
  float colourAlpha = max(pc.colorAlpha, 1.0 / frames);
  float momentsAlpha = max(pc.momentsAlpha, 1.0 / frames);
  vec3 colour = mix(h.colour, signal, colourAlpha);
  vec2 moments = mix(h.moments, vec2(l, l * l), momentsAlpha);
  imageStore(momentsOut, pixel, vec4(moments, frames, 0.0));
  imageStore(accumulatedOut, pixel, vec4(colour, 0.0));
  if (frames < float(pc.varianceHistoryFrames)) return true;
  // What svgf-variance gave these pixels before: the colour as stored, the fp32 moments.
  imageStore(filteredOut, pixel, vec4(colour, max(moments.y - moments.x * moments.x, 0.0)));
  return false;
}

void main() {
  if (gl_LocalInvocationIndex == 0u) tileNeedsSpatialVariance = false;
  barrier();
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (inImage(pixel) && accumulate(pixel)) tileNeedsSpatialVariance = true;
  barrier();
  if (gl_LocalInvocationIndex == 0u && tileNeedsSpatialVariance) {
    SvgfVarianceTiles list = SvgfVarianceTiles(pc.varianceTiles);
    uint slot = atomicAdd(list.header.groupsX, 1u);
    list.tiles[slot] = gl_WorkGroupID.x | (gl_WorkGroupID.y << 16u);
  }
}
