// The scene as shaders see it: buffer_reference views of the arrays in GpuSceneRefs (set 0,
// binding 0) and the texture arrays (set 0, bindings 1..). Include once per shader.
#ifndef BOUNCE_RT_SCENE_GLSL
#define BOUNCE_RT_SCENE_GLSL
#include "shared/scene_layout.h"

layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer InstanceArray {
  GpuInstance v[];
};
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer UintArray {
  uint v[];
};
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer Vec2Array {
  vec2 v[];
};
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer Vec3Array {
  vec3 v[];
};
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer Vec4Array {
  vec4 v[];
};

// Nodes, triangles, instances, geometries and materials as 16-byte quarters, the view the
// traversal and the shading of its hits read them through. A view of GpuBvhNode[] with the
// scalar layout promises only 4-byte alignment, so a GPU compiler fetches a 64-byte node through
// it as sixteen 32-bit loads; every element of these arrays starts on a 16-byte boundary (each
// array is its own allocation and its element a multiple of 16 bytes), and through this view it
// takes four 128-bit loads. docs/ray-tracing.md, "128-bit loads".
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer QuadArray {
  vec4 v[];
};

GpuBvhNode loadBvhNode(QuadArray nodes, uint index) {
  vec4 q0 = nodes.v[4u * index];
  vec4 q1 = nodes.v[4u * index + 1u];
  vec4 q2 = nodes.v[4u * index + 2u];
  vec4 q3 = nodes.v[4u * index + 3u];
  return GpuBvhNode(q0.xyz, floatBitsToUint(q0.w), q1.xyz, floatBitsToUint(q1.w), q2.xyz,
                    floatBitsToUint(q2.w), q3.xyz, floatBitsToUint(q3.w));
}

GpuTriangle loadTriangle(QuadArray triangles, uint index) {
  vec4 q0 = triangles.v[3u * index];
  vec4 q1 = triangles.v[3u * index + 1u];
  vec4 q2 = triangles.v[3u * index + 2u];
  return GpuTriangle(q0.xyz, floatBitsToUint(q0.w), q1.xyz, floatBitsToUint(q1.w), q2.xyz,
                     floatBitsToUint(q2.w));
}

GpuWideBvhNode loadWideBvhNode(QuadArray nodes, uint index) {
  uvec4 q0 = floatBitsToUint(nodes.v[5u * index]);
  uvec4 q1 = floatBitsToUint(nodes.v[5u * index + 1u]);
  uvec4 q2 = floatBitsToUint(nodes.v[5u * index + 2u]);
  uvec4 q3 = floatBitsToUint(nodes.v[5u * index + 3u]);
  uvec4 q4 = floatBitsToUint(nodes.v[5u * index + 4u]);
  return GpuWideBvhNode(uintBitsToFloat(q0.xyz), q0.w, q1.x, q1.y, q1.zw, q2.xy, q2.zw, q3.xy,
                        q3.zw, q4.xy, q4.zw);
}

layout(set = 0, binding = 0, scalar) uniform SceneBlock { GpuSceneRefs scene; };

// One binding per (encoding, size class); see the texture-reference layout in scene_layout.h.
layout(set = 0, binding = 1) uniform sampler2DArray textureLinear64;
layout(set = 0, binding = 2) uniform sampler2DArray textureLinear128;
layout(set = 0, binding = 3) uniform sampler2DArray textureLinear256;
layout(set = 0, binding = 4) uniform sampler2DArray textureLinear512;
layout(set = 0, binding = 5) uniform sampler2DArray textureLinear1024;
layout(set = 0, binding = 6) uniform sampler2DArray textureLinear2048;
layout(set = 0, binding = 7) uniform sampler2DArray textureSrgb64;
layout(set = 0, binding = 8) uniform sampler2DArray textureSrgb128;
layout(set = 0, binding = 9) uniform sampler2DArray textureSrgb256;
layout(set = 0, binding = 10) uniform sampler2DArray textureSrgb512;
layout(set = 0, binding = 11) uniform sampler2DArray textureSrgb1024;
layout(set = 0, binding = 12) uniform sampler2DArray textureSrgb2048;

uint textureBindingSlot(uint ref) {
  uint sizeClass = (ref >> 16) & 0xFu;
  return sizeClass + (((ref & TEXTURE_SRGB_BIT) != 0u) ? TEXTURE_SIZE_CLASSES : 0u);
}

// Filtered lookup at an explicit mip level. Without descriptor indexing, a switch over constant
// bindings is how a dynamic texture choice is written.
vec4 sampleSceneTexture(uint ref, vec2 uv, float lod) {
  vec3 c = vec3(uv, float(ref & 0xFFFFu));
  switch (textureBindingSlot(ref)) {
    case 0u: return textureLod(textureLinear64, c, lod);
    case 1u: return textureLod(textureLinear128, c, lod);
    case 2u: return textureLod(textureLinear256, c, lod);
    case 3u: return textureLod(textureLinear512, c, lod);
    case 4u: return textureLod(textureLinear1024, c, lod);
    case 5u: return textureLod(textureLinear2048, c, lod);
    case 6u: return textureLod(textureSrgb64, c, lod);
    case 7u: return textureLod(textureSrgb128, c, lod);
    case 8u: return textureLod(textureSrgb256, c, lod);
    case 9u: return textureLod(textureSrgb512, c, lod);
    case 10u: return textureLod(textureSrgb1024, c, lod);
    default: return textureLod(textureSrgb2048, c, lod);
  }
}

// Four filtered lookups (refs[i] at lods[i]) through one sampleSceneTexture call. Every call
// is inlined with its switch over the twelve bindings, and a CPU driver (llvmpipe) compiles the
// sampling code of each case in each copy: a surface that read its four maps by four calls cost
// four times the compile (docs/startup.md). The loop is kept a loop for that reason. A ref of
// NO_TEXTURE reads nothing and gives vec4(1.0).
void sampleSceneTextures(uvec4 refs, vec2 uv, vec4 lods, out vec4 texels[4]) {
  [[dont_unroll]] for (uint i = 0u; i < 4u; ++i) {
    if (refs[i] == NO_TEXTURE)
      texels[i] = vec4(1.0);
    else
      texels[i] = sampleSceneTexture(refs[i], uv, lods[i]);
  }
}

// Unfiltered mip-0 texel with repeat wrapping: what the tracer's alpha test reads, so that the
// CPU reference (src/scene/texture_pack.h, sampleAlphaNearest) can reproduce it exactly.
vec4 fetchSceneTexelNearest(uint ref, vec2 uv) {
  uint side = TEXTURE_MIN_SIZE << ((ref >> 16) & 0xFu);
  ivec2 texel = clamp(ivec2(floor(fract(uv) * float(side))), ivec2(0), ivec2(int(side) - 1));
  ivec3 c = ivec3(texel, int(ref & 0xFFFFu));
  switch (textureBindingSlot(ref)) {
    case 0u: return texelFetch(textureLinear64, c, 0);
    case 1u: return texelFetch(textureLinear128, c, 0);
    case 2u: return texelFetch(textureLinear256, c, 0);
    case 3u: return texelFetch(textureLinear512, c, 0);
    case 4u: return texelFetch(textureLinear1024, c, 0);
    case 5u: return texelFetch(textureLinear2048, c, 0);
    case 6u: return texelFetch(textureSrgb64, c, 0);
    case 7u: return texelFetch(textureSrgb128, c, 0);
    case 8u: return texelFetch(textureSrgb256, c, 0);
    case 9u: return texelFetch(textureSrgb512, c, 0);
    case 10u: return texelFetch(textureSrgb1024, c, 0);
    default: return texelFetch(textureSrgb2048, c, 0);
  }
}

// 128-bit loads (QuadArray above): an instance is seven quarters (objectToWorld, worldToObject,
// its indices and flags), a geometry one.
GpuInstance sceneInstance(uint i) {
  QuadArray quads = QuadArray(scene.instances);
  uvec4 ids = floatBitsToUint(quads.v[7u * i + 6u]);
  return GpuInstance(vec4[3](quads.v[7u * i], quads.v[7u * i + 1u], quads.v[7u * i + 2u]),
                     vec4[3](quads.v[7u * i + 3u], quads.v[7u * i + 4u], quads.v[7u * i + 5u]),
                     ids.x, ids.y, ids.z, ids.w);
}
GpuGeometry sceneGeometry(uint i) {
  uvec4 g = floatBitsToUint(QuadArray(scene.geometries).v[i]);
  return GpuGeometry(g.x, g.y, g.z, g.w);
}
// Four 128-bit loads (QuadArray above): baseColor; emissive, metallic; roughness, alphaCutoff,
// normalScale, flags; the four texture references.
GpuMaterial sceneMaterial(uint i) {
  QuadArray quads = QuadArray(scene.materials);
  vec4 q1 = quads.v[4u * i + 1u];
  vec4 q2 = quads.v[4u * i + 2u];
  uvec4 textures = floatBitsToUint(quads.v[4u * i + 3u]);
  return GpuMaterial(quads.v[4u * i], q1.xyz, q1.w, q2.x, q2.y, q2.z, floatBitsToUint(q2.w),
                     textures.x, textures.y, textures.z, textures.w);
}

// The three vertex indices (into the shared streams) of a triangle of a geometry.
uvec3 triangleVertices(GpuGeometry g, uint primitive) {
  UintArray indices = UintArray(scene.indices);
  uint base = g.firstIndex + 3u * primitive;
  return uvec3(indices.v[base], indices.v[base + 1u], indices.v[base + 2u]) + g.vertexOffset;
}

vec2 interpolateUv(uvec3 tri, vec2 bary) {
  Vec2Array uvs = Vec2Array(scene.uvs);
  return uvs.v[tri.x] * (1.0 - bary.x - bary.y) + uvs.v[tri.y] * bary.x + uvs.v[tri.z] * bary.y;
}

// The vertex colour (glTF COLOR_0) at the hit: it multiplies the material's base colour and
// alpha (glTF 2.0 §3.9.2). White when the scene has no vertex colours (scene.colors == 0).
vec4 interpolateVertexColor(uvec3 tri, vec2 bary) {
  if (scene.colors == uint64_t(0)) return vec4(1.0);
  UintArray colors = UintArray(scene.colors);
  return unpackUnorm4x8(colors.v[tri.x]) * (1.0 - bary.x - bary.y) +
         unpackUnorm4x8(colors.v[tri.y]) * bary.x + unpackUnorm4x8(colors.v[tri.z]) * bary.y;
}

vec3 interpolateNormal(uvec3 tri, vec2 bary) {
  Vec3Array normals = Vec3Array(scene.normals);
  return normals.v[tri.x] * (1.0 - bary.x - bary.y) + normals.v[tri.y] * bary.x +
         normals.v[tri.z] * bary.y;
}

vec3 transformPoint(vec4 rows[3], vec3 p) {
  return vec3(dot(rows[0].xyz, p) + rows[0].w, dot(rows[1].xyz, p) + rows[1].w,
              dot(rows[2].xyz, p) + rows[2].w);
}

vec3 transformVector(vec4 rows[3], vec3 v) {
  return vec3(dot(rows[0].xyz, v), dot(rows[1].xyz, v), dot(rows[2].xyz, v));
}

// Normals transform with the inverse transpose: n_world = transpose(worldToObject) * n_object.
vec3 transformNormal(GpuInstance inst, vec3 n) {
  return inst.worldToObject[0].xyz * n.x + inst.worldToObject[1].xyz * n.y +
         inst.worldToObject[2].xyz * n.z;
}

#endif
