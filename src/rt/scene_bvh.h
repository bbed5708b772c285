// Everything the GPU tracer needs from a Scene, as plain arrays in the layouts of
// shared/scene_layout.h: one BLAS per mesh, the triangles in BLAS leaf order, the flattened
// vertex streams, the instances and a TLAS over them. The renderer uploads the vectors as they
// are and rebuilds only the TLAS (buildTlas) when instances move.
//
// ==== Node layout and traversal contract (what shaders/rt/ must do) ============================
//
// Arrays: tlasNodes, blasNodes (GpuBvhNode), triangles (GpuTriangle), instances (GpuInstance).
// Roots: the TLAS root is tlasNodes[0]; instance i's BLAS root is blasNodes[instances[i].blasRoot].
//
// A node holds two child slots (left, right); each slot is one of
//   interior  count == 0, index != BVH_INVALID: index = a node in the same array. BLAS indices
//             are absolute in blasNodes (already offset when the per-mesh BLAS were
//             concatenated), so no per-instance base is added.
//   leaf      count > 0. BLAS: triangles[index .. index + count), count <= BVH_MAX_LEAF_TRIANGLES.
//             TLAS: count == 1, index = the instance index.
//   empty     count == 0, index == BVH_INVALID, box min = +1e30 > max = -1e30. Only a root
//             has one (a tree over 0 or 1 primitives; an empty mesh, a scene with no
//             instances). A traversal must never follow it.
// Child boxes are in the space of the tree: world space for the TLAS, object space for a BLAS.
// Every tree is at most maxDepth = BVH_STACK_SIZE / 2 nodes deep, so one stack of
// BVH_STACK_SIZE entries shared by both levels cannot overflow (see below).
//
// Box test (per child, both children of a fetched node):
//   invDir = 1 / dir, with components whose magnitude is below 1e-20 replaced by +-1e-20 (the
//   sign of the component; -0 counts as +) so no 0 * inf NaN appears;
//   near/far planes per axis are chosen by the sign of invDir (invDir < 0: near = max), NOT by
//   min/max of the two plane distances. With this rule the inverted empty box always gives
//   tNear > tFar, so empty slots need no special case; a min/max-swapping slab test would
//   instead treat the empty box as the whole space.
//   plane distances are (plane - origin) * invDir;
//   tNear = max(tMin, near distances), tFar = min(tMax, far distances * (1 + 2 * gamma(3)))
//   where 1 + 2 * gamma(3) = 1.0000004 (Ize 2013, "Robust BVH ray traversal": makes the
//   float slab test conservative, so a hit the watertight triangle test finds is never culled).
//   Ize's bound is derived for that form. The precomputed form plane * invDir - origin *
//   invDir is fine only unfused: contracted into fma(plane, invDir, -origin * invDir) (what GPU
//   compilers do unless told `precise`) it rejected 14% of rays aimed at the edges of a 1 cm box
//   1 km from the world origin in a CPU experiment, against none for the other two forms.
//   The child is entered when tNear <= tFar.
//
// Traversal (cpu_trace.cpp is the reference implementation; it mirrors this step by step):
//   - One stack of BVH_STACK_SIZE uint entries (shared/scene_layout.h, BVH_STACK_*). An entry is
//     an interior node index of the current level; at the TLAS level, an instance index with
//     BVH_STACK_INSTANCE set; at the BLAS level, a leaf: BVH_STACK_LEAF | (count - 1) << 26 |
//     first triangle (so a scene has fewer than 2^26 triangles, a leaf at most 16).
//   - The loop runs in three steps (Aila and Laine 2009, "while-while"): (1) interior nodes:
//     visiting one tests both child boxes; hit children (interior, leaf or instance entries)
//     are ordered by tNear, ties to the left: with two, push the far one and continue with the
//     near one; with one, continue with it; with none, pop (within the level). (2) While the
//     entry is a BLAS leaf, intersect its triangles, then pop (within the level). (3) With no
//     entry left in the level, change level or stop (below); with an instance entry, enter it.
//     Popped entries are not re-tested against a tMax that leaf hits shortened since.
//   - Popping at the BLAS level when the stack is back at the height it had when the BLAS was
//     entered returns to the TLAS level (world-space ray). An empty stack at the TLAS level
//     ends the traversal.
//   - Entering an instance: transform the ray by instances[i].worldToObject (origin as a point,
//     direction as a vector, the direction NOT normalised), so t is the same in world and
//     object space and tMax carries over unchanged; recompute invDir and the triangle test's
//     shear; remember the stack height; continue at blasRoot.
//   - Triangles: intersectTriangle from shared/ray_triangle.h on (tMin, tMax) in object space.
//     A triangle with GPU_TRIANGLE_ALPHA_TESTED in `geometry` is accepted only if the alpha test
//     accepts it (alpha-tested materials); closest hit then sets tMax = t, any hit returns.
//   - Reported hit: instance; geometry = instance.geometryBase + (geometry & 0x7FFFFFFF) (the
//     global index into geometries); primitive; barycentrics b1, b2 (weights of v1, v2);
//     frontFacing = the triangle test's frontFacing, flipped when the instance's transform
//     mirrors (det(worldToObject 3x3) < 0), matching glTF's rule for negative-determinant
//     nodes.
//
// ==== Wide BLAS traversal (BvhLayout::Wide; Ylitie, Karras and Laine 2017, §4) ==================
//
// The TLAS part is the loop above, with instance entries only. Entering an instance runs its
// BLAS to completion with a stack of its own (BVH_WIDE_STACK_SIZE node groups), then pops the
// next TLAS entry. The same slab test (decoded planes origin + q * 2^e, then exactly the box
// test above) and triangle test are used, so the precision rules hold unchanged.
//   - octant: bit a set when the object-space invDir component a is negative; octantInv =
//     7 ^ octant.
//   - A node group is (base, bits): base = a node's childBase, bits 24..31 = the interior
//     children still to visit (child slot s sits at bit 24 + (s ^ octantInv), so the highest
//     bit is the child nearest along the ray's octant), bits 0..7 = that node's interior mask.
//     The root starts as (blasRoot, 1 << 31): bit 31 maps to a slot with no interior slot below
//     it in a zero mask, i.e. node base + 0.
//   - Loop: take the highest hit bit of the current group, clear it, push the group if hits
//     remain, fetch node base + bitCount(mask & ((1 << s) - 1)). Test its 8 children (empty
//     slots, meta 0, skipped): hit interior children set their bits in the new group
//     (childBase, bits | interior mask); hit leaves set (unary count) << offset in a triangle
//     mask. Then intersect the triangle mask's triangles (triangleBase + bit, lowest first);
//     then, if the new group has no hits left, pop (end of the BLAS when the stack is empty).
//     Popped groups are not re-tested against a shortened tMax.
// ================================================================================================
#pragma once
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "rt/bvh_builder.h"
#include "scene/scene.h"
#include "shared/scene_layout.h"

namespace bounce::rt {

// The node layout of the BLAS (the TLAS is 2-wide in both). Binary: GpuBvhNode, the layout
// described above. Wide: GpuWideBvhNode (shared/scene_layout.h), the 8-wide compressed layout
// of Ylitie et al. 2017, traversed as written under "Wide BLAS traversal" below.
enum class BvhLayout : uint32_t { Binary = gpu::BVH_LAYOUT_BINARY, Wide = gpu::BVH_LAYOUT_WIDE };

// "binary" / "wide" (the --bvh values); parseBvhLayout throws bounce::Error on anything else.
const char* bvhLayoutName(BvhLayout layout);
BvhLayout parseBvhLayout(const std::string& name);

struct SceneBvhOptions {
  // maxLeafSize defaults to BVH_MAX_LEAF_TRIANGLES; with BvhLayout::Wide it is capped at
  // BVH_WIDE_MAX_LEAF_TRIANGLES (the wide node's leaves hold at most 3 triangles).
  BvhBuildOptions blas;
  BvhBuildOptions tlas = tlasBuildOptions();  // maxLeafSize 1
  BvhLayout layout = BvhLayout::Binary;
};

struct SceneBvhStats {
  double seconds = 0.0;      // the whole buildSceneBvh call
  double blasSeconds = 0.0;  // all BLAS builds (meshes built in parallel)
  double tlasSeconds = 0.0;
  double trianglesPerSecond = 0.0;  // unique triangles / blasSeconds
  uint64_t triangleCount = 0;       // unique (per mesh) triangles
  uint32_t blasNodeCount = 0;       // of the layout built (wide nodes with BvhLayout::Wide)
  uint32_t tlasNodeCount = 0;
  uint32_t maxBlasDepth = 0;  // in nodes of the layout built
  uint32_t tlasDepth = 0;
  // SAH cost of each (binary) BLAS, averaged with the meshes' triangle counts as weights; with
  // BvhLayout::Wide, of the binary tree it was collapsed from.
  double blasSahCost = 0.0;
  double tlasSahCost = 0.0;
  // Bytes of each array as uploaded.
  struct Bytes {
    size_t blasNodes = 0 /* of either layout */, triangles = 0, tlasNodes = 0, instances = 0,
           geometries = 0;
    size_t indices = 0, positions = 0, normals = 0, uvs = 0, tangents = 0, colors = 0;
    size_t total() const {
      return blasNodes + triangles + tlasNodes + instances + geometries + indices + positions +
             normals + uvs + tangents + colors;
    }
  } bytes;
};

struct SceneBvh {
  // Per mesh, in Scene::meshes order.
  std::vector<uint32_t> blasRoot;          // index of the mesh's BLAS root in blasNodes
  std::vector<uint32_t> blasTriangleBase;  // index of the mesh's first triangle in triangles
  std::vector<uint32_t> geometryBase;      // index of the mesh's geometry 0 in geometries
  std::vector<Aabb> meshBounds;  // object-space bounds (empty for a mesh without triangles)

  BvhLayout layout = BvhLayout::Binary;
  std::vector<gpu::GpuBvhNode> blasNodes;          // BvhLayout::Binary (else empty)
  std::vector<gpu::GpuWideBvhNode> blasWideNodes;  // BvhLayout::Wide (else empty)
  std::vector<gpu::GpuTriangle> triangles;         // BLAS leaf order, object-space positions
  std::vector<gpu::GpuGeometry> geometries;        // every (mesh, geometry) in mesh order
  std::vector<uint32_t> indices;                   // relative to the geometry's vertexOffset
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;
  std::vector<glm::vec2> uvs;
  std::vector<glm::vec4> tangents;  // (1, 0, 0, 1) where a geometry has none
  // Vertex colours (glTF COLOR_0) as RGBA8 unorm, R in the low byte (GLSL unpackUnorm4x8):
  // white where a geometry has none; empty when no geometry of the scene has any.
  std::vector<uint32_t> colors;

  std::vector<gpu::GpuInstance> instances;  // in Scene::instances order
  std::vector<gpu::GpuBvhNode> tlasNodes;

  SceneBvhStats stats;
};

// Builds all of the above. Meshes' BLAS are built in parallel (a large mesh uses the threads
// itself). Throws bounce::Error for input no tracer could use: out-of-range indices or mesh
// references, NaN/infinite positions, non-finite instance transforms, more than 2^32 - 1
// triangles. An instance with a singular transform is hidden (GPU_INSTANCE_HIDDEN).
SceneBvh buildSceneBvh(const Scene& scene, const SceneBvhOptions& options = {});

// The GPU instance for a mesh placed by objectToWorld (affine; the last row is ignored).
// Throws bounce::Error when the transform is not finite; a singular one gives a hidden
// instance (GPU_INSTANCE_HIDDEN in flags, zero matrices).
gpu::GpuInstance makeGpuInstance(const glm::mat4& objectToWorld, uint32_t mesh,
                                 const SceneBvh& bvh);
// Rewrites both matrices of an instance, e.g. when it moves, and its hidden flag (set while
// the transform is singular); the TLAS must then be rebuilt.
void setInstanceTransform(gpu::GpuInstance& instance, const glm::mat4& objectToWorld);

// The TLAS over `instances`: one leaf per instance (leaf index = instance index), boxes in
// world space from meshBounds[instance.mesh] transformed by objectToWorld. Hidden instances
// and instances of meshes without triangles are left out. Cheap enough to run every frame
// (docs/ray-tracing.md has its build times; test_bvh prints them).
std::vector<gpu::GpuBvhNode> buildTlas(std::span<const gpu::GpuInstance> instances,
                                       std::span<const Aabb> meshBounds,
                                       const BvhBuildOptions& options = tlasBuildOptions(),
                                       BvhBuildStats* stats = nullptr, bool keepHidden = false);

// World-space bounds of a mesh's object-space box under the instance's objectToWorld,
// slightly enlarged to cover the rounding of the object-space ray transform.
Aabb instanceWorldBounds(const gpu::GpuInstance& instance, const Aabb& meshBounds);

// ---- refitting the TLAS for moved instances (docs/ray-tracing.md, "Moving instances") -------
// A refit keeps a TLAS's tree and rewrites its boxes for the instances' current placement: no
// rebuild, and the same work on the GPU (shaders/rt/scene_refit_tlas.comp) as here. The tree
// must have a leaf for every instance that may ever show, so it is built with hidden instances
// kept (buildRefittableTlas); a hidden instance's leaf box is empty, so no ray enters it.

// The TLAS of buildTlas, with hidden instances kept (placed at the origin for the build).
std::vector<gpu::GpuBvhNode> buildRefittableTlas(std::span<const gpu::GpuInstance> instances,
                                                 std::span<const Aabb> meshBounds);

// The order of a refit: the interior nodes by depth, deepest level first, so that each level
// reads only boxes the levels before it wrote; nodes[levelStart[l] .. levelStart[l + 1]) is
// level l. A GPU refit runs one level per step with a barrier between steps.
struct RefitPlan {
  std::vector<uint32_t> nodes;
  std::vector<uint32_t> levelStart;  // levels + 1 entries
  uint32_t levels() const { return levelStart.empty() ? 0u : uint32_t(levelStart.size() - 1); }
};
using TlasRefitPlan = RefitPlan;
TlasRefitPlan planTlasRefit(std::span<const gpu::GpuBvhNode> tlas);
// The plan of the tree rooted at `root` in a BLAS node array of either layout (absolute node
// indices), for refitting a deforming mesh's BLAS (src/rt/gpu_deformer.h).
RefitPlan planBinaryRefit(std::span<const gpu::GpuBvhNode> nodes, uint32_t root);
RefitPlan planWideRefit(std::span<const gpu::GpuWideBvhNode> nodes, uint32_t root);

// Rewrites every child box of `tlas` along `plan`: a leaf's from instanceWorldBounds (empty for
// a hidden instance), an interior child's as the union of its two child boxes.
void refitTlas(std::span<gpu::GpuBvhNode> tlas, const TlasRefitPlan& plan,
               std::span<const gpu::GpuInstance> instances, std::span<const Aabb> meshBounds);

// The SAH cost of a TLAS as it stands (measureBvh with the TLAS build's traversal cost): node
// and leaf areas relative to the root's, so it measures how well the tree fits its boxes
// whatever the scene's size. A refit that makes boxes overlap and grow raises it; GpuScene
// rebuilds the tree when it has grown by GpuSceneOptions::tlasRebuildRatio. Empty (hidden)
// boxes count as area 0. O(nodes).
double tlasSahCost(std::span<const gpu::GpuBvhNode> tlas);

// ---- rebuilding a refitted TLAS that has degraded ---------------------------------------------
// A refitted tree is only as good as the placement it was built for: instances that travel far
// from it make boxes overlap and grow. The policy (GpuScene's, tested on the CPU) refits, then
// compares the tree's SAH cost with its cost right after its last build (both relative to their
// own root's area) and rebuilds over the current placement once the ratio exceeds a limit. A
// fresh build's cost would be the exact reference, but building to find it out is what the
// refit avoids.
struct TlasRefitState {
  TlasRefitPlan plan;
  double builtCost = 0.0;  // tlasSahCost right after the last build, refitted
  double costRatio = 1.0;  // of the last update: tlasSahCost(refitted tree) / builtCost
  uint32_t rebuilds = 0;   // by updateRefittedTlas
};

// buildRefittableTlas over the instances' current placement into `tlas`, its plan, and a refit
// at once, so that `tlas` holds what any refit for this placement writes (hidden instances'
// boxes empty) and state.builtCost is the baseline for this placement.
void buildRefittedTlas(std::vector<gpu::GpuBvhNode>& tlas, TlasRefitState& state,
                       std::span<const gpu::GpuInstance> instances,
                       std::span<const Aabb> meshBounds);

// Refits `tlas` to the instances' placement (O(instances)), measures state.costRatio, and
// rebuilds (buildRefittedTlas) when it exceeds rebuildRatio > 0. Returns true when it rebuilt.
// A tree built while every instance was hidden (builtCost 0) is rebuilt as soon as one shows.
bool updateRefittedTlas(std::vector<gpu::GpuBvhNode>& tlas, TlasRefitState& state,
                        std::span<const gpu::GpuInstance> instances,
                        std::span<const Aabb> meshBounds, double rebuildRatio);

}  // namespace bounce::rt
