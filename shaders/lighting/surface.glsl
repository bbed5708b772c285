// What light transport needs to know about a hit point, for the reference path tracer and the
// real-time passes alike: position, a geometric normal and a shading normal on the side the ray
// came from, the glTF material there (textures applied) as a BrdfMaterial, and the radiance it
// emits back along the ray.
#ifndef BOUNCE_LIGHTING_SURFACE_GLSL
#define BOUNCE_LIGHTING_SURFACE_GLSL
#include "common/brdf.glsl"
#include "rt/trace.glsl"

struct Surface {
  vec3 position;
  vec3 geometricNormal;  // unit, on the side of the incoming ray
  vec3 shadingNormal;    // unit, on the same side, with wo above it
  vec3 emission;         // radiance towards the ray origin (front faces only)
  uint material;
  BrdfMaterial brdf;
};

// The mip level at which a texture is at most maxSide texels wide (0 = always the full mip).
// Seed 000's gi-trace-diffuse-rays "always samples materials at a coarse mip level, to reduce
// bandwidth": diffuse GI rays scatter over the hemisphere, so their hits are incoherent and a
// full-resolution fetch misses the cache; and what the GI needs of a texture is its average
// over a footprint much larger than a texel. The mips are box-filtered (texture_pack.cpp), so a
// coarse mip keeps each region's mean albedo.
float coarseTextureLod(uint ref, uint maxSide) {
  if (maxSide == 0u) return 0.0;
  uint side = TEXTURE_MIN_SIZE << ((ref >> 16) & 0xFu);
  return max(0.0, log2(float(side) / float(maxSide)));
}

// Emitted radiance of a material given its emissive texel (read only where the factor is
// positive): emissive factor (strength folded in) x emissive texture.
vec3 emissionFromTexel(GpuMaterial m, vec4 emissiveTexel) {
  vec3 e = m.emissive;
  if (m.emissiveTexture != NO_TEXTURE && any(greaterThan(e, vec3(0.0)))) e *= emissiveTexel.rgb;
  return e;
}

// Emitted radiance of a material at uv.
vec3 materialEmission(GpuMaterial m, vec2 uv) {
  bool reads = m.emissiveTexture != NO_TEXTURE && any(greaterThan(m.emissive, vec3(0.0)));
  return emissionFromTexel(m, reads ? sampleSceneTexture(m.emissiveTexture, uv, 0.0) : vec4(1.0));
}

// The normal map's perturbation of shading normal n, in a tangent frame made from the
// triangle's uv gradient (the glTF sample viewer's rule when a mesh has no tangents):
// t = dP/du made orthogonal to n, b = cross(n, t), flipped when the uv layout is mirrored
// (glTF's v runs down the image, so an unmirrored layout has b along -dP/dv).
vec3 applyNormalMap(GpuMaterial m, vec3 n, vec3 e1, vec3 e2, vec2 duv1, vec2 duv2,
                    vec4 normalTexel) {
  float det = duv1.x * duv2.y - duv1.y * duv2.x;
  if (abs(det) < 1e-12) return n;
  vec3 dPdu = (e1 * duv2.y - e2 * duv1.y) / det;
  vec3 dPdv = (e2 * duv1.x - e1 * duv2.x) / det;
  vec3 t = dPdu - n * dot(n, dPdu);
  if (dot(t, t) < 1e-20) return n;
  t = normalize(t);
  vec3 b = cross(n, t);
  if (dot(b, dPdv) > 0.0) b = -b;
  vec3 tangentSpace = normalTexel.rgb * 2.0 - 1.0;
  tangentSpace.xy *= m.normalScale;
  vec3 perturbed = tangentSpace.x * t + tangentSpace.y * b + tangentSpace.z * n;
  return dot(perturbed, perturbed) > 1e-12 ? normalize(perturbed) : n;
}

bool instanceMirrors(GpuInstance instance) {
  return dot(instance.worldToObject[0].xyz,
             cross(instance.worldToObject[1].xyz, instance.worldToObject[2].xyz)) < 0.0;
}

// The surface at a hit with its textures read at mips at most maxTextureSide texels wide (0:
// full resolution; see coarseTextureLod).
Surface loadSurfaceAtCoarseMip(TraceHit hit, vec3 rayDirection, bool lambertOnly, uint maxTextureSide) {
  GpuInstance instance = sceneInstance(hit.instance);
  GpuGeometry geometry = sceneGeometry(hit.geometry);
  GpuMaterial m = sceneMaterial(geometry.material);
  uvec3 tri = triangleVertices(geometry, hit.primitive);
  Vec3Array positions = Vec3Array(scene.positions);
  vec3 p0 = transformPoint(instance.objectToWorld, positions.v[tri.x]);
  vec3 p1 = transformPoint(instance.objectToWorld, positions.v[tri.y]);
  vec3 p2 = transformPoint(instance.objectToWorld, positions.v[tri.z]);
  vec2 b = hit.barycentrics;

  Surface s;
  s.material = geometry.material;
  s.position = p0 * (1.0 - b.x - b.y) + p1 * b.x + p2 * b.y;
  vec3 e1 = p1 - p0;
  vec3 e2 = p2 - p0;
  // The glTF front face, from the same world-space triangle and rule the light table uses for
  // the emitting side (src/lighting/light_table.cpp), so that light sampling and BRDF hits
  // agree exactly on which side emits: counter-clockwise, or clockwise under a mirroring
  // instance transform. This is TraceHit.frontFacing by definition.
  vec3 frontNormal = cross(e1, e2) * (instanceMirrors(instance) ? -1.0 : 1.0);
  bool frontFacing = dot(frontNormal, rayDirection) < 0.0;
  vec3 ng = dot(frontNormal, frontNormal) > 0.0 ? normalize(frontNormal) : -rayDirection;
  if (dot(ng, rayDirection) > 0.0) ng = -ng;
  s.geometricNormal = ng;

  // The interpolated normal decides which side is the back; the normal map is applied in the
  // front-side frame and flipped with it (the sample viewer's rule for double-sided surfaces).
  vec3 ns = transformNormal(instance, interpolateNormal(tri, b));
  ns = dot(ns, ns) > 0.0 ? normalize(ns) : ng;
  bool flip = dot(ns, ng) < 0.0;
  if (flip) ns = -ns;
  vec2 uv = interpolateUv(tri, b);
  // The material's maps, read up front by one call (rt/scene.glsl: one copy of the sampling
  // code to compile instead of four). Emission is one-sided: only the glTF front face emits.
  // It is read at full resolution even here, so that it matches what NEE's light sampling
  // (lights.glsl) sees of the same emitter.
  bool emits = frontFacing && any(greaterThan(m.emissive, vec3(0.0)));
  vec4 texels[4];  // normal, base colour, metallic-roughness, emission
  sampleSceneTextures(uvec4(m.normalTexture, m.baseColorTexture, m.metallicRoughnessTexture,
                            emits ? m.emissiveTexture : NO_TEXTURE),
                      uv,
                      vec4(coarseTextureLod(m.normalTexture, maxTextureSide),
                           coarseTextureLod(m.baseColorTexture, maxTextureSide),
                           coarseTextureLod(m.metallicRoughnessTexture, maxTextureSide), 0.0),
                      texels);
  if (m.normalTexture != NO_TEXTURE) {
    Vec2Array uvs = Vec2Array(scene.uvs);
    vec2 uv0 = uvs.v[tri.x];
    vec3 front = flip ? -ns : ns;
    ns = applyNormalMap(m, front, e1, e2, uvs.v[tri.y] - uv0, uvs.v[tri.z] - uv0, texels[0]);
    if (flip) ns = -ns;
  }
  // A shading normal that hides the viewer would make the BRDF zero for every direction.
  if (dot(ns, -rayDirection) <= 0.0 || any(isnan(ns))) ns = ng;
  s.shadingNormal = ns;

  vec3 baseColor = m.baseColor.rgb * interpolateVertexColor(tri, b).rgb;
  if (m.baseColorTexture != NO_TEXTURE)
    baseColor *= texels[1].rgb;
  float metallic = m.metallic;
  float roughness = m.roughness;
  if (m.metallicRoughnessTexture != NO_TEXTURE) {
    vec4 mr = texels[2];
    roughness *= mr.g;
    metallic *= mr.b;
  }
  if (lambertOnly) metallic = 0.0;
  s.brdf = makeBrdfMaterial(baseColor, metallic, roughness, lambertOnly);
  s.emission = frontFacing ? emissionFromTexel(m, texels[3]) : vec3(0.0);
  return s;
}

// The surface at full texture resolution: the path tracer and the GBuffer.
Surface loadSurface(TraceHit hit, vec3 rayDirection, bool lambertOnly) {
  return loadSurfaceAtCoarseMip(hit, rayDirection, lambertOnly, 0u);
}

#endif
