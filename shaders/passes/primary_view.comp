// primary-view: casts one primary ray per pixel centre through the BVH and writes one surface
// attribute (albedo, normal, depth, instance or geometry id). The first image of a scene.
#version 460
#include "common/color.glsl"
#include "rt/trace.glsl"
#include "shared/primary_view_io.h"

layout(local_size_x = PRIMARY_VIEW_GROUP_SIZE, local_size_y = PRIMARY_VIEW_GROUP_SIZE) in;
layout(push_constant, scalar) uniform Push { PrimaryViewConstants pc; };
layout(buffer_reference, scalar, buffer_reference_align = 4) writeonly buffer OutputImage { vec4 v[]; };

vec3 surfaceAlbedo(TraceHit hit) {
  GpuGeometry g = sceneGeometry(hit.geometry);
  GpuMaterial m = sceneMaterial(g.material);
  uvec3 tri = triangleVertices(g, hit.primitive);
  vec3 albedo = m.baseColor.rgb * interpolateVertexColor(tri, hit.barycentrics).rgb;
  if (m.baseColorTexture != NO_TEXTURE)
    albedo *= sampleSceneTexture(m.baseColorTexture, interpolateUv(tri, hit.barycentrics), 0.0).rgb;
  return albedo;
}

// Shading normal in world space, facing the viewer (double-sided display).
vec3 surfaceNormal(TraceHit hit, vec3 rayDir) {
  GpuGeometry g = sceneGeometry(hit.geometry);
  vec3 n = interpolateNormal(triangleVertices(g, hit.primitive), hit.barycentrics);
  n = normalize(transformNormal(sceneInstance(hit.instance), n));
  return dot(n, rayDir) > 0.0 ? -n : n;
}

vec3 shade(TraceHit hit, vec3 rayDir) {
  switch (pc.view) {
    case PRIMARY_VIEW_ALBEDO: return surfaceAlbedo(hit);
    case PRIMARY_VIEW_NORMAL: return displayToLinear(surfaceNormal(hit, rayDir) * 0.5 + 0.5);
    case PRIMARY_VIEW_DEPTH: {
      float depth = hit.t * dot(rayDir, pc.camera.forward);
      float v = 1.0 - clamp((depth - pc.camera.nearDepth) /
                            max(pc.camera.farDepth - pc.camera.nearDepth, 1e-6), 0.0, 1.0);
      return displayToLinear(vec3(v));
    }
    case PRIMARY_VIEW_INSTANCE: return displayToLinear(idColor(hit.instance));
    default: return displayToLinear(idColor(hit.geometry));
  }
}

void main() {
  uvec2 pixel = gl_GlobalInvocationID.xy;
  if (any(greaterThanEqual(pixel, pc.resolution))) return;
  vec3 dir = cameraRayDirection(pc.camera, vec2(pixel) + 0.5, vec2(pc.resolution));
  TraceHit hit = traceClosest(pc.camera.position, dir, 0.0, 3.0e38, pc.alphaTest != 0u);
  vec4 result = vec4(traceHitFound(hit) ? shade(hit, dir) : vec3(0.0), 1.0);
  OutputImage(pc.outputImage).v[pixel.y * pc.resolution.x + pixel.x] = result;
}
