// vbuffer (vertex stage): one draw per (instance, geometry) without vertex buffers; the vertex
// is fetched from the scene's streams through buffer device addresses (gl_VertexIndex = 3 x
// primitive + corner).
#version 460
#include "passes/hybrid_frame.glsl"
#include "rt/scene.glsl"

layout(push_constant, scalar) uniform Push { VBufferDrawConstants pc; };

layout(location = 0) out vec2 outUv;
layout(location = 1) flat out uint outPrimitive;
layout(location = 2) out float outVertexAlpha;  // COLOR_0's alpha, for the alpha test

void main() {
  uint primitive = uint(gl_VertexIndex) / 3u;
  uint corner = uint(gl_VertexIndex) % 3u;
  uvec3 tri = triangleVertices(sceneGeometry(pc.geometry), primitive);
  uint vertex = corner == 0u ? tri.x : (corner == 1u ? tri.y : tri.z);
  vec3 objectPosition = Vec3Array(scene.positions).v[vertex];
  vec3 world = transformPoint(sceneInstance(pc.instance).objectToWorld, objectPosition);
  gl_Position = FrameBlock(pc.frame).v.viewProjection * vec4(world, 1.0);
  outUv = Vec2Array(scene.uvs).v[vertex];
  outPrimitive = primitive;
  outVertexAlpha = scene.colors == uint64_t(0) ? 1.0 : unpackUnorm4x8(UintArray(scene.colors).v[vertex]).a;
}
