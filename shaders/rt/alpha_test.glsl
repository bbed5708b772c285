// The alpha test of both tracers: the software traversal (rt/trace.glsl) calls it for
// triangles flagged GPU_TRIANGLE_ALPHA_TESTED, the hardware tracer's any-hit shader
// (rt/hw_alpha_test.rahit) for the non-opaque geometries of its acceleration structures, so
// both accept the same candidate hits. GpuScene::alphaAccepts mirrors it on the CPU.
#ifndef BOUNCE_RT_ALPHA_TEST_GLSL
#define BOUNCE_RT_ALPHA_TEST_GLSL
#include "rt/scene.glsl"

// Alpha test of a candidate hit on a MASK/BLEND material: base-colour alpha (factor x texel,
// nearest, mip 0, x vertex colour) against the cutoff; BLEND counts as a mask at 0.5.
bool alphaAccepts(uint globalGeometry, uint primitive, vec2 bary) {
  GpuGeometry g = sceneGeometry(globalGeometry);
  GpuMaterial m = sceneMaterial(g.material);
  float alpha = m.baseColor.a;
  uvec3 tri = triangleVertices(g, primitive);
  if (m.baseColorTexture != NO_TEXTURE)
    alpha *= fetchSceneTexelNearest(m.baseColorTexture, interpolateUv(tri, bary)).a;
  alpha *= interpolateVertexColor(tri, bary).a;
  float cutoff = (m.flags & MATERIAL_ALPHA_BLEND) != 0u ? 0.5 : m.alphaCutoff;
  return alpha >= cutoff;
}

#endif
