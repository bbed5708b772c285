// vbuffer (fragment stage, alpha-tested materials): writes which triangle covers the pixel
// unless the tracer's own alpha test (base-colour alpha, nearest texel of mip 0, vertex colour
// alpha; shaders/rt/trace.glsl) cuts it out, so that raster and rays agree on what is cut out. A
// shader that may discard loses early depth testing, hence the separate opaque pipeline
// (vbuffer_opaque.frag) for everything else.
#version 460
#include "passes/hybrid_frame.glsl"
#include "rt/scene.glsl"

layout(push_constant, scalar) uniform Push { VBufferDrawConstants pc; };

layout(location = 0) in vec2 inUv;
layout(location = 1) flat in uint inPrimitive;
layout(location = 2) in float inVertexAlpha;
layout(location = 0) out uvec4 outIds;

bool alphaCutOut() {
  GpuMaterial m = sceneMaterial(sceneGeometry(pc.geometry).material);
  if ((m.flags & (MATERIAL_ALPHA_MASK | MATERIAL_ALPHA_BLEND)) == 0u) return false;
  float alpha = m.baseColor.a;
  if (m.baseColorTexture != NO_TEXTURE) alpha *= fetchSceneTexelNearest(m.baseColorTexture, inUv).a;
  alpha *= inVertexAlpha;
  float cutoff = (m.flags & MATERIAL_ALPHA_BLEND) != 0u ? 0.5 : m.alphaCutoff;
  return alpha < cutoff;
}

void main() {
  if (alphaCutOut()) discard;
  outIds = uvec4(pc.instance, pc.geometry, inPrimitive, 0u);
}
