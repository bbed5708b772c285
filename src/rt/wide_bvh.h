// The 8-wide compressed BLAS layout (shared/scene_layout.h, GpuWideBvhNode; Ylitie, Karras and
// Laine 2017), built by collapsing a binned-SAH binary tree (rt/bvh_builder.h) whose leaves
// hold at most BVH_WIDE_MAX_LEAF_TRIANGLES primitives.
//
// Collapse: greedy, top down. A wide node starts from its binary node's two children and
// repeatedly opens the interior child of largest surface area (replacing it by its two
// children) until it has 8 children or only leaves: the children then cover the subtree with
// as few node visits as possible where rays most often go, the rule Embree and Wald et al. 2008
// use for their BVH4/BVH8 from a BVH2. It is O(n) and keeps the binary tree's leaves as they
// are; docs/ray-tracing.md says why it stands in for the paper's SAH-optimal dynamic program.
// Children are then placed in slots by ray octant (the paper's §3.1 cost table, assigned
// greedily), and their boxes quantised conservatively (every decoded float box contains the
// exact child box).
#pragma once
#include <cstdint>
#include <vector>

#include "rt/bvh_builder.h"
#include "scene/scene.h"
#include "shared/scene_layout.h"

namespace bounce::rt {

struct WideBvh {
  // Root at node 0; childBase indexes `nodes`, triangleBase indexes `primitiveOrder`.
  std::vector<gpu::GpuWideBvhNode> nodes;
  // Wide leaf order: primitiveOrder[i] is an index into the binary tree's input primitives.
  std::vector<uint32_t> primitiveOrder;
  uint32_t maxDepth = 0;  // in nodes, root = 1
};

// Throws bounce::Error when a leaf of `binary` holds more than BVH_WIDE_MAX_LEAF_TRIANGLES.
WideBvh collapseToWide(const Bvh& binary);

// Box of child `slot` decoded in float exactly as the traversal decodes it (origin + q * 2^e).
Aabb decodeWideChildBox(const gpu::GpuWideBvhNode& node, uint32_t slot);

// Byte `slot` of a uvec2 of eight bytes (slot 0 = low byte of x).
inline uint32_t wideByte(const gpu::uvec2& bytes, uint32_t slot) {
  return (bytes[slot >> 2] >> ((slot & 3u) * 8u)) & 0xFFu;
}

}  // namespace bounce::rt
