// What the deforming-mesh passes read and write (src/rt/gpu_deformer.h): `scene-deform`
// (shaders/rt/scene_deform.comp) poses every vertex of the deforming meshes into the scene's
// vertex streams, then `scene-refit-blas` (shaders/rt/scene_refit_blas.comp) copies the posed
// positions into those meshes' triangles and refits their BLAS boxes, deepest level first.
// The CPU mirror of the pose is src/scene/deformation.cpp.
#ifndef BOUNCE_SHARED_DEFORM_IO_H
#define BOUNCE_SHARED_DEFORM_IO_H
#include "shared/compat.h"

BOUNCE_BEGIN_SHARED

BOUNCE_CONST uint DEFORM_NO_SKIN = 0xFFFFFFFFu;

// One geometry of a deforming mesh.
struct GpuDeformGeometry {
  uint firstVertex;  // its first vertex in the scene's vertex streams
  uint vertexCount;
  uint restBase;   // its first vertex in the rest arrays (deforming vertices only)
  uint jointBase;  // its skin's first joint matrix; DEFORM_NO_SKIN = not skinned
  uint morphBase;  // delta of target k, vertex i: deltas[morphBase + k * vertexCount + i]
  uint morphCount;
  uint weightBase;  // its mesh's first weight in the morph weights
  uint pad0;
};
BOUNCE_CHECK_SIZE(GpuDeformGeometry, 32);

// A vertex before posing: the mesh's own (bind-pose) streams, and its four joints (16 bits
// each, two to a word) and weights.
struct GpuDeformVertex {
  vec3 position;
  uint joints01;
  vec3 normal;
  uint joints23;
  vec4 tangent;
  vec4 weights;
};
BOUNCE_CHECK_SIZE(GpuDeformVertex, 64);

struct GpuMorphDelta {
  vec3 position;
  vec3 normal;
  vec3 tangent;
};
BOUNCE_CHECK_SIZE(GpuMorphDelta, 36);

struct DeformConstants {
  DeviceAddress geometries;        // GpuDeformGeometry[]
  DeviceAddress geometryOfVertex;  // uint[] per rest vertex: its GpuDeformGeometry
  DeviceAddress rest;              // GpuDeformVertex[]
  DeviceAddress deltas;            // GpuMorphDelta[]
  DeviceAddress jointRows;         // vec4[3 * joints]: rows of the affine joint matrices
  DeviceAddress morphWeights;      // float[]
  DeviceAddress positions;         // the scene's streams (GpuSceneRefs), rewritten
  DeviceAddress previousPositions;
  DeviceAddress normals;
  DeviceAddress tangents;
  uint vertexCount;  // rest vertices
  // 0: the previous positions become the new pose too (the first pose: no motion from the
  // bind pose); 1: they keep the pose before this one.
  uint keepPrevious;
};
BOUNCE_CHECK_SIZE(DeformConstants, 88);

BOUNCE_CONST uint DEFORM_GROUP_SIZE = 64u;

// One deforming mesh's BLAS: refitted by one workgroup.
struct GpuRefitBlas {
  uint triangleFirst;  // its triangles in the scene's triangle array (BLAS leaf order)
  uint triangleCount;
  uint geometryBase;  // global index of its geometry 0
  uint mesh;          // Scene mesh index (its box in meshBounds)
  uint root;          // its BLAS root in the node array
  uint planFirst;     // its plan: interior nodes deepest level first, in plan[planFirst ..]
  uint levelStart;    // where its levels + 1 level starts begin in plan
  uint levels;
};
BOUNCE_CHECK_SIZE(GpuRefitBlas, 32);

struct BlasRefitConstants {
  DeviceAddress meshes;      // GpuRefitBlas[]
  DeviceAddress plan;        // uint[]
  DeviceAddress blasNodes;   // GpuBvhNode[] or GpuWideBvhNode[] (layout)
  DeviceAddress wideBoxes;   // BVH_LAYOUT_WIDE: vec4[2 * nodes], each wide node's exact box
  DeviceAddress triangles;   // GpuTriangle[]
  DeviceAddress geometries;  // GpuGeometry[]
  DeviceAddress indices;     // uint[]
  DeviceAddress positions;   // vec3[], posed
  DeviceAddress meshBounds;  // vec4[2 * meshes]: the TLAS refit's object-space mesh boxes
  uint blasLayout;           // BVH_LAYOUT_BINARY or BVH_LAYOUT_WIDE
  uint pad0;
};
BOUNCE_CHECK_SIZE(BlasRefitConstants, 80);

BOUNCE_CONST uint BLAS_REFIT_GROUP_SIZE = 256u;

BOUNCE_END_SHARED
#endif
