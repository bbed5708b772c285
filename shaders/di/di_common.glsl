// What every ReSTIR DI pass shares (shared/restir_di_io.h): the constants, the GBuffer images and
// the shading point they give, the reservoir encoding, choosing a light candidate, a sample's
// integrand and target function, and the one visibility ray.
#ifndef BOUNCE_DI_DI_COMMON_GLSL
#define BOUNCE_DI_DI_COMMON_GLSL
#include "common/brdf.glsl"
#include "common/random.glsl"
#include "lighting/lights.glsl"
#include "passes/hybrid_frame.glsl"
#include "shared/restir_di_io.h"

layout(buffer_reference, scalar, buffer_reference_align = 8) readonly buffer DiBlock {
  DiConstants v;
};

layout(push_constant, scalar) uniform Push { DiPassConstants pc; };

layout(set = 1, binding = DI_BINDING_BASE_COLOR, rgba16f) uniform readonly image2D baseColors;
layout(set = 1, binding = DI_BINDING_NORMALS, rgba16f) uniform readonly image2D normals;
layout(set = 1, binding = DI_BINDING_DEPTH, r32f) uniform readonly image2D depths;
layout(set = 1, binding = DI_BINDING_EMISSIVE, rgba16f) uniform readonly image2D emissives;
layout(set = 1, binding = DI_BINDING_FLAGS, r32ui) uniform readonly uimage2D flags;

// Purposes of the chain's random numbers (common/random.glsl).
const uint RANDOM_DI_CANDIDATES = 0x44490001u;
const uint RANDOM_DI_TEMPORAL = 0x44490002u;
const uint RANDOM_DI_SPATIAL = 0x44490003u;

// A stream of uniform numbers for one pixel and purpose.
uvec4 diRandomKey(FrameConstants f, DiConstants di, ivec2 pixel, uint purpose) {
  return pcg4d(uvec4(uvec2(pixel), f.frameIndex, purpose ^ (di.seed * 0x9E3779B9u)));
}

vec4 diRandom(inout uvec4 key) {
  key = pcg4d(key + uvec4(0x632BE5ABu));
  return uniformFromHash(key);
}

// ---- the shading point ------------------------------------------------------------------------

struct DiSurface {
  vec3 position;
  vec3 normal;           // shading normal
  vec3 geometricNormal;  // on the viewer's side
  vec3 wo;               // towards the camera
  float depth;           // view depth
  BrdfMaterial brdf;
  bool valid;            // a surface covers the pixel
};

DiSurface loadDiSurface(FrameConstants f, ivec2 pixel) {
  DiSurface s;
  s.valid = all(lessThan(uvec2(pixel), f.resolution)) && all(greaterThanEqual(pixel, ivec2(0))) &&
            (imageLoad(flags, pixel).x & GBUFFER_FLAG_SURFACE) != 0u;
  vec4 encoded = s.valid ? imageLoad(normals, pixel) : vec4(0.0);
  s.normal = decodeOctahedral(encoded.xy);
  s.geometricNormal = decodeOctahedral(encoded.zw);
  s.depth = s.valid ? imageLoad(depths, pixel).x : 0.0;
  vec3 dir = pixelRayDirection(f, vec2(pixel) + 0.5);
  s.wo = -dir;
  s.position = positionFromDepth(f, vec2(pixel) + 0.5, s.depth);
  vec4 baseMetallic = s.valid ? imageLoad(baseColors, pixel) : vec4(0.0);
  float roughness = s.valid ? imageLoad(emissives, pixel).w : 1.0;
  bool lambert = (f.flags & FRAME_FLAG_LAMBERT) != 0u;
  s.brdf = makeBrdfMaterial(baseMetallic.rgb, lambert ? 0.0 : baseMetallic.w, roughness, lambert);
  s.valid = s.valid && s.depth > 0.0;
  return s;
}

// RTXDI's reuse tests: a neighbour (in space or time) shows the same surface when its view depth
// is within depthTolerance of ours (relative) and its normal within normalTolerance (cosine).
bool diSimilarSurface(DiConstants di, float depth, vec3 n, float otherDepth, vec3 otherN) {
  return otherDepth > 0.0 && abs(otherDepth - depth) <= di.depthTolerance * depth &&
         dot(n, otherN) >= di.normalTolerance;
}

// ---- reservoirs -------------------------------------------------------------------------------

struct DiReservoir {
  uint light;  // DI_NO_LIGHT: none
  vec2 u;      // the light's primary sample
  float W;     // unbiased contribution weight
  float M;     // confidence
  // Frames since di-shade's final shadow ray found this sample visible from this pixel;
  // DI_VISIBILITY_UNKNOWN: never (a new candidate, a neighbour's sample)
  uint visibleAge;
};

DiReservoir emptyDiReservoir() {
  DiReservoir r;
  r.light = DI_NO_LIGHT;
  r.u = vec2(0.0);
  r.W = 0.0;
  r.M = 0.0;
  r.visibleAge = DI_VISIBILITY_UNKNOWN;
  return r;
}

uvec4 packDiReservoir(DiReservoir r) {
  uint light = r.light == DI_NO_LIGHT ? DI_NO_LIGHT : r.light | (min(r.visibleAge, DI_VISIBILITY_UNKNOWN) << DI_VISIBLE_AGE_SHIFT);
  return uvec4(light, packUnorm2x16(r.u), floatBitsToUint(r.W), floatBitsToUint(r.M));
}

// The sample of a packed reservoir, without its visibility age: equal for the same point y.
uvec2 packedDiSample(uvec4 packed) {
  return uvec2(packed.x == DI_NO_LIGHT ? DI_NO_LIGHT : packed.x & ~DI_VISIBLE_AGE_MASK, packed.y);
}

// Anything non-finite or negative reads as an empty reservoir: NaN never enters history.
DiReservoir unpackDiReservoir(uvec4 v) {
  DiReservoir r;
  r.light = v.x == DI_NO_LIGHT ? DI_NO_LIGHT : v.x & ~DI_VISIBLE_AGE_MASK;
  r.visibleAge = v.x == DI_NO_LIGHT ? DI_VISIBILITY_UNKNOWN : (v.x & DI_VISIBLE_AGE_MASK) >> DI_VISIBLE_AGE_SHIFT;
  r.u = unpackUnorm2x16(v.y);
  r.W = uintBitsToFloat(v.z);
  r.M = uintBitsToFloat(v.w);
  if (!isFiniteValue(r.W) || !isFiniteValue(r.M) || r.W < 0.0 || r.M < 0.0) return emptyDiReservoir();
  if (r.light == DI_NO_LIGHT) r.W = 0.0;
  return r;
}

// Weighted reservoir sampling (Chao 1982; Bitterli et al. 2020, Alg. 2): keeps `light`, `u` with
// probability w / (sum of w so far); true when it is kept.
// The kept sample's visibility is unknown from here on; a caller that keeps one whose age it
// knows (the pixel's own history) sets visibleAge after.
bool diStream(inout DiReservoir r, inout float weightSum, uint light, vec2 u, float w, float M, float random) {
  r.M += M;
  if (!(w > 0.0)) return false;
  weightSum += w;
  if (random * weightSum >= w) return false;
  r.light = light;
  r.u = u;
  r.visibleAge = DI_VISIBILITY_UNKNOWN;
  return true;
}

// ---- lights -----------------------------------------------------------------------------------

// Probability that a light candidate is a local light (the rest go to the distant lights,
// uniformly): half each when both kinds exist.
float diLocalPick() {
  if (lightTables.localLightCount == 0u) return 0.0;
  return lightTables.distantLightCount > 0u ? 0.5 : 1.0;
}

// The probability with which a light candidate is `light` (its u is uniform).
float diSelectionPdf(uint light) {
  float local = diLocalPick();
  if ((light & DI_LIGHT_DISTANT) != 0u) {
    uint k = light & ~DI_LIGHT_DISTANT;
    return k < lightTables.distantLightCount ? (1.0 - local) / float(lightTables.distantLightCount) : 0.0;
  }
  if (light >= lightTables.localLightCount) return 0.0;
  return local * LightAliasArray(lightTables.lightAlias).v[light].pmf;
}

// One light candidate from a, its u (quantised as the reservoir stores it) from b, and the
// probability diSelectionPdf gives it (without a second load of its alias entry); DI_NO_LIGHT
// when the scene has no lights.
uint sampleDiLight(vec4 a, vec2 b, out vec2 u, out float pdf) {
  u = unpackUnorm2x16(packUnorm2x16(b));
  pdf = 0.0;
  float local = diLocalPick();
  if (a.x < local) {
    float pmf;
    uint light = pickLocalLight(a.yz, pmf);
    pdf = local * pmf;
    return light;
  }
  uint n = lightTables.distantLightCount;
  if (n == 0u) return DI_NO_LIGHT;
  pdf = (1.0 - local) / float(n);
  return DI_LIGHT_DISTANT | min(uint(a.w * float(n)), n - 1u);
}

uint sampleDiLight(vec4 a, vec2 b, out vec2 u) {
  float pdf;
  return sampleDiLight(a, b, u, pdf);
}

// A sample's integrand at a shading point (restir_di_io.h): f cos L G |dy/du|, unshadowed, and
// where its shadow ray goes.
struct DiLight {
  vec3 contribution;
  vec3 direction;     // unit, towards the light
  vec3 shadowTarget;  // local lights: the ray's end
  bool distant;       // distant lights: the ray goes to infinity along direction
  // |d omega / du| (emissive triangles: cos at the light x area / distance^2; 0 for lights no
  // ray can hit): turns a solid-angle density into one over u (di_brdf_candidate.glsl).
  float solidAngleToU;
};

DiLight noDiLight() {
  DiLight l;
  l.contribution = vec3(0.0);
  l.direction = vec3(0.0, 1.0, 0.0);
  l.shadowTarget = vec3(0.0);
  l.distant = false;
  l.solidAngleToU = 0.0;
  return l;
}

// The light's radiance times the geometry term and |dy/du| (before the BRDF), filling in the
// direction; zero where the light does not reach x. An emissive triangle's radiance is, when
// `exact`, its emissive texture at the point with its alpha test (di-shade's integrand), else its
// material's mean emission (GpuEmissiveTriangle::meanEmission): the target functions use that,
// which spares every candidate the geometry, material, vertex and texture fetches. A target only
// has to be positive wherever the integrand is (the mean of an emitter's emission is), so the
// estimate stays unbiased; it is only less well matched on strongly textured emitters.
vec3 diIncidentLight(uint light, vec2 u, vec3 x, bool exact, inout DiLight l) {
  if ((light & DI_LIGHT_DISTANT) != 0u) {
    uint k = light & ~DI_LIGHT_DISTANT;
    if (k >= lightTables.distantLightCount) return vec3(0.0);
    GpuDistantLight d = DistantLightArray(lightTables.distantLights).v[k];
    l.distant = true;
    l.direction = d.cosHalfAngle < 1.0 ? sampleCone(d.towardLight, d.cosHalfAngle, u) : d.towardLight;
    // Radiance x the cone's solid angle (lighting_io.h): the integrand over a uniform u.
    return d.coneWeight;
  }
  if (light >= lightTables.localLightCount) return vec3(0.0);
  if (light >= lightTables.emissiveTriangleCount) {
    GpuPunctualLight p = loadPunctualLight(light - lightTables.emissiveTriangleCount);
    vec3 toLight = p.position - x;
    float distanceSq = dot(toLight, toLight);
    if (!(distanceSq > 0.0)) return vec3(0.0);
    l.direction = toLight * inversesqrt(distanceSq);
    l.shadowTarget = p.position;
    float attenuation = 1.0;
    if (p.type == PUNCTUAL_LIGHT_SPOT) {
      float a = clamp(dot(p.spotDirection, -l.direction) * p.angleScale + p.angleOffset, 0.0, 1.0);
      attenuation = a * a;
    }
    return p.intensity * (attenuation / distanceSq);
  }
  GpuEmissiveTriangle e = loadEmissiveTriangle(light);
  vec2 b = uniformTriangleBarycentrics(u);
  vec3 y = e.p0 + b.x * e.edge1 + b.y * e.edge2;
  vec3 toLight = y - x;
  float distanceSq = dot(toLight, toLight);
  if (!(distanceSq > 0.0)) return vec3(0.0);
  l.direction = toLight * inversesqrt(distanceSq);
  l.shadowTarget = offsetRayOrigin(y, e.frontNormal);
  float cosLight = -dot(e.frontNormal, l.direction);
  if (cosLight <= 0.0) return vec3(0.0);
  vec3 radiance = decodeRgb9e5(e.meanEmission);
  if (exact) {
    GpuGeometry g = sceneGeometry(e.geometry);
    GpuMaterial m = sceneMaterial(g.material);
    // Cut-out parts of an alpha-tested emitter are not there (as lights.glsl).
    if ((m.flags & (MATERIAL_ALPHA_MASK | MATERIAL_ALPHA_BLEND)) != 0u && !alphaAccepts(e.geometry, e.primitive, b))
      return vec3(0.0);
    radiance = materialEmission(m, interpolateUv(triangleVertices(g, e.primitive), b));
  }
  // Area measure to u: |dy/du| = area.
  l.solidAngleToU = cosLight * e.area / distanceSq;
  return radiance * l.solidAngleToU;
}

DiLight evaluateDiLightAs(DiSurface s, uint light, vec2 u, bool exact) {
  DiLight l = noDiLight();
  if (light == DI_NO_LIGHT || !s.valid) return l;
  vec3 incident = diIncidentLight(light, u, s.position, exact, l);
  if (!any(greaterThan(incident, vec3(0.0))) || dot(l.direction, s.geometricNormal) <= 0.0) return l;
  vec3 f = brdfEvaluate(s.brdf, s.normal, s.wo, l.direction);
  l.contribution = f * max(dot(s.normal, l.direction), 0.0) * incident;
  return l;
}

// What the target functions see (the emitters' mean emission, above).
DiLight evaluateDiLight(DiSurface s, uint light, vec2 u) { return evaluateDiLightAs(s, light, u, false); }

// The integrand itself (di-shade).
DiLight evaluateDiLightExact(DiSurface s, uint light, vec2 u) { return evaluateDiLightAs(s, light, u, true); }

// The target function p_hat: the luminance of the unshadowed integrand.
float diTarget(DiLight l) {
  return max(brdfLuminance(l.contribution), 0.0);
}

// The shadow ray from s to the light. Each pass calls it once: every call inlines a whole BVH
// traversal, which a CPU driver compiles per copy (docs/startup.md).
bool diVisible(DiSurface s, DiLight l) {
  vec3 origin = offsetRayOrigin(s.position, s.geometricNormal);
  vec3 direction = l.distant ? l.direction : l.shadowTarget - origin;
  return traceVisibility(origin, direction, 0.0, l.distant ? 3.0e38 : 1.0, true);
}

// Unbiased contribution weight of a reservoir whose inputs' weights sum to `weightSum`, with
// normalisation `Z` (the confidence of the inputs that could have produced the sample).
float diContributionWeight(float weightSum, float targetOfSample, float Z) {
  return targetOfSample > 0.0 && Z > 0.0 ? weightSum / (Z * targetOfSample) : 0.0;
}

#endif
