// Watertight ray/triangle intersection (Woop, Benthin, Wald 2013, "Watertight Ray/Triangle
// Intersection", JCGT 2(1)). Shared by the GPU traversal and the CPU brute-force reference, so
// both answer with the same arithmetic. Edges shared by two triangles are never missed: the
// test shears the ray into a space where it runs along +z and evaluates 2D edge functions
// there, with consistent rounding on both sides of an edge.
#ifndef BOUNCE_SHARED_RAY_TRIANGLE_H
#define BOUNCE_SHARED_RAY_TRIANGLE_H
#include "shared/compat.h"

BOUNCE_BEGIN_SHARED

// Per-ray constants of the shear (section 3 of the paper): kz is the dominant axis of the
// direction, kx/ky the other two, swapped to keep the winding when dir[kz] < 0.
struct RayShear {
  int kx;
  int ky;
  int kz;
  vec3 shear;  // (Sx, Sy, Sz)
};

BOUNCE_FN RayShear makeRayShear(vec3 dir) {
  RayShear s;
  vec3 a = abs(dir);
  s.kz = (a.x > a.y) ? (a.x > a.z ? 0 : 2) : (a.y > a.z ? 1 : 2);
  s.kx = (s.kz + 1) % 3;
  s.ky = (s.kx + 1) % 3;
  if (dir[s.kz] < 0.0f) {
    int t = s.kx;
    s.kx = s.ky;
    s.ky = t;
  }
  s.shear = vec3(dir[s.kx] / dir[s.kz], dir[s.ky] / dir[s.kz], 1.0f / dir[s.kz]);
  return s;
}

struct TriangleHit {
  bool hit;
  float t;
  float b1;          // barycentric weight of v1
  float b2;          // barycentric weight of v2
  bool frontFacing;  // counter-clockwise seen from the ray origin (glTF front face)
};

// Hit with t in (tMin, tMax); both sides of the triangle count. The edge functions are
// BOUNCE_PRECISE: a GPU compiler must not contract them into FMAs, which would break the
// antisymmetry of U, V, W between two triangles sharing an edge (and so watertightness) and
// make the GPU disagree with the CPU.
BOUNCE_FN TriangleHit intersectTriangle(vec3 origin, RayShear s, vec3 v0, vec3 v1, vec3 v2,
                                        float tMin, float tMax) {
  TriangleHit h;
  h.hit = false;
  h.t = 0.0f;
  h.b1 = 0.0f;
  h.b2 = 0.0f;
  h.frontFacing = false;
  vec3 A = v0 - origin;
  vec3 B = v1 - origin;
  vec3 C = v2 - origin;
  BOUNCE_PRECISE float Ax = A[s.kx] - s.shear.x * A[s.kz];
  BOUNCE_PRECISE float Ay = A[s.ky] - s.shear.y * A[s.kz];
  BOUNCE_PRECISE float Bx = B[s.kx] - s.shear.x * B[s.kz];
  BOUNCE_PRECISE float By = B[s.ky] - s.shear.y * B[s.kz];
  BOUNCE_PRECISE float Cx = C[s.kx] - s.shear.x * C[s.kz];
  BOUNCE_PRECISE float Cy = C[s.ky] - s.shear.y * C[s.kz];
  // Scaled barycentrics: U for v0, V for v1, W for v2.
  BOUNCE_PRECISE float U = Cx * By - Cy * Bx;
  BOUNCE_PRECISE float V = Ax * Cy - Ay * Cx;
  BOUNCE_PRECISE float W = Bx * Ay - By * Ax;
  if ((U < 0.0f || V < 0.0f || W < 0.0f) && (U > 0.0f || V > 0.0f || W > 0.0f)) return h;
  BOUNCE_PRECISE float det = U + V + W;
  if (det == 0.0f) return h;
  BOUNCE_PRECISE float Az = s.shear.z * A[s.kz];
  BOUNCE_PRECISE float Bz = s.shear.z * B[s.kz];
  BOUNCE_PRECISE float Cz = s.shear.z * C[s.kz];
  BOUNCE_PRECISE float T = U * Az + V * Bz + W * Cz;
  float t = T / det;
  if (!(t > tMin && t < tMax)) return h;
  h.hit = true;
  h.t = t;
  h.b1 = V / det;
  h.b2 = W / det;
  // With the shear's handedness, det > 0 means the triangle winds counter-clockwise as seen
  // from the origin (glTF's front face).
  h.frontFacing = det > 0.0f;
  return h;
}

BOUNCE_END_SHARED
#endif
