// bench-rays: one kind of ray per dispatch (see shared/bench_rays_io.h), so each kind's
// traversal cost can be timed alone. Results are written per pixel so no ray is optimised away.
#version 460
#include "common/random.glsl"
#include "common/sampling.glsl"
#include "rt/trace.glsl"
#include "shared/bench_rays_io.h"

layout(local_size_x = BENCH_RAYS_GROUP_SIZE, local_size_y = BENCH_RAYS_GROUP_SIZE) in;
layout(push_constant, scalar) uniform Push { BenchRaysConstants pc; };
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer SurfaceArray { BenchSurface v[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer ResultArray { uint v[]; };

// Offset along the normal, scaled with the position's magnitude, so secondary rays do not
// re-hit their own surface.
vec3 offsetOrigin(vec3 p, vec3 n) { return p + n * (1e-4 + 1e-5 * length(p)); }

void tracePrimary(uvec2 pixel, uint index) {
  vec3 dir = cameraRayDirection(pc.camera, vec2(pixel) + 0.5, vec2(pc.resolution));
  TraceHit hit = traceClosest(pc.camera.position, dir, 0.0, 3.0e38, true);
  BenchSurface s;
  s.valid = traceHitFound(hit) ? 1u : 0u;
  s.position = vec3(0.0);
  s.normal = vec3(0.0, 1.0, 0.0);
  s.pad = 0.0;
  if (traceHitFound(hit)) {
    GpuGeometry g = sceneGeometry(hit.geometry);
    vec3 n = interpolateNormal(triangleVertices(g, hit.primitive), hit.barycentrics);
    n = normalize(transformNormal(sceneInstance(hit.instance), n));
    if (dot(n, dir) > 0.0) n = -n;
    s.normal = n;
    s.position = offsetOrigin(pc.camera.position + hit.t * dir, n);
  }
  SurfaceArray(pc.surfaces).v[index] = s;
  ResultArray(pc.results).v[index] = s.valid;
}

void traceSecondary(uvec2 pixel, uint index) {
  BenchSurface s = SurfaceArray(pc.surfaces).v[index];
  uint result = 2u;
  if (s.valid != 0u) {
    if (pc.mode == BENCH_RAYS_SHADOW) {
      vec3 dir = sampleCone(pc.toSun, pc.sunCosHalfAngle, random2(pixel, pc.frame, RANDOM_BENCH_SUN));
      result = traceVisibility(s.position, dir, 0.0, 3.0e38, true) ? 0u : 1u;
    } else {
      vec3 dir = sampleCosineHemisphere(s.normal, random2(pixel, pc.frame, RANDOM_BENCH_DIFFUSE));
      result = traceHitFound(traceClosest(s.position, dir, 0.0, 3.0e38, true)) ? 1u : 0u;
    }
  }
  ResultArray(pc.results).v[index] = result;
}

void main() {
  uvec2 pixel = gl_GlobalInvocationID.xy;
  if (any(greaterThanEqual(pixel, pc.resolution))) return;
  uint index = pixel.y * pc.resolution.x + pixel.x;
  if (pc.mode == BENCH_RAYS_PRIMARY)
    tracePrimary(pixel, index);
  else
    traceSecondary(pixel, index);
}
