// Binned-SAH BVH construction on the CPU (Wald 2007, "On fast construction of SAH-based
// bounding volume hierarchies"), writing the 2-wide GPU node layout of shared/scene_layout.h
// directly. Used for every BLAS (one per mesh, leaves of up to BVH_MAX_LEAF_TRIANGLES
// triangles) and for the per-frame TLAS (leaves of one instance).
//
// The output is deterministic: the same input gives the same nodes and primitive order for any
// thread count. Split decisions never depend on threading (binning merges exact min/max and
// integer counts; partitions are sequential), and nodes are numbered in depth-first pre-order
// (a node, then its whole left subtree, then its right subtree) however subtrees were
// scheduled.
#pragma once
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "scene/scene.h"
#include "shared/scene_layout.h"

namespace bounce::rt {

struct BvhBuildOptions {
  // Largest leaf; a range this small becomes a leaf unless the SAH finds a cheaper split.
  // BVH_MAX_LEAF_TRIANGLES for a BLAS, 1 for a TLAS.
  uint32_t maxLeafSize = gpu::BVH_MAX_LEAF_TRIANGLES;
  // SAH bins per axis (2 .. 64). A few tens of bins come close to a full SAH sweep (Wald
  // 2007); on a 200k-triangle mesh 16 bins gave an SAH cost 0.8% above 32 bins, 8 bins 1.6%.
  // Ranges under 32 primitives use at most 8 (bvh_builder.cpp, kFewBins).
  uint32_t binCount = 16;
  // Cost of visiting a node relative to intersecting one primitive (SAH constant C_t / C_i).
  float traversalCost = 1.0f;
  // Longest root-to-leaf path, counted in nodes. The default leaves half of the traversal
  // stack (BVH_STACK_SIZE) to each level, so a traversal that keeps TLAS and BLAS entries on one
  // stack never overflows. Where the SAH would go deeper, the builder splits at the object
  // median instead.
  uint32_t maxDepth = gpu::BVH_STACK_SIZE / 2;
  // Threads used, the calling thread included; 0 = std::thread::hardware_concurrency(). Small
  // inputs are built on the calling thread alone, where threads would cost more than they save.
  uint32_t threadCount = 0;
  // Fill the tree statistics (SAH cost, depth, leaf count) with a pass over the finished tree;
  // a per-frame TLAS that does not report them can skip it.
  bool measureTree = true;
};

// Options for a TLAS: one instance per leaf.
BvhBuildOptions tlasBuildOptions();

struct BvhBuildStats {
  double seconds = 0.0;              // wall time of the build (without the measuring pass)
  double primitivesPerSecond = 0.0;  // primitives / seconds (triangles/s for a BLAS)
  uint32_t primitiveCount = 0;
  uint32_t nodeCount = 0;
  uint32_t threadsUsed = 1;
  // The rest is filled only with BvhBuildOptions::measureTree.
  uint32_t leafCount = 0;
  uint32_t maxDepth = 0;  // in nodes, root = 1
  // SAH cost of the tree: sum over nodes of traversalCost * P(node) plus sum over leaves of
  // primitives * P(leaf), where P is the surface area relative to the root's. Lower is better.
  double sahCost = 0.0;
};

struct Bvh {
  // Root at node 0. A leaf child's index points into `primitiveOrder` (first of `count`).
  std::vector<gpu::GpuBvhNode> nodes;
  // Leaf ranges index into this: primitiveOrder[i] is an index into the input spans.
  std::vector<uint32_t> primitiveOrder;
  BvhBuildStats stats;
};

// Working memory of a build (the builder's two arrays of primitive references, 96 bytes per
// primitive), kept between builds: a caller that builds many BVHs one after another
// (buildSceneBvh, one BLAS per mesh) then touches fresh pages only once, where page faults
// cost about a seventh of the build. One build at a time may use a scratch.
class BvhScratch {
 public:
  // At least `bytes` bytes, 64-byte aligned; the last block when it is large enough.
  void* reserve(size_t bytes);

 private:
  struct Free {
    void operator()(void* p) const;
  };
  std::unique_ptr<void, Free> block_;
  size_t bytes_ = 0;
};

// Builds a BVH over primitives given by their bounds and centroids (the point used to bin
// them; for triangles, the vertex average or the box centre). Zero primitives give a root whose
// two children are empty. Throws bounce::Error on NaN or infinite input, a box with
// min > max, mismatched span sizes, invalid options, or more primitives than maxDepth allows.
// `scratch`, when given, provides the working memory (else the build allocates its own).
Bvh buildBvh(std::span<const Aabb> boxes, std::span<const glm::vec3> centroids,
             const BvhBuildOptions& options = {}, BvhScratch* scratch = nullptr);

// A child slot that nothing can hit: count 0, index BVH_INVALID and an inverted box.
void setEmptyChild(gpu::GpuBvhNode& node, bool right);

// Surface-area statistics of an existing tree whose leaf children index a primitive array
// (SAH cost, leaves, depth); used by buildBvh and by tests.
BvhBuildStats measureBvh(std::span<const gpu::GpuBvhNode> nodes, uint32_t root,
                         float traversalCost);

}  // namespace bounce::rt
