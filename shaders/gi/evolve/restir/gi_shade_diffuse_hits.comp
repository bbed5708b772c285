// gi-shade-diffuse-hits: x2 of each GI pixel's ray from the closest hit gi-trace-diffuse-rays
// found. A miss sees the sky (x2 is then a direction). A hit x2 gets its emission (none from
// the emitters ReSTIR DI samples, FRAME_FLAG_DI_LIGHTS), the set-up of one NEE shadow ray
// (traced by gi-trace-diffuse-nee-rays, which walks the list of GI pixels with one:
// ray_list.glsl) and, by RestirGiSettings::secondVertex, the cache's irradiance or a continued
// path (restir_gi_second_vertex.glsl). The pipeline is specialized for the second vertex
// (GI_SPEC_SECOND_VERTEX), so the continued path's traversal is compiled in only where it runs.
#version 460
#include "gi/evolve/restir/restir_gi_second_vertex.glsl"
#include "gi/evolve/cache/cache_radiance.glsl"
#include "lighting/regularize.glsl"
#include "gi/evolve/restir/ray_list.glsl"

layout(local_size_x = RESTIR_GI_GROUP_SIZE, local_size_y = RESTIR_GI_GROUP_SIZE) in;
layout(push_constant, scalar) uniform Push { RestirGiPassConstants pc; };

layout(set = 1, binding = GI_SHADE_BINDING_NORMALS, rgba16f) uniform readonly image2D normals;
layout(set = 1, binding = GI_SHADE_BINDING_DEPTH, r32f) uniform readonly image2D depths;
layout(set = 1, binding = GI_SHADE_BINDING_RAYS, rgba32f) uniform readonly image2D rays;
layout(set = 1, binding = GI_SHADE_BINDING_HIT_IDS, rgba32ui) uniform readonly uimage2D hitIds;
layout(set = 1, binding = GI_SHADE_BINDING_HIT_BARYCENTRICS, rg32f) uniform readonly image2D hitBarycentrics;
layout(set = 1, binding = GI_SHADE_BINDING_HIT, rgba32f) uniform writeonly image2D hitOut;
layout(set = 1, binding = GI_SHADE_BINDING_HIT_NORMAL, rgba16f) uniform writeonly image2D hitNormalOut;
layout(set = 1, binding = GI_SHADE_BINDING_HIT_RADIANCE, rgba32f) uniform writeonly image2D hitRadianceOut;
layout(set = 1, binding = GI_SHADE_BINDING_NEE_RAY, rgba32f) uniform writeonly image2D neeRayOut;
layout(set = 1, binding = GI_SHADE_BINDING_NEE_RADIANCE, rgba32f) uniform writeonly image2D neeRadianceOut;
layout(set = 1, binding = GI_SHADE_BINDING_NEE_VISIBILITY, r16f) uniform writeonly image2D neeVisibilityOut;

void writeResult(ivec2 g, vec3 x2, uint kind, vec3 n2, vec3 radiance, vec4 neeRay, vec3 neeRadiance) {
  imageStore(hitOut, g, vec4(x2, float(kind)));
  imageStore(hitNormalOut, g, vec4(encodeOctahedral(n2), 0.0, 0.0));
  imageStore(hitRadianceOut, g, finiteOrZero(vec4(radiance, 0.0)));
  imageStore(neeRayOut, g, neeRay);
  imageStore(neeRadianceOut, g, finiteOrZero(vec4(neeRadiance, 0.0)));
  imageStore(neeVisibilityOut, g, vec4(0.0));
}

const uint RANDOM_GI_CACHE = 0x47490005u;

// Light from the 3rd vertex on, reflected at x2 (seed 000, "Clipmap for 3rd+ vertices"): the
// cache holds irradiance / pi at x2 (sky + all indirect bounces, no direct light of the sun or
// lights, which NEE adds), so the reflected radiance is x2's reflectance times it: the diffuse
// albedo, and for metals their specular lobe's split-sum albedo (indirectHitReflectance), so
// that a metal is not black to the GI but for its highlights.
vec3 cacheBounce(FrameConstants f, Surface s, vec3 wo, uint seed) {
  RestirGiConstants gi = RestirGiBlock(pc.gi).v;
  vec3 reflectance = indirectHitReflectance(f.specularAlbedo, s.brdf, s.shadingNormal, wo);
  ClipmapCacheView cache = clipmapCacheView(gi.cache);
  return reflectance * cacheLookupIrradiance(cache, s.position, s.geometricNormal, seed ^ RANDOM_GI_CACHE);
}

// gi-trace-diffuse-rays' hit for GI pixel g, as a TraceHit (the fields loadSurface reads).
TraceHit tracedHit(ivec2 g) {
  uvec4 ids = imageLoad(hitIds, g);
  TraceHit hit = noHit(0.0);
  if (ids.x == GI_HIT_NONE) return hit;
  hit.instance = ids.x;
  hit.geometry = ids.y;
  hit.primitive = ids.z;
  hit.barycentrics = imageLoad(hitBarycentrics, g).xy;
  return hit;
}

layout(constant_id = GI_SPEC_SECOND_VERTEX) const uint SPEC_SECOND_VERTEX = RESTIR_GI_SECOND_VERTEX_ANY;

void main() {
  FrameConstants f = FrameBlock(pc.frame).v;
  RestirGiConstants gi = RestirGiBlock(pc.gi).v;
  ivec2 g = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(g), gi.giResolution))) return;
  lightTables = LightTablesBlock(gi.lights).v;
  vec4 ray = imageLoad(rays, g);
  ivec2 pixel = giRepresentativePixel(f, gi, g);
  PrimaryVertex x1 = makePrimaryVertex(f, pixel, imageLoad(normals, pixel), imageLoad(depths, pixel).x);
  vec3 dir = ray.xyz;
  // No ray, or a direction below the geometric surface (zero contribution, as in the reference).
  if (ray.w == 0.0 || dot(dir, x1.geometricNormal) <= 0.0) {
    writeResult(g, x1.position, RESTIR_GI_KIND_NONE, vec3(0.0, 0.0, 1.0), vec3(0.0), vec4(0.0), vec3(0.0));
    return;
  }
  TraceHit hit = tracedHit(g);
  if (!traceHitFound(hit)) {
    writeResult(g, x1.position + dir * RESTIR_GI_SKY_DISTANCE, RESTIR_GI_KIND_SKY, -dir,
                skyRadianceToward(f, dir), vec4(0.0), vec3(0.0));
    return;
  }
  bool lambert = (f.flags & FRAME_FLAG_LAMBERT) != 0u;
  Surface s = loadSurfaceAtCoarseMip(hit, dir, lambert, gi.materialTextureSide);
  vec3 wo = -dir;
  // ReSTIR DI lights x1 from the emitters the light tables sample (FRAME_FLAG_DI_LIGHTS): a GI
  // ray that hits one adds no emission, or direct light would count twice.
  bool diLit = (f.flags & FRAME_FLAG_DI_LIGHTS) != 0u && lightTablesSampleMaterial(s.material);
  vec3 radiance = diLit ? vec3(0.0) : s.emission;
  vec4 neeRay = vec4(0.0);
  vec3 neeRadiance = vec3(0.0);
  uvec4 key = pcg4d(uvec4(g, f.frameIndex, RANDOM_GI_PATH));
  if (gi.maxPathBounces > 1u) {
    float localPick;
    LightSample l = sampleSecondVertexLight(f, s.position, key, localPick);
    uint secondVertex = SPEC_SECOND_VERTEX == RESTIR_GI_SECOND_VERTEX_ANY ? gi.secondVertex : SPEC_SECOND_VERTEX;
    bool continues = secondVertex == RESTIR_GI_SECOND_VERTEX_PATH;
    bool addsCache = secondVertex == RESTIR_GI_SECOND_VERTEX_CACHE && gi.maxPathBounces > 2u;
    if (l.valid && dot(l.direction, s.geometricNormal) > 0.0) {
      // With the cache at x2 (already approximate), a glossy x2's lobe is regularized for its
      // light sample (lighting/regularize.glsl): the sun's peak on a near-mirror hit by a
      // diffuse ray made rare, huge samples that reuse spread into blotches. The continued path
      // (the unbiased configuration) keeps the true lobe.
      BrdfMaterial lobe = continues ? s.brdf : regularizedMaterial(s.brdf, DIFFUSE_RAY_HIT_MIN_ALPHA);
      vec3 brdf = brdfEvaluate(lobe, s.shadingNormal, wo, l.direction);
      neeRadiance = brdf * max(dot(s.shadingNormal, l.direction), 0.0) * l.radianceOverPdf;
      // MIS against the continued path's BRDF ray, which can hit the same emitter. The cache
      // never counts the emitters NEE samples (cache_radiance.glsl): no weight with it.
      if (continues && l.pdf > 0.0)
        neeRadiance *= powerHeuristic(l.pdf, brdfPdf(s.brdf, s.shadingNormal, wo, l.direction));
      neeRay = l.distant ? vec4(l.direction, 0.0) : vec4(l.shadowTarget, 1.0);
    }
    if (continues)
      radiance += continuedPath(f, s, wo, key, localPick, gi.maxPathBounces, lambert, gi.materialTextureSide);
    if (addsCache) radiance += cacheBounce(f, s, wo, key.x);
  }
  writeResult(g, s.position, RESTIR_GI_KIND_SURFACE, s.geometricNormal, radiance, neeRay, neeRadiance);
  if (any(notEqual(neeRay.xyz, vec3(0.0))))
    rayListAppend(pc.rayLists, GI_RAY_LIST_NEE, gi.giResolution, g, 1u);
}
