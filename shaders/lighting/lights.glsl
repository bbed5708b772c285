// Next-event estimation: picking a light and a point on it for a shading point, and the density
// with which a BRDF-sampled ray that hits an emissive triangle would have been picked (for MIS).
// The tables are built on the CPU (src/lighting/light_table.cpp); their layout is described in
// shared/lighting_io.h, and the entry point loads them into `lightTables` first.
#ifndef BOUNCE_LIGHTING_LIGHTS_GLSL
#define BOUNCE_LIGHTING_LIGHTS_GLSL
#include "common/ray_offset.glsl"
#include "common/sampling.glsl"
#include "lighting/light_tables.glsl"
#include "lighting/surface.glsl"

// A point on a light as seen from a shading point x.
struct LightSample {
  vec3 direction;       // unit, from x towards the light
  vec3 shadowTarget;    // trace the shadow ray to here (local lights) ...
  bool distant;         // ... or to infinity along direction (distant lights)
  vec3 radianceOverPdf; // incoming radiance / (pdf of this direction), selection included
  float pdf;            // solid-angle density for MIS; 0 for delta lights (no MIS)
  bool valid;
};

LightSample invalidLightSample() {
  LightSample l;
  l.direction = vec3(0.0, 1.0, 0.0);
  l.shadowTarget = vec3(0.0);
  l.distant = false;
  l.radianceOverPdf = vec3(0.0);
  l.pdf = 0.0;
  l.valid = false;
  return l;
}

// Walker's alias method: u.x picks an entry uniformly, u.y keeps it or takes its alias.
uint pickLocalLight(vec2 u, out float pmf) {
  LightAliasArray table = LightAliasArray(lightTables.lightAlias);
  uint n = lightTables.localLightCount;
  uint i = min(uint(u.x * float(n)), n - 1u);
  GpuLightAlias entry = table.v[i];
  uint chosen = u.y < entry.threshold ? i : entry.alias;
  pmf = table.v[chosen].pmf;
  return chosen;
}

// GpuEmissiveTriangle::meanEmission (RGB9E5: three 9-bit mantissas, a 5-bit exponent biased by
// 15; EXT_texture_shared_exponent; encoded by src/lighting/light_table.cpp).
vec3 decodeRgb9e5(uint bits) {
  float scale = exp2(float(int(bits >> 27u) - 24));
  return vec3(uvec3(bits, bits >> 9u, bits >> 18u) & uvec3(511u)) * scale;
}

// A uniform point on the triangle (Shirley's square-root warp; Pharr et al., PBRT 3rd ed.
// §13.6.4): barycentrics (b1, b2) of v1 and v2.
vec2 uniformTriangleBarycentrics(vec2 u) {
  float r = sqrt(u.x);
  return vec2(r * (1.0 - u.y), r * u.y);
}

LightSample sampleEmissiveTriangle(uint index, float pmf, vec3 x, vec2 u) {
  GpuEmissiveTriangle e = loadEmissiveTriangle(index);
  vec2 b = uniformTriangleBarycentrics(u);
  vec3 y = e.p0 + b.x * e.edge1 + b.y * e.edge2;
  vec3 toLight = y - x;
  float distanceSq = dot(toLight, toLight);
  LightSample l = invalidLightSample();
  if (!(distanceSq > 0.0)) return l;
  l.direction = toLight * inversesqrt(distanceSq);
  float cosLight = -dot(e.frontNormal, l.direction);
  if (cosLight <= 0.0) return l;  // x is behind the emitting side
  GpuGeometry g = sceneGeometry(e.geometry);
  GpuMaterial m = sceneMaterial(g.material);
  // A cut-out part of an alpha-tested emitter is not there: BRDF rays pass through it
  // (traceClosest with the alpha test), so light sampling must not count it either.
  if ((m.flags & (MATERIAL_ALPHA_MASK | MATERIAL_ALPHA_BLEND)) != 0u &&
      !alphaAccepts(e.geometry, e.primitive, b))
    return l;
  vec2 uv = interpolateUv(triangleVertices(g, e.primitive), b);
  vec3 radiance = materialEmission(m, uv);
  // Area density pmf / area, turned into solid angle at x.
  l.pdf = pmf * distanceSq / (cosLight * e.area);
  l.radianceOverPdf = radiance / l.pdf;
  l.shadowTarget = offsetRayOrigin(y, e.frontNormal);
  l.valid = l.pdf > 0.0;
  return l;
}

// glTF KHR_lights_punctual: intensity / distance^2, times the spot's smooth angular falloff.
LightSample samplePunctualLight(uint index, float pmf, vec3 x) {
  GpuPunctualLight p = loadPunctualLight(index);
  vec3 toLight = p.position - x;
  float distanceSq = dot(toLight, toLight);
  LightSample l = invalidLightSample();
  if (!(distanceSq > 0.0)) return l;
  l.direction = toLight * inversesqrt(distanceSq);
  float attenuation = 1.0;
  if (p.type == PUNCTUAL_LIGHT_SPOT) {
    float a = clamp(dot(p.spotDirection, -l.direction) * p.angleScale + p.angleOffset, 0.0, 1.0);
    attenuation = a * a;
  }
  l.radianceOverPdf = p.intensity * (attenuation / (distanceSq * pmf));
  l.shadowTarget = p.position;
  l.pdf = 0.0;
  l.valid = attenuation > 0.0;
  return l;
}

// One local light (emissive triangle or punctual light), picked in proportion to its power.
// u.xy choose the light, u.zw the point on it.
LightSample sampleLocalLight(vec3 x, vec4 u) {
  if (lightTables.localLightCount == 0u) return invalidLightSample();
  float pmf;
  uint index = pickLocalLight(u.xy, pmf);
  if (!(pmf > 0.0)) return invalidLightSample();
  if (index < lightTables.emissiveTriangleCount) return sampleEmissiveTriangle(index, pmf, x, u.zw);
  return samplePunctualLight(index - lightTables.emissiveTriangleCount, pmf, x);
}

// Distant light k: a direction uniformly within its cone (or its one direction).
LightSample sampleDistantLight(uint k, vec2 u) {
  GpuDistantLight d = DistantLightArray(lightTables.distantLights).v[k];
  LightSample l = invalidLightSample();
  l.distant = true;
  l.direction = d.cosHalfAngle < 1.0 ? sampleCone(d.towardLight, d.cosHalfAngle, u) : d.towardLight;
  l.radianceOverPdf = d.coneWeight;
  l.pdf = 0.0;  // never hit by BRDF rays: no MIS
  l.valid = true;
  return l;
}

// Whether light sampling picks points on emitters of `material` (materialLightAreaPdf > 0); the
// large emitters the real-time tables leave to rays are not (src/lighting/gpu_light_tables.h).
bool lightTablesSampleMaterial(uint material) {
  return FloatArray(lightTables.materialLightAreaPdf).v[material] > 0.0;
}

// Density with which sampleLocalLight would have produced the direction of a ray from
// `origin` that hit the front of an emissive triangle of `material` at `hitPoint`, whose
// geometric normal is n.
float emissiveHitLightPdf(uint material, vec3 origin, vec3 hitPoint, vec3 n) {
  float areaPdf = FloatArray(lightTables.materialLightAreaPdf).v[material];
  vec3 d = hitPoint - origin;
  float distanceSq = dot(d, d);
  float cosLight = abs(dot(n, d)) * inversesqrt(distanceSq);
  return cosLight > 0.0 ? areaPdf * distanceSq / cosLight : 0.0;
}

#endif
