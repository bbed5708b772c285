// GPU layout of a scene: instances, geometries, materials, vertex streams, and the two-level
// BVH (one BLAS per mesh, a TLAS over instances). Shared by C++ (src/rt/scene_bvh.cpp writes it)
// and GLSL (shaders/rt/ reads it through buffer device addresses).
#ifndef BOUNCE_SHARED_SCENE_LAYOUT_H
#define BOUNCE_SHARED_SCENE_LAYOUT_H
#include "shared/compat.h"

BOUNCE_BEGIN_SHARED

// ---- BVH nodes --------------------------------------------------------------------------------
// A 2-wide node holds the boxes of both children, so one 64-byte fetch decides which children a
// ray enters (Aila & Laine 2009 layout). A child is either an interior node (count == 0, index =
// node index in the same node array) or a leaf (count > 0, index = first triangle in the
// triangle array for a BLAS, or the instance index for a TLAS, whose leaves hold one instance).
// An empty child has count == 0 and index == BVH_INVALID; its box is inverted so no ray hits it.
// Node 0 of each tree is its root; child indices are absolute in the array (a BLAS's nodes sit
// in one shared array at an offset given by its instances' blasRoot).
// The BLAS may instead use the 8-wide compressed layout below (GpuWideBvhNode); the TLAS is
// 2-wide in both layouts, and the triangle and instance layouts are the same.
BOUNCE_CONST uint BVH_INVALID = 0xFFFFFFFFu;
BOUNCE_CONST uint BVH_MAX_LEAF_TRIANGLES = 8u;
BOUNCE_CONST uint BVH_STACK_SIZE = 64u;
// Traversal stack entries (src/rt/scene_bvh.h, "traversal contract"): an interior node index;
// at the TLAS level, an instance index | BVH_STACK_INSTANCE; in a BLAS, a leaf:
// BVH_STACK_LEAF | (count - 1) << BVH_STACK_LEAF_COUNT_SHIFT | first triangle. Hence every
// scene has fewer than BVH_MAX_SCENE_TRIANGLES triangles and BLAS leaves at most 16.
BOUNCE_CONST uint BVH_STACK_INSTANCE = 0x80000000u;
BOUNCE_CONST uint BVH_STACK_LEAF = 0x40000000u;
BOUNCE_CONST uint BVH_STACK_LEAF_COUNT_SHIFT = 26u;
BOUNCE_CONST uint BVH_STACK_LEAF_INDEX_MASK = 0x03FFFFFFu;
BOUNCE_CONST uint BVH_MAX_SCENE_TRIANGLES = 0x04000000u;

struct GpuBvhNode {
  vec3 leftMin;
  uint leftIndex;
  vec3 leftMax;
  uint leftCount;
  vec3 rightMin;
  uint rightIndex;
  vec3 rightMax;
  uint rightCount;
};
BOUNCE_CHECK_SIZE(GpuBvhNode, 64);

// ---- the 8-wide compressed BLAS layout ---------------------------------------------------------
// After Ylitie, Karras and Laine 2017 ("Efficient incoherent ray traversal on GPUs through
// compressed wide BVHs", §3): one 80-byte node holds up to 8 children, their boxes quantised to
// 8 bits per plane on a per-node grid. Built by collapsing the binned-SAH binary tree
// (src/rt/wide_bvh.h); docs/ray-tracing.md has the whole story.
//
// Grid: the node's box starts at `origin`; along axis a the grid step is 2^e_a, e_a the signed
// exponent stored biased by 127 in byte a of `exponentsAndMask` (so the step's float bits are
// byte << 23). A child's box decodes to origin + q * 2^e per plane (q the 8-bit quantised
// plane); q * 2^e is exact in float, so the decoded plane is one rounding of that sum, and the
// builder chooses every q so that the decoded float box contains the child's exact box
// (conservative: a slab test on the decoded box never culls a hit on the child's triangles).
// Children: slot i (0..7) is byte i of `meta`, `quantLo*`, `quantHi*` (byte i of a uvec2 is
// byte i % 4 of word i / 4, little end first). meta byte of a slot:
//   empty     0: skipped by the traversal (its quantised planes are 0 and mean nothing)
//   interior  BVH_WIDE_INTERIOR_META + i (= 1 << 5 | (24 + i), the paper's encoding); bit i of
//             the interior mask (byte 3 of `exponentsAndMask`) is set, and the child node is
//             childBase + the number of interior slots below i
//   leaf      (unary triangle count: 1, 3 or 7) << 5 | offset; its triangles are
//             triangles[triangleBase + offset .. + count), count <= BVH_WIDE_MAX_LEAF_TRIANGLES,
//             offset + count <= 24, so a node's leaf triangles fit 24 bits of a hit mask.
// Interior children of a node are contiguous from childBase; its leaf triangles contiguous from
// triangleBase (absolute indices, already offset when the per-mesh trees are concatenated).
// Slot order: the child in slot i is the one a ray whose direction lies in octant i reaches
// first (octant bit 0: x < 0, bit 1: y < 0, bit 2: z < 0), so a ray visits the interior
// children hit in the order slot ^ octant = 0, 1, .. 7 without sorting by distance.
BOUNCE_CONST uint BVH_WIDE_MAX_LEAF_TRIANGLES = 3u;
BOUNCE_CONST uint BVH_WIDE_EXPONENT_BIAS = 127u;
BOUNCE_CONST uint BVH_WIDE_INTERIOR_META = 0x38u;  // meta of slot i: 0x38 + i (= 32 | 24 + i)
// Traversal stack of the wide BLAS (node groups: child base, hit bits | interior mask); each
// level pushes at most one entry and a tree is at most BVH_STACK_SIZE / 2 levels deep.
BOUNCE_CONST uint BVH_WIDE_STACK_SIZE = 32u;

struct GpuWideBvhNode {
  vec3 origin;
  uint exponentsAndMask;  // bytes 0..2: biased exponents of x, y, z; byte 3: interior mask
  uint childBase;         // first child node (blasNodes index)
  uint triangleBase;      // first leaf triangle (triangles index)
  uvec2 meta;
  uvec2 quantLoX;
  uvec2 quantLoY;
  uvec2 quantLoZ;
  uvec2 quantHiX;
  uvec2 quantHiY;
  uvec2 quantHiZ;
};
BOUNCE_CHECK_SIZE(GpuWideBvhNode, 80);

// GpuSceneRefs::blasLayout: which node layout blasNodes holds.
BOUNCE_CONST uint BVH_LAYOUT_BINARY = 0u;  // GpuBvhNode
BOUNCE_CONST uint BVH_LAYOUT_WIDE = 1u;    // GpuWideBvhNode
// Specialization constant 0 of every pipeline that traces (GpuScene::specialization()): the
// scene's layout, so the driver compiles one traversal loop, not both (the second loop doubled
// lavapipe's compile time and sets the registers of the binary loop on a GPU). A pipeline created
// without it keeps BVH_LAYOUT_ANY and reads blasLayout per ray.
BOUNCE_CONST uint BVH_SPEC_BLAS_LAYOUT = 0u;
BOUNCE_CONST uint BVH_LAYOUT_ANY = 2u;
// A pass's own specialization constants follow the scene's, from this id on (ComputePass).
BOUNCE_CONST uint PASS_SPEC_FIRST = 1u;

// Triangles in BVH leaf order with their positions copied in (object space), so the
// intersection loop touches one array. `geometry` holds the geometry index local to the mesh
// in its low 31 bits and GPU_TRIANGLE_ALPHA_TESTED in the top bit.
BOUNCE_CONST uint GPU_TRIANGLE_ALPHA_TESTED = 0x80000000u;
// 48 bytes, each vertex in its own 16-byte quarter, so that the traversal fetches a triangle
// as three 128-bit loads (shaders/rt/scene.glsl, loadTriangle).
struct GpuTriangle {
  vec3 v0;
  uint primitive;  // triangle index within its geometry (glTF primitive)
  vec3 v1;
  uint geometry;
  vec3 v2;
  uint padding;
};
BOUNCE_CHECK_SIZE(GpuTriangle, 48);

// One placed mesh. Transforms are affine, stored as the three rows of a 3x4 matrix.
// GPU_INSTANCE_HIDDEN: the placement is singular (a scale of 0, how glTF animations hide
// objects); both matrices are then zero and the TLAS leaves the instance out, so no ray and no
// raster draw can reach it until a later placement is invertible again.
BOUNCE_CONST uint GPU_INSTANCE_HIDDEN = 1u;
struct GpuInstance {
  vec4 objectToWorld[3];
  vec4 worldToObject[3];
  uint blasRoot;      // index of the mesh's BLAS root in the BLAS node array
  uint geometryBase;  // global index of the mesh's geometry 0 in the geometry array
  uint mesh;
  uint flags;
};
BOUNCE_CHECK_SIZE(GpuInstance, 112);

// One glTF primitive: a triangle list with its material. Indices are relative to vertexOffset
// in the scene's shared vertex streams.
struct GpuGeometry {
  uint firstIndex;
  uint vertexOffset;
  uint triangleCount;
  uint material;
};
BOUNCE_CHECK_SIZE(GpuGeometry, 16);

// ---- materials and textures ---------------------------------------------------------------------
// Textures live in 2D array images, one per (size class, encoding), because lavapipe 22.3 has
// no descriptor indexing (DESIGN.md §1). A texture reference packs the layer (bits 0-15), the
// size class (bits 16-19: side 64 << class) and the encoding (bit 20: sRGB). NO_TEXTURE = none.
BOUNCE_CONST uint NO_TEXTURE = 0xFFFFFFFFu;
BOUNCE_CONST uint TEXTURE_SIZE_CLASSES = 6u;  // 64, 128, 256, 512, 1024, 2048
BOUNCE_CONST uint TEXTURE_MIN_SIZE = 64u;
BOUNCE_CONST uint TEXTURE_SRGB_BIT = 0x100000u;

BOUNCE_CONST uint MATERIAL_DOUBLE_SIDED = 1u;
BOUNCE_CONST uint MATERIAL_ALPHA_MASK = 2u;
BOUNCE_CONST uint MATERIAL_ALPHA_BLEND = 4u;  // treated as mask at cutoff 0.5 by the tracer

struct GpuMaterial {
  vec4 baseColor;  // linear RGBA factor
  vec3 emissive;   // linear radiance factor, emissive_strength folded in
  float metallic;
  float roughness;
  float alphaCutoff;
  float normalScale;
  uint flags;
  uint baseColorTexture;
  uint metallicRoughnessTexture;
  uint normalTexture;
  uint emissiveTexture;
};
BOUNCE_CHECK_SIZE(GpuMaterial, 64);

// ---- the scene as the shaders see it ---------------------------------------------------------
// Addresses of every scene array; bound as a uniform buffer at (set 0, binding 0).
struct GpuSceneRefs {
  DeviceAddress blasNodes;   // GpuBvhNode[] or GpuWideBvhNode[] (blasLayout)
  DeviceAddress triangles;   // GpuTriangle[]
  DeviceAddress tlasNodes;   // GpuBvhNode[]
  DeviceAddress instances;   // GpuInstance[]
  DeviceAddress geometries;  // GpuGeometry[]
  DeviceAddress materials;   // GpuMaterial[]
  DeviceAddress indices;     // uint[]
  DeviceAddress positions;   // vec3[]
  DeviceAddress normals;     // vec3[]
  DeviceAddress uvs;         // vec2[]
  DeviceAddress tangents;    // vec4[] (xyz tangent, w handedness)
  // uint[] per vertex: glTF COLOR_0 as RGBA8 unorm (R in the low byte, unpackUnorm4x8), white
  // for geometries without it; 0 when no geometry of the scene has vertex colours.
  DeviceAddress colors;
  uint instanceCount;
  uint geometryCount;
  uint materialCount;
  uint triangleCount;
  vec3 boundsMin;
  // Non-zero: every traceClosest/traceVisibility adds one to *rayCounter (GpuScene::
  // setRayCounting; `bounce bench` reports rays per pass with it).
  uint rayCounting;
  vec3 boundsMax;
  // BVH_LAYOUT_BINARY or BVH_LAYOUT_WIDE: the layout of blasNodes (the TLAS is always 2-wide).
  // Read once per ray, uniformly (shaders/rt/trace.glsl).
  uint blasLayout;
  DeviceAddress rayCounter;  // uint, zeroed per frame by vk::GpuTimer
  // vec3[]: last frame's positions, for motion vectors of deforming meshes (scene-deform keeps
  // them); the same address as `positions` in a scene where nothing deforms.
  DeviceAddress previousPositions;
};
BOUNCE_CHECK_SIZE(GpuSceneRefs, 160);

BOUNCE_CONST uint SCENE_SET = 0u;
BOUNCE_CONST uint SCENE_BINDING_REFS = 0u;
// Bindings 1 .. 2*TEXTURE_SIZE_CLASSES: sampler2DArray per (encoding, class); binding
// 1 + class for linear, 1 + TEXTURE_SIZE_CLASSES + class for sRGB.
BOUNCE_CONST uint SCENE_BINDING_TEXTURES = 1u;

BOUNCE_END_SHARED
#endif
