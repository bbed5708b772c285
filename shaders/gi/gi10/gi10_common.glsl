// What GI-1.0's passes share (shared/gi10_io.h; research/gi10_lux_denoisers.md §1): the buffer
// references, the probe's hemisphere map, fp16 probe cells and L2 spherical harmonics.
#ifndef BOUNCE_GI_GI10_COMMON_GLSL
#define BOUNCE_GI_GI10_COMMON_GLSL
#include "common/random.glsl"
#include "common/sampling.glsl"
#include "passes/hybrid_frame.glsl"
#include "shared/gi10_io.h"

layout(buffer_reference, scalar, buffer_reference_align = 8) readonly buffer Gi10ConstantsRef {
  Gi10Constants v;
};
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer Gi10ProbesRef {
  Gi10Probe v[];
};
layout(buffer_reference, scalar, buffer_reference_align = 8) buffer Gi10RadianceRef {
  uvec2 v[];
};
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer Gi10ShRef {
  vec3 v[];
};
layout(buffer_reference, scalar, buffer_reference_align = 8) buffer Gi10SpawnRef {
  uvec2 v[];
};
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer Gi10RaysRef {
  Gi10Ray v[];
};
layout(buffer_reference, scalar, buffer_reference_align = 4) coherent buffer Gi10CacheRef {
  Gi10CacheCell v[];
};
layout(buffer_reference, scalar, buffer_reference_align = 4) coherent buffer Gi10CountersRef {
  Gi10Counters v;
};

// Adds one to the statistics counter `field` of Gi10Counters for every lane that runs it, with
// one atomic per subgroup: a per-lane atomic on one address from every probe ray serialised
// (`k` is the including pass's Gi10Constants).
#define GI10_COUNT(k, field)                                                    \
  {                                                                             \
    uint lanes_ = subgroupBallotBitCount(subgroupBallot(true));                 \
    if (subgroupElect()) atomicAdd(Gi10CountersRef(k.counters).v.field, lanes_); \
  }

// ---- the probe's hemisphere ------------------------------------------------------------------
// Capsaicin maps a probe's hemisphere hemi-octahedrally (§1.3). Here the 8x8 cells are equal
// in solid angle instead (2 pi / 64 each): Shirley & Chiu's concentric square-to-disk map, then
// Lambert's azimuthal equal-area projection of the disk onto the hemisphere. A ray uniform in a
// cell is then uniform in solid angle, so each cell's sample weighs the same in the SH
// projection and in the blend, without a Jacobian per cell.

vec2 gi10SquareToDisk(vec2 u) {
  vec2 o = 2.0 * u - 1.0;
  if (o.x == 0.0 && o.y == 0.0) return vec2(0.0);
  float r, theta;
  if (abs(o.x) > abs(o.y)) {
    r = o.x;
    theta = (PI / 4.0) * (o.y / o.x);
  } else {
    r = o.y;
    theta = PI / 2.0 - (PI / 4.0) * (o.x / o.y);
  }
  return r * vec2(cos(theta), sin(theta));
}

vec2 gi10DiskToSquare(vec2 d) {
  float r = length(d);
  if (r == 0.0) return vec2(0.5);
  float phi = atan(d.y, d.x);
  if (phi < -PI / 4.0) phi += 2.0 * PI;
  vec2 ab;
  if (phi < PI / 4.0) {
    ab = vec2(r, phi * r / (PI / 4.0));
  } else if (phi < 3.0 * PI / 4.0) {
    ab = vec2(-(phi - PI / 2.0) * r / (PI / 4.0), r);
  } else if (phi < 5.0 * PI / 4.0) {
    ab = vec2(-r, -(phi - PI) * r / (PI / 4.0));
  } else {
    ab = vec2((phi - 3.0 * PI / 2.0) * r / (PI / 4.0), -r);
  }
  return clamp(0.5 * ab + 0.5, vec2(0.0), vec2(1.0));
}

// The world direction at square position u in [0,1]^2 of the hemisphere around unit n.
vec3 gi10HemisphereDirection(vec3 n, vec2 u) {
  vec2 d = gi10SquareToDisk(u);
  float r2 = dot(d, d);
  vec2 xy = d * sqrt(max(0.0, 2.0 - r2));
  vec3 t, b;
  orthonormalBasis(n, t, b);
  return normalize(xy.x * t + xy.y * b + (1.0 - r2) * n);
}

// The inverse: the square position of world direction `dir` (above n) on n's hemisphere.
vec2 gi10HemisphereSquare(vec3 n, vec3 dir) {
  vec3 t, b;
  orthonormalBasis(n, t, b);
  vec3 l = vec3(dot(dir, t), dot(dir, b), max(dot(dir, n), 0.0));
  return gi10DiskToSquare(l.xy / sqrt(1.0 + l.z));
}

uint gi10CellOfSquare(vec2 u) {
  uvec2 c = min(uvec2(u * float(GI10_PROBE_SIZE)), uvec2(GI10_PROBE_SIZE - 1u));
  return c.y * GI10_PROBE_SIZE + c.x;
}

vec2 gi10CellCentre(uint cell) {
  return (vec2(cell % GI10_PROBE_SIZE, cell / GI10_PROBE_SIZE) + 0.5) / float(GI10_PROBE_SIZE);
}

// ---- fp16 probe cells --------------------------------------------------------------------------

uvec2 gi10PackCell(vec3 radiance, float hitDistance) {
  vec3 r = clamp(radiance, vec3(0.0), vec3(65000.0));
  return uvec2(packHalf2x16(r.xy), packHalf2x16(vec2(r.z, min(hitDistance, GI10_MISS_DISTANCE))));
}

vec4 gi10UnpackCell(uvec2 packed) {
  return vec4(unpackHalf2x16(packed.x), unpackHalf2x16(packed.y));
}

float gi10Luma(vec3 c) { return dot(c, vec3(0.2126, 0.7152, 0.0722)); }

// ---- L2 spherical harmonics (§1.3: probes are projected on 9 coefficients) -------------------

void gi10ShBasis(vec3 d, out float y[9]) {
  y[0] = 0.282095;
  y[1] = 0.488603 * d.y;
  y[2] = 0.488603 * d.z;
  y[3] = 0.488603 * d.x;
  y[4] = 1.092548 * d.x * d.y;
  y[5] = 1.092548 * d.y * d.z;
  y[6] = 0.315392 * (3.0 * d.z * d.z - 1.0);
  y[7] = 1.092548 * d.x * d.z;
  y[8] = 0.546274 * (d.x * d.x - d.y * d.y);
}

// Irradiance / pi at normal n from the probe tile's SH of radiance: the clamped-cosine
// convolution (Ramamoorthi & Hanrahan 2001: A0 = pi, A1 = 2 pi / 3, A2 = pi / 4) over pi.
vec3 gi10ShIrradianceOverPi(Gi10ShRef sh, uint tile, vec3 n) {
  float y[9];
  gi10ShBasis(n, y);
  const float band[9] = float[9](1.0, 2.0 / 3.0, 2.0 / 3.0, 2.0 / 3.0, 0.25, 0.25, 0.25, 0.25, 0.25);
  vec3 e = vec3(0.0);
  for (uint i = 0u; i < 9u; ++i) e += sh.v[tile * 9u + i] * (band[i] * y[i]);
  return max(e, vec3(0.0));
}

// ---- screen geometry ---------------------------------------------------------------------------

// World size of `pixels` pixels' footprint at view depth `depth`.
float gi10Footprint(Gi10Constants k, float depth, float pixels) {
  return k.pixelFootprint * pixels * depth;
}

float gi10ViewDepth(FrameConstants f, vec3 p) { return dot(p - f.camera.position, f.camera.forward); }

#endif
