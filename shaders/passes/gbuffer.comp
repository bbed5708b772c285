// gbuffer: turns the visibility buffer into surface attributes. The barycentrics come from
// intersecting the pixel's camera ray with the triangle the vbuffer names (Burns & Hunt 2013,
// "The Visibility Buffer: A Cache-Friendly Approach to Deferred Shading", JCGT 2(2)), so the
// GBuffer sees exactly the point a primary ray would hit; the surface itself (normal map,
// textures, emission) is loaded by the same code as the reference path tracer's hits.
#version 460
#include "passes/hybrid_frame.glsl"
#include "lighting/surface.glsl"

layout(local_size_x = HYBRID_GROUP_SIZE, local_size_y = HYBRID_GROUP_SIZE) in;
layout(push_constant, scalar) uniform Push { HybridPassConstants pc; };

layout(set = 1, binding = GBUFFER_BINDING_IDS, rgba32ui) uniform readonly uimage2D vbufferIds;
layout(set = 1, binding = GBUFFER_BINDING_BASE_COLOR, rgba16f) uniform writeonly image2D baseColorOut;
layout(set = 1, binding = GBUFFER_BINDING_NORMALS, rgba16f) uniform writeonly image2D normalsOut;
layout(set = 1, binding = GBUFFER_BINDING_DEPTH, r32f) uniform writeonly image2D depthOut;
layout(set = 1, binding = GBUFFER_BINDING_UV, rg32f) uniform writeonly image2D uvOut;
layout(set = 1, binding = GBUFFER_BINDING_VELOCITY, rg16f) uniform writeonly image2D velocityOut;
layout(set = 1, binding = GBUFFER_BINDING_EMISSIVE, rgba16f) uniform writeonly image2D emissiveOut;
layout(set = 1, binding = GBUFFER_BINDING_FLAGS, r32ui) uniform writeonly uimage2D flagsOut;

// Distance along the unit ray to the plane of the triangle and the barycentrics (of v1, v2)
// of that point (Möller & Trumbore 1997, without the inside test: the vbuffer already knows
// the triangle covers the pixel).
vec3 intersectPlane(vec3 origin, vec3 dir, vec3 p0, vec3 p1, vec3 p2) {
  vec3 e1 = p1 - p0;
  vec3 e2 = p2 - p0;
  vec3 p = cross(dir, e2);
  float det = dot(e1, p);
  if (abs(det) < 1e-30) return vec3(0.0);
  float inv = 1.0 / det;
  vec3 s = origin - p0;
  float b1 = dot(s, p) * inv;
  vec3 q = cross(s, e1);
  float b2 = dot(dir, q) * inv;
  return vec3(dot(e2, q) * inv, b1, b2);
}

TraceHit hitFromVBuffer(FrameConstants f, uvec4 ids, vec3 dir) {
  GpuInstance instance = sceneInstance(ids.x);
  uvec3 tri = triangleVertices(sceneGeometry(ids.y), ids.z);
  Vec3Array positions = Vec3Array(scene.positions);
  vec3 p0 = transformPoint(instance.objectToWorld, positions.v[tri.x]);
  vec3 p1 = transformPoint(instance.objectToWorld, positions.v[tri.y]);
  vec3 p2 = transformPoint(instance.objectToWorld, positions.v[tri.z]);
  vec3 tb = intersectPlane(f.camera.position, dir, p0, p1, p2);
  vec3 frontNormal = cross(p1 - p0, p2 - p0) * (instanceMirrors(instance) ? -1.0 : 1.0);
  TraceHit hit;
  hit.t = tb.x;
  hit.instance = ids.x;
  hit.geometry = ids.y;
  hit.primitive = ids.z;
  hit.barycentrics = tb.yz;
  hit.frontFacing = dot(frontNormal, dir) < 0.0;
  return hit;
}

// Pixel motion since last frame, camera and object: the surface point's last-frame object-space
// position (a deforming mesh's previous pose, scene-deform) placed by last frame's instance
// transform, seen by last frame's camera. A point behind last frame's camera gets a huge vector,
// which every reprojection rejects.
vec2 pixelVelocity(FrameConstants f, vec2 pixelCentre, TraceHit hit) {
  uvec3 tri = triangleVertices(sceneGeometry(hit.geometry), hit.primitive);
  Vec3Array positions = Vec3Array(scene.previousPositions);
  vec3 objectPosition = positions.v[tri.x] * (1.0 - hit.barycentrics.x - hit.barycentrics.y) +
                        positions.v[tri.y] * hit.barycentrics.x +
                        positions.v[tri.z] * hit.barycentrics.y;
  GpuInstance previousInstance = InstanceArray(f.previousInstances).v[hit.instance];
  vec3 previousWorld = transformPoint(previousInstance.objectToWorld, objectPosition);
  vec4 clip = f.previousViewProjection * vec4(previousWorld, 1.0);
  if (clip.w <= 0.0) return vec2(65504.0);
  vec2 previous = (clip.xy / clip.w * 0.5 + 0.5) * vec2(f.resolution);
  return pixelCentre - previous;
}

void writeSky(ivec2 pixel) {
  imageStore(baseColorOut, pixel, vec4(0.0));
  imageStore(normalsOut, pixel, vec4(0.0));
  imageStore(depthOut, pixel, vec4(0.0));
  imageStore(uvOut, pixel, vec4(0.0));
  imageStore(velocityOut, pixel, vec4(0.0));
  imageStore(emissiveOut, pixel, vec4(0.0));
  imageStore(flagsOut, pixel, uvec4(0u));
}

void main() {
  FrameConstants f = FrameBlock(pc.frame).v;
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(pixel), f.resolution))) return;
  uvec4 ids = imageLoad(vbufferIds, pixel);
  if (ids.x == VBUFFER_NO_HIT) {
    writeSky(pixel);
    return;
  }
  vec2 centre = vec2(pixel) + 0.5;
  vec3 dir = pixelRayDirection(f, centre);
  TraceHit hit = hitFromVBuffer(f, ids, dir);
  Surface s = loadSurface(hit, dir, false);
  GpuMaterial m = sceneMaterial(sceneGeometry(hit.geometry).material);

  uint flags = GBUFFER_FLAG_SURFACE;
  if (!hit.frontFacing) flags |= GBUFFER_FLAG_BACK_FACING;
  if ((m.flags & (MATERIAL_ALPHA_MASK | MATERIAL_ALPHA_BLEND)) != 0u) flags |= GBUFFER_FLAG_ALPHA_TESTED;
  float roughness = sqrt(s.brdf.alpha);
  imageStore(baseColorOut, pixel, vec4(s.brdf.baseColor, s.brdf.metallic));
  imageStore(normalsOut, pixel,
             vec4(encodeOctahedral(s.shadingNormal), encodeOctahedral(s.geometricNormal)));
  imageStore(depthOut, pixel, vec4(hit.t * dot(dir, f.camera.forward)));
  imageStore(uvOut, pixel, vec4(interpolateUv(triangleVertices(sceneGeometry(hit.geometry), hit.primitive),
                                              hit.barycentrics), 0.0, 0.0));
  imageStore(velocityOut, pixel, vec4(pixelVelocity(f, centre, hit), 0.0, 0.0));
  imageStore(emissiveOut, pixel, vec4(s.emission, roughness));
  imageStore(flagsOut, pixel, uvec4(flags));
}
