#include "rt/wide_bvh.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "core/error.h"

namespace bounce::rt {
namespace {

constexpr uint32_t kWidth = 8;

// One child slot of a binary node: a box and what it points at (GpuBvhNode's convention).
struct BinaryChild {
  Aabb box;
  uint32_t index = gpu::BVH_INVALID;
  uint32_t count = 0;
  bool interior() const { return count == 0; }
};

float surfaceArea(const Aabb& b) {
  const glm::vec3 e = b.extent();
  return e.x * e.y + e.y * e.z + e.z * e.x;
}

void addChild(const glm::vec3& lo, const glm::vec3& hi, uint32_t index, uint32_t count,
              std::vector<BinaryChild>& out) {
  if (count == 0 && index == gpu::BVH_INVALID) return;  // an empty slot (only at a root)
  out.push_back({Aabb{lo, hi}, index, count});
}

void addChildren(const gpu::GpuBvhNode& node, std::vector<BinaryChild>& out) {
  addChild(node.leftMin, node.leftMax, node.leftIndex, node.leftCount, out);
  addChild(node.rightMin, node.rightMax, node.rightIndex, node.rightCount, out);
}

// Greedy collapse: open the interior child of largest surface area until 8 children.
std::vector<BinaryChild> collectChildren(const Bvh& binary, uint32_t node) {
  std::vector<BinaryChild> children;
  addChildren(binary.nodes[node], children);
  while (children.size() < kWidth) {
    int best = -1;
    float bestArea = -1.0f;
    for (size_t i = 0; i < children.size(); ++i) {
      if (!children[i].interior()) continue;
      const float area = surfaceArea(children[i].box);
      if (area > bestArea) bestArea = area, best = int(i);
    }
    if (best < 0) break;
    const uint32_t opened = children[size_t(best)].index;
    children.erase(children.begin() + best);
    addChildren(binary.nodes[opened], children);
  }
  return children;
}

// Slot of each child: the paper's cost of child c in slot s is the projection of the child's
// offset from the node centre onto the direction of octant s (signs +-1). The child with the
// lowest cost lies furthest back along that direction, so rays of octant s reach it first.
// Assigned greedily, cheapest (child, slot) pair first (the paper uses an auction; with at most
// 8 x 8 pairs the difference is small and this is deterministic).
std::array<int, kWidth> assignSlots(const std::vector<BinaryChild>& children, const Aabb& node) {
  struct Pair {
    float cost;
    uint32_t child, slot;
  };
  std::vector<Pair> pairs;
  const glm::vec3 centre = node.center();
  for (uint32_t c = 0; c < children.size(); ++c) {
    const glm::vec3 offset = children[c].box.center() - centre;
    for (uint32_t s = 0; s < kWidth; ++s) {
      const glm::vec3 dir(s & 1 ? -1.0f : 1.0f, s & 2 ? -1.0f : 1.0f, s & 4 ? -1.0f : 1.0f);
      pairs.push_back({glm::dot(offset, dir), c, s});
    }
  }
  std::stable_sort(pairs.begin(), pairs.end(),
                   [](const Pair& a, const Pair& b) { return a.cost < b.cost; });
  std::array<int, kWidth> childOfSlot;
  childOfSlot.fill(-1);
  std::array<bool, kWidth> placed{};
  for (const Pair& p : pairs) {
    if (placed[p.child] || childOfSlot[p.slot] >= 0) continue;
    childOfSlot[p.slot] = int(p.child);
    placed[p.child] = true;
  }
  return childOfSlot;
}

float decodePlane(float origin, uint32_t q, float scale) {
  return origin + float(q) * scale;
}

// The per-node grid along one axis: the smallest power-of-two step 2^e for which 255 steps
// from the origin reach the node's max in float (so q = 255 always covers it).
int gridExponent(float lo, float hi) {
  const double extent = double(hi) - double(lo);
  int e = -126;  // the smallest normal step (biased exponent 1)
  if (extent > 0.0) {
    int exponent;
    std::frexp(extent / 255.0, &exponent);  // extent / 255 < 2^exponent
    e = std::max(e, exponent - 1);
  }
  while (decodePlane(lo, 255, std::ldexp(1.0f, e)) < hi) ++e;
  while (e > -126 && decodePlane(lo, 255, std::ldexp(1.0f, e - 1)) >= hi) --e;
  if (e + int(gpu::BVH_WIDE_EXPONENT_BIAS) > 254)
    fail("wide BVH: node extent {} too large", extent);
  return e;
}

void setByte(gpu::uvec2& bytes, uint32_t slot, uint32_t value) {
  bytes[slot >> 2] |= (value & 0xFFu) << ((slot & 3u) * 8u);
}

class Collapser {
 public:
  explicit Collapser(const Bvh& binary) : binary_(binary) {}

  WideBvh run() {
    out_.nodes.emplace_back();
    fill(0, 0, 1);
    return std::move(out_);
  }

 private:
  // Writes wide node `wide` from binary node `node`, then its interior children.
  void fill(uint32_t wide, uint32_t node, uint32_t depth) {
    out_.maxDepth = std::max(out_.maxDepth, depth);
    const std::vector<BinaryChild> children = collectChildren(binary_, node);
    Aabb box;
    for (const BinaryChild& c : children) box.extend(c.box);
    const std::array<int, kWidth> childOfSlot = assignSlots(children, box);

    gpu::GpuWideBvhNode n{};
    n.origin = box.empty() ? glm::vec3(0.0f) : box.min;
    glm::vec3 scale(1.0f);
    for (int axis = 0; axis < 3; ++axis) {
      const int e = box.empty() ? 0 : gridExponent(box.min[axis], box.max[axis]);
      scale[axis] = std::ldexp(1.0f, e);
      n.exponentsAndMask |= uint32_t(e + int(gpu::BVH_WIDE_EXPONENT_BIAS)) << (8 * axis);
    }
    n.childBase = uint32_t(out_.nodes.size());
    n.triangleBase = uint32_t(out_.primitiveOrder.size());

    std::vector<std::pair<uint32_t, uint32_t>> interior;  // (binary node, wide node)
    uint32_t interiorCount = 0;
    for (uint32_t slot = 0; slot < kWidth; ++slot) {
      if (childOfSlot[slot] < 0) continue;
      const BinaryChild& c = children[size_t(childOfSlot[slot])];
      quantise(n, slot, c.box, scale);
      if (c.interior()) {
        setByte(n.meta, slot, gpu::BVH_WIDE_INTERIOR_META + slot);
        n.exponentsAndMask |= 1u << (24 + slot);
        interior.push_back({c.index, n.childBase + interiorCount++});
      } else {
        if (c.count > gpu::BVH_WIDE_MAX_LEAF_TRIANGLES)
          fail("wide BVH: a binary leaf of {} triangles (at most {})", c.count,
               gpu::BVH_WIDE_MAX_LEAF_TRIANGLES);
        const uint32_t offset = uint32_t(out_.primitiveOrder.size()) - n.triangleBase;
        const uint32_t unary = (1u << c.count) - 1u;
        setByte(n.meta, slot, unary << 5 | offset);
        for (uint32_t k = 0; k < c.count; ++k)
          out_.primitiveOrder.push_back(binary_.primitiveOrder[c.index + k]);
      }
    }
    out_.nodes.resize(out_.nodes.size() + interiorCount);
    out_.nodes[wide] = n;
    for (const auto& [binaryNode, wideNode] : interior) fill(wideNode, binaryNode, depth + 1);
  }

  // Smallest grid box around `exact` whose float decode contains it: round outwards, then step
  // further out where the float sum origin + q * 2^e rounded inwards.
  static void quantise(gpu::GpuWideBvhNode& n, uint32_t slot, const Aabb& exact,
                       const glm::vec3& scale) {
    gpu::uvec2* lo[3] = {&n.quantLoX, &n.quantLoY, &n.quantLoZ};
    gpu::uvec2* hi[3] = {&n.quantHiX, &n.quantHiY, &n.quantHiZ};
    for (int axis = 0; axis < 3; ++axis) {
      const double o = n.origin[axis], s = scale[axis];
      auto clampQ = [](double q) { return uint32_t(std::clamp(q, 0.0, 255.0)); };
      uint32_t qlo = clampQ(std::floor((double(exact.min[axis]) - o) / s));
      uint32_t qhi = clampQ(std::ceil((double(exact.max[axis]) - o) / s));
      while (qlo > 0 && decodePlane(n.origin[axis], qlo, scale[axis]) > exact.min[axis]) --qlo;
      while (qhi < 255 && decodePlane(n.origin[axis], qhi, scale[axis]) < exact.max[axis]) ++qhi;
      setByte(*lo[axis], slot, qlo);
      setByte(*hi[axis], slot, qhi);
    }
  }

  const Bvh& binary_;
  WideBvh out_;
};

}  // namespace

WideBvh collapseToWide(const Bvh& binary) {
  if (binary.nodes.empty()) fail("wide BVH: the binary tree has no root");
  return Collapser(binary).run();
}

Aabb decodeWideChildBox(const gpu::GpuWideBvhNode& node, uint32_t slot) {
  const gpu::uvec2* lo[3] = {&node.quantLoX, &node.quantLoY, &node.quantLoZ};
  const gpu::uvec2* hi[3] = {&node.quantHiX, &node.quantHiY, &node.quantHiZ};
  Aabb box;
  for (int axis = 0; axis < 3; ++axis) {
    const uint32_t biased = (node.exponentsAndMask >> (8 * axis)) & 0xFFu;
    const float scale = std::ldexp(1.0f, int(biased) - int(gpu::BVH_WIDE_EXPONENT_BIAS));
    box.min[axis] = decodePlane(node.origin[axis], wideByte(*lo[axis], slot), scale);
    box.max[axis] = decodePlane(node.origin[axis], wideByte(*hi[axis], slot), scale);
  }
  return box;
}

}  // namespace bounce::rt
