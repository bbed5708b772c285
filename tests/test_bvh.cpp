// The CPU BVH: structural invariants of built trees on random and degenerate input,
// determinism across thread counts, the CPU traversal of the GPU arrays against brute force on
// random multi-instance scenes (with and without an alpha test), TLAS rebuilds after moves, the
// wide compressed BLAS (its encoding, conservative quantisation, and traversal against brute
// force and the binary layout) and build throughput (printed, not asserted).
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "core/error.h"
#include "rt/bvh_builder.h"
#include "rt/cpu_trace.h"
#include "rt/scene_bvh.h"
#include "rt/wide_bvh.h"
#include "scene/load.h"

namespace bounce::rt {
namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();

// ---- inputs -----------------------------------------------------------------------------------

struct Triangle {
  glm::vec3 a, b, c;
};

struct Primitives {
  std::vector<Aabb> boxes;
  std::vector<glm::vec3> centroids;
  void add(const Triangle& t) {
    Aabb box;
    box.extend(t.a);
    box.extend(t.b);
    box.extend(t.c);
    boxes.push_back(box);
    centroids.push_back((t.a + t.b + t.c) / 3.0f);
  }
};

glm::vec3 randomPoint(std::mt19937& rng, float lo, float hi) {
  std::uniform_real_distribution<float> u(lo, hi);
  return {u(rng), u(rng), u(rng)};
}

// Triangles of size about `size` scattered through a cube of side `extent`.
std::vector<Triangle> triangleSoup(size_t count, uint32_t seed, float extent = 10.0f,
                                   float size = 0.5f) {
  std::mt19937 rng(seed);
  std::vector<Triangle> triangles(count);
  for (Triangle& t : triangles) {
    t.a = randomPoint(rng, -extent / 2, extent / 2);
    t.b = t.a + randomPoint(rng, -size, size);
    t.c = t.a + randomPoint(rng, -size, size);
  }
  return triangles;
}

Primitives primitivesOf(const std::vector<Triangle>& triangles) {
  Primitives p;
  for (const Triangle& t : triangles) p.add(t);
  return p;
}

// A closed bumpy sphere tessellated in latitude and longitude: about 2 * side^2 triangles of
// a connected surface, the shape of real meshes (unlike a soup).
std::vector<Triangle> bumpySphere(int side, float radius = 10.0f) {
  auto point = [&](int i, int j) {
    float theta = 3.14159265f * float(i) / float(side);
    float phi = 6.2831853f * float(j) / float(side);
    float r = radius * (1.0f + 0.05f * std::sin(7.0f * theta) * std::cos(5.0f * phi));
    return r * glm::vec3(std::sin(theta) * std::cos(phi), std::cos(theta),
                         std::sin(theta) * std::sin(phi));
  };
  std::vector<Triangle> triangles;
  triangles.reserve(size_t(2) * side * side);
  for (int i = 0; i < side; ++i)
    for (int j = 0; j < side; ++j) {
      glm::vec3 p00 = point(i, j), p01 = point(i, j + 1), p10 = point(i + 1, j),
                p11 = point(i + 1, j + 1);
      triangles.push_back({p00, p10, p11});
      triangles.push_back({p00, p11, p01});
    }
  return triangles;
}

// ---- invariants -------------------------------------------------------------------------------

bool contains(const glm::vec3& outerMin, const glm::vec3& outerMax, const Aabb& inner) {
  return glm::all(glm::lessThanEqual(outerMin, inner.min)) &&
         glm::all(glm::lessThanEqual(inner.max, outerMax));
}

// Walks the tree from the root and checks everything the GPU traversal relies on. Returns the
// union of the primitives below each visited slot to check the boxes bottom-up.
class InvariantChecker {
 public:
  InvariantChecker(const Bvh& bvh, const Primitives& input, const BvhBuildOptions& options)
      : bvh_(bvh), input_(input), options_(options) {}

  void check() {
    const size_t n = input_.boxes.size();
    ASSERT_FALSE(bvh_.nodes.empty());
    ASSERT_EQ(bvh_.primitiveOrder.size(), n);
    ASSERT_LE(bvh_.nodes.size(), std::max<size_t>(1, n - (n > 0 ? 1 : 0)));
    visited_.assign(bvh_.nodes.size(), false);
    covered_.assign(n, 0);
    visitNode(0, 1);
    if (::testing::Test::HasFatalFailure()) return;
    // Every node reachable (none orphaned), every primitive in exactly one leaf.
    EXPECT_EQ(std::count(visited_.begin(), visited_.end(), true), long(bvh_.nodes.size()));
    for (size_t i = 0; i < n; ++i) ASSERT_EQ(covered_[i], 1) << "leaf slot " << i;
    std::vector<uint32_t> sorted = bvh_.primitiveOrder;
    std::sort(sorted.begin(), sorted.end());
    for (size_t i = 0; i < n; ++i) ASSERT_EQ(sorted[i], i) << "primitive order is no permutation";
    const gpu::GpuBvhNode& root = bvh_.nodes[0];
    if (n == 0) {
      EXPECT_TRUE(isEmpty(root.leftIndex, root.leftCount));
      EXPECT_TRUE(isEmpty(root.rightIndex, root.rightCount));
    }
  }

 private:
  static bool isEmpty(uint32_t index, uint32_t count) {
    return count == 0 && index == gpu::BVH_INVALID;
  }

  Aabb visitNode(uint32_t node, uint32_t depth) {
    Aabb bounds;
    EXPECT_LT(node, bvh_.nodes.size());
    if (node >= bvh_.nodes.size()) return bounds;
    EXPECT_FALSE(visited_[node]) << "node " << node << " reached twice (cycle or shared child)";
    if (visited_[node]) return bounds;
    visited_[node] = true;
    EXPECT_LE(depth, options_.maxDepth);
    const gpu::GpuBvhNode& n = bvh_.nodes[node];
    bounds.extend(visitSlot(node, n.leftMin, n.leftMax, n.leftIndex, n.leftCount, depth));
    bounds.extend(visitSlot(node, n.rightMin, n.rightMax, n.rightIndex, n.rightCount, depth));
    return bounds;
  }

  Aabb visitSlot(uint32_t node, const glm::vec3& lo, const glm::vec3& hi, uint32_t index,
                 uint32_t count, uint32_t depth) {
    Aabb contents;
    if (isEmpty(index, count)) {
      EXPECT_EQ(node, 0u) << "only a root may have an empty slot";
      EXPECT_TRUE(glm::all(glm::greaterThan(lo, hi))) << "empty slot box must be inverted";
      return contents;
    }
    if (count == 0) {
      EXPECT_GT(index, node) << "children follow their parent (pre-order)";
      contents = visitNode(index, depth + 1);
    } else {
      EXPECT_LE(count, options_.maxLeafSize);
      EXPECT_LE(size_t(index) + count, bvh_.primitiveOrder.size());
      for (uint32_t k = index; k < index + count && k < covered_.size(); ++k) {
        ++covered_[k];
        uint32_t primitive = bvh_.primitiveOrder[k];
        if (primitive < input_.boxes.size()) contents.extend(input_.boxes[primitive]);
      }
    }
    EXPECT_TRUE(contents.empty() || contains(lo, hi, contents))
        << "slot box of node " << node << " does not contain its subtree";
    return contents;
  }

  const Bvh& bvh_;
  const Primitives& input_;
  const BvhBuildOptions& options_;
  std::vector<bool> visited_;
  std::vector<int> covered_;
};

void expectValidTree(const Primitives& input, BvhBuildOptions options) {
  Bvh bvh = buildBvh(input.boxes, input.centroids, options);
  InvariantChecker(bvh, input, options).check();
  EXPECT_EQ(bvh.stats.primitiveCount, input.boxes.size());
  EXPECT_EQ(bvh.stats.nodeCount, bvh.nodes.size());
}

BvhBuildOptions leafSize(uint32_t maxLeaf) {
  BvhBuildOptions options;
  options.maxLeafSize = maxLeaf;
  return options;
}

// ---- builder ----------------------------------------------------------------------------------

TEST(BvhBuilder, RandomSoupsOfManySizesAreValid) {
  for (size_t n : {0, 1, 2, 7, 1000, 100000}) {
    SCOPED_TRACE("n = " + std::to_string(n));
    Primitives input = primitivesOf(triangleSoup(n, uint32_t(n) + 1));
    expectValidTree(input, leafSize(gpu::BVH_MAX_LEAF_TRIANGLES));
    expectValidTree(input, leafSize(1));
  }
}

TEST(BvhBuilder, MeshSurfaceIsValid) {
  Primitives input = primitivesOf(bumpySphere(100));
  expectValidTree(input, leafSize(gpu::BVH_MAX_LEAF_TRIANGLES));
}

TEST(BvhBuilder, ZeroPrimitivesGiveAnEmptyRoot) {
  Bvh bvh = buildBvh({}, {}, {});
  ASSERT_EQ(bvh.nodes.size(), 1u);
  EXPECT_EQ(bvh.nodes[0].leftIndex, gpu::BVH_INVALID);
  EXPECT_EQ(bvh.nodes[0].leftCount, 0u);
  EXPECT_EQ(bvh.nodes[0].rightIndex, gpu::BVH_INVALID);
  EXPECT_EQ(bvh.nodes[0].rightCount, 0u);
}

TEST(BvhBuilder, OnePrimitiveIsALeafBesideAnEmptySlot) {
  Primitives input = primitivesOf(triangleSoup(1, 5));
  Bvh bvh = buildBvh(input.boxes, input.centroids, {});
  ASSERT_EQ(bvh.nodes.size(), 1u);
  EXPECT_EQ(bvh.nodes[0].leftCount, 1u);
  EXPECT_EQ(bvh.nodes[0].leftIndex, 0u);
  EXPECT_EQ(bvh.nodes[0].rightIndex, gpu::BVH_INVALID);
  EXPECT_EQ(bvh.nodes[0].leftMin, input.boxes[0].min);
  EXPECT_EQ(bvh.nodes[0].leftMax, input.boxes[0].max);
}

TEST(BvhBuilder, IdenticalCentroidsFallBackToSplittingByIndex) {
  std::vector<Triangle> triangles;
  std::mt19937 rng(3);
  for (int i = 0; i < 5000; ++i) {
    // Different shapes, one centroid.
    glm::vec3 d1 = randomPoint(rng, -1, 1), d2 = randomPoint(rng, -1, 1);
    triangles.push_back({glm::vec3(2.0f) + d1, glm::vec3(2.0f) + d2, glm::vec3(2.0f) - d1 - d2});
  }
  Primitives input = primitivesOf(triangles);
  for (glm::vec3& c : input.centroids) c = glm::vec3(2.0f);
  for (uint32_t maxLeaf : {1u, 4u, 8u}) expectValidTree(input, leafSize(maxLeaf));
  // Fully identical boxes too.
  Primitives same;
  for (int i = 0; i < 3000; ++i) same.add({glm::vec3(0), glm::vec3(1, 0, 0), glm::vec3(0, 1, 0)});
  expectValidTree(same, leafSize(8));
  expectValidTree(same, leafSize(1));
}

TEST(BvhBuilder, HugeTinyFlatAndPointPrimitivesAreValid) {
  std::vector<Triangle> triangles = triangleSoup(2000, 11, 10.0f, 1e-6f);  // tiny
  std::vector<Triangle> huge = triangleSoup(50, 12, 1e6f, 1e5f);
  triangles.insert(triangles.end(), huge.begin(), huge.end());
  for (int i = 0; i < 500; ++i) {  // flat in z, and points
    float x = float(i % 25), y = float(i / 25);
    triangles.push_back({{x, y, 0}, {x + 1, y, 0}, {x, y + 1, 0}});
    triangles.push_back({{x, y, 5}, {x, y, 5}, {x, y, 5}});
  }
  Primitives input = primitivesOf(triangles);
  expectValidTree(input, leafSize(gpu::BVH_MAX_LEAF_TRIANGLES));
  expectValidTree(input, leafSize(1));
}

TEST(BvhBuilder, DepthLimitHoldsWhereSahWouldGoDeep) {
  // Boxes at exponentially growing distances: the SAH peels them off one by one, which would
  // make a chain as deep as the input is long.
  Primitives input;
  for (int i = 0; i < 120; ++i) {
    float x = std::pow(1.5f, float(i));
    input.add({{x, 0, 0}, {x * 1.0001f, 1, 0}, {x, 0, 1}});
  }
  BvhBuildOptions options = leafSize(1);
  options.maxDepth = gpu::BVH_STACK_SIZE;
  EXPECT_GT(buildBvh(input.boxes, input.centroids, options).stats.maxDepth, 10u)
      << "the input no longer provokes a deep tree; the test below would prove nothing";
  options.maxDepth = 10;
  Bvh bvh = buildBvh(input.boxes, input.centroids, options);
  EXPECT_LE(bvh.stats.maxDepth, 10u);
  InvariantChecker(bvh, input, options).check();
  options.maxDepth = 6;  // 120 leaves of 1 need 7 levels
  EXPECT_THROW(buildBvh(input.boxes, input.centroids, options), Error);
}

TEST(BvhBuilder, RejectsBadInput) {
  Primitives input = primitivesOf(triangleSoup(100, 2));
  const float nan = std::numeric_limits<float>::quiet_NaN();
  {
    Primitives bad = input;
    bad.boxes[37].max.y = nan;
    EXPECT_THROW(buildBvh(bad.boxes, bad.centroids, {}), Error);
  }
  {
    Primitives bad = input;
    bad.centroids[99].z = nan;
    EXPECT_THROW(buildBvh(bad.boxes, bad.centroids, {}), Error);
  }
  {
    Primitives bad = input;
    bad.boxes[0].min.x = -kInfinity;
    EXPECT_THROW(buildBvh(bad.boxes, bad.centroids, {}), Error);
  }
  {
    Primitives bad = input;
    std::swap(bad.boxes[5].min, bad.boxes[5].max);  // inverted
    EXPECT_THROW(buildBvh(bad.boxes, bad.centroids, {}), Error);
  }
  {
    // Large enough to take the threaded path.
    Primitives big = primitivesOf(triangleSoup(40000, 3));
    big.boxes[39999].min.x = nan;
    BvhBuildOptions options;
    options.threadCount = 2;
    EXPECT_THROW(buildBvh(big.boxes, big.centroids, options), Error);
  }
  EXPECT_THROW(buildBvh(input.boxes, std::span(input.centroids).first(50), {}), Error);
  BvhBuildOptions options;
  options.binCount = 1;
  EXPECT_THROW(buildBvh(input.boxes, input.centroids, options), Error);
  options = {};
  options.maxLeafSize = 0;
  EXPECT_THROW(buildBvh(input.boxes, input.centroids, options), Error);
}

TEST(BvhBuilder, OutputDoesNotDependOnThreadCount) {
  // Large enough for parallel binning at the root and many subtree tasks.
  for (bool mesh : {false, true}) {
    SCOPED_TRACE(mesh ? "mesh" : "soup");
    Primitives input =
        mesh ? primitivesOf(bumpySphere(260)) : primitivesOf(triangleSoup(300000, 9));
    BvhBuildOptions options;
    options.threadCount = 1;
    Bvh reference = buildBvh(input.boxes, input.centroids, options);
    EXPECT_EQ(reference.stats.threadsUsed, 1u);
    for (uint32_t threads : {2u, 3u, 4u}) {
      options.threadCount = threads;
      Bvh bvh = buildBvh(input.boxes, input.centroids, options);
      EXPECT_EQ(bvh.stats.threadsUsed, threads);
      ASSERT_EQ(bvh.nodes.size(), reference.nodes.size()) << threads << " threads";
      EXPECT_EQ(0, std::memcmp(bvh.nodes.data(), reference.nodes.data(),
                               bvh.nodes.size() * sizeof(gpu::GpuBvhNode)))
          << threads << " threads";
      EXPECT_EQ(bvh.primitiveOrder, reference.primitiveOrder) << threads << " threads";
    }
    InvariantChecker(reference, input, options).check();
  }
}

// Ranges of up to 8 primitives are split by an exact SAH sweep (every plane between centroids
// sorted along each axis). On small random sets, with centroids on a coarse grid so that many
// tie, the root's split must cost what the best plane found by brute force costs.
TEST(BvhBuilder, SmallRangesTakeTheBestExactSplit) {
  std::mt19937 rng(5);
  std::uniform_int_distribution<int> grid(0, 3);
  std::uniform_real_distribution<float> size(0.05f, 1.5f);
  BvhBuildOptions options = tlasBuildOptions();  // leaves of one: the root always splits
  for (int trial = 0; trial < 400; ++trial) {
    const uint32_t n = 2 + uint32_t(trial % 7);
    Primitives input;
    for (uint32_t i = 0; i < n; ++i) {
      const glm::vec3 c(float(grid(rng)), float(grid(rng)), float(grid(rng)));
      const glm::vec3 half(size(rng), size(rng), size(rng));
      input.boxes.push_back({c - half, c + half});
      input.centroids.push_back(c);
    }
    auto halfArea = [](const Aabb& b) {
      const glm::vec3 d = b.max - b.min;
      return double(d.x) * d.y + double(d.y) * d.z + double(d.z) * d.x;
    };
    double best = std::numeric_limits<double>::infinity();
    for (int axis = 0; axis < 3; ++axis) {
      std::vector<uint32_t> order(n);
      for (uint32_t i = 0; i < n; ++i) order[i] = i;
      std::stable_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
        return input.centroids[a][axis] < input.centroids[b][axis];
      });
      for (uint32_t k = 1; k < n; ++k) {
        Aabb left, right;
        for (uint32_t i = 0; i < n; ++i) (i < k ? left : right).extend(input.boxes[order[i]]);
        best = std::min(best, halfArea(left) * k + halfArea(right) * (n - k));
      }
    }
    Bvh bvh = buildBvh(input.boxes, input.centroids, options);
    const gpu::GpuBvhNode& root = bvh.nodes[0];
    auto count = [&](uint32_t index, uint32_t leafCount) {
      return leafCount > 0 ? leafCount : measureBvh(bvh.nodes, index, 1.0f).primitiveCount;
    };
    const double cost =
        halfArea({root.leftMin, root.leftMax}) * count(root.leftIndex, root.leftCount) +
        halfArea({root.rightMin, root.rightMax}) * count(root.rightIndex, root.rightCount);
    EXPECT_NEAR(cost, best, 1e-5 * best) << "trial " << trial << ", " << n << " primitives";
  }
}

// A scratch handed from build to build (as buildSceneBvh does from mesh to mesh) changes
// nothing in the output, whether the next input is larger or smaller.
TEST(BvhBuilder, ReusedScratchGivesTheSameTree) {
  BvhScratch scratch;
  for (uint32_t count : {30000u, 500u, 70000u, 9u}) {
    Primitives input = primitivesOf(triangleSoup(count, count));
    for (uint32_t threads : {1u, 2u}) {
      BvhBuildOptions options;
      options.threadCount = threads;
      const Bvh fresh = buildBvh(input.boxes, input.centroids, options);
      const Bvh reused = buildBvh(input.boxes, input.centroids, options, &scratch);
      ASSERT_EQ(reused.nodes.size(), fresh.nodes.size()) << count;
      EXPECT_EQ(0, std::memcmp(reused.nodes.data(), fresh.nodes.data(),
                               fresh.nodes.size() * sizeof(gpu::GpuBvhNode)))
          << count;
      EXPECT_EQ(reused.primitiveOrder, fresh.primitiveOrder) << count;
    }
  }
}

// ---- scenes for traversal tests ---------------------------------------------------------------

Geometry geometryOf(const std::vector<Triangle>& triangles, uint32_t material) {
  Geometry g;
  g.material = material;
  for (const Triangle& t : triangles) {
    for (const glm::vec3& p : {t.a, t.b, t.c}) {
      g.indices.push_back(uint32_t(g.positions.size()));
      g.positions.push_back(p);
      g.normals.push_back(glm::vec3(0, 0, 1));
      g.uvs.push_back(glm::vec2(p.x, p.y));
    }
  }
  return g;
}

// A grid in the xy plane facing +z, sharing vertices (so rays meet shared edges).
Geometry gridGeometry(int cells, uint32_t material) {
  Geometry g;
  g.material = material;
  for (int y = 0; y <= cells; ++y)
    for (int x = 0; x <= cells; ++x) {
      g.positions.push_back(glm::vec3(float(x) / cells - 0.5f, float(y) / cells - 0.5f, 0.0f));
      g.normals.push_back(glm::vec3(0, 0, 1));
      g.uvs.push_back(glm::vec2(float(x) / cells, float(y) / cells));
      g.tangents.push_back(glm::vec4(1, 0, 0, 1));
    }
  for (int y = 0; y < cells; ++y)
    for (int x = 0; x < cells; ++x) {
      uint32_t i = uint32_t(y * (cells + 1) + x);
      uint32_t right = i + 1, up = i + uint32_t(cells) + 1, diagonal = up + 1;
      g.indices.insert(g.indices.end(), {i, right, diagonal, i, diagonal, up});
    }
  return g;
}

glm::mat4 randomTransform(std::mt19937& rng, bool mirror) {
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  glm::mat4 m = glm::translate(glm::mat4(1.0f), randomPoint(rng, -4.0f, 4.0f));
  glm::vec3 axis = glm::normalize(randomPoint(rng, -1.0f, 1.0f) + glm::vec3(0.01f));
  m = glm::rotate(m, 6.2831853f * u(rng), axis);
  glm::vec3 scale(0.3f + 2.5f * u(rng), 0.3f + 2.5f * u(rng), 0.3f + 2.5f * u(rng));
  if (mirror) scale.x = -scale.x;
  return glm::scale(m, scale);
}

// Several meshes (soup with an opaque and an alpha-tested geometry, a sphere, an alpha-tested
// grid, an empty mesh, a mesh whose geometry has no triangles) placed by rotated, non-uniformly
// scaled, translated and one mirrored instance.
Scene randomScene(uint32_t seed) {
  std::mt19937 rng(seed);
  Scene scene;
  scene.name = "random scene " + std::to_string(seed);
  scene.materials.resize(2);
  scene.materials[1].alphaMode = AlphaMode::Mask;
  Mesh soup;
  soup.geometries.push_back(geometryOf(triangleSoup(120, seed * 7 + 1, 2.0f, 0.4f), 0));
  soup.geometries.push_back(geometryOf(triangleSoup(80, seed * 7 + 2, 2.0f, 0.4f), 1));
  Mesh sphere;
  sphere.geometries.push_back(geometryOf(bumpySphere(10, 1.0f), 0));
  Mesh grid;
  grid.geometries.push_back(gridGeometry(10, 1));
  Mesh empty;
  Mesh noTriangles;
  noTriangles.geometries.push_back(Geometry{});
  scene.meshes = {soup, sphere, grid, empty, noTriangles};
  for (uint32_t i = 0; i < 9; ++i) {
    Instance instance;
    instance.mesh = i % 5 == 3 ? 3 : i % 3;
    instance.transform = randomTransform(rng, i == 4);
    scene.instances.push_back(instance);
  }
  scene.instances.push_back({4, glm::mat4(1.0f), "no triangles"});
  validateScene(scene, scene.name);
  return scene;
}

// World boxes of the instances that have triangles.
std::vector<Aabb> instanceBoxes(const Scene& scene) {
  std::vector<Aabb> boxes;
  for (const Instance& instance : scene.instances) {
    Aabb object, world;
    for (const Geometry& g : scene.meshes[instance.mesh].geometries)
      for (const glm::vec3& p : g.positions) object.extend(p);
    if (object.empty()) continue;
    for (int corner = 0; corner < 8; ++corner) {
      glm::vec3 p(corner & 1 ? object.max.x : object.min.x,
                  corner & 2 ? object.max.y : object.min.y,
                  corner & 4 ? object.max.z : object.min.z);
      world.extend(glm::vec3(instance.transform * glm::vec4(p, 1.0f)));
    }
    boxes.push_back(world);
  }
  return boxes;
}

// Half the rays start inside the scene's box, half outside; most aim at a point in a random
// instance's box, the rest go anywhere. Lengths vary (t is in units of the direction), some
// directions lie along axes or axis planes, some tMin > 0, some tMax finite.
struct RayQuery {
  Ray ray;
  float tMax;
};

std::vector<RayQuery> randomRays(const Scene& scene, size_t count, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  const Aabb bounds = scene.bounds();
  const std::vector<Aabb> targets = instanceBoxes(scene);
  const glm::vec3 center = bounds.center();
  const float radius = 0.5f * glm::length(bounds.extent());
  auto pointIn = [&](const Aabb& box) { return box.min + box.extent() * randomPoint(rng, 0, 1); };
  std::vector<RayQuery> rays(count);
  for (size_t i = 0; i < count; ++i) {
    Ray& ray = rays[i].ray;
    if (i % 2 == 0) {
      ray.origin = pointIn(bounds);
    } else {
      glm::vec3 away = glm::normalize(randomPoint(rng, -1.0f, 1.0f) + glm::vec3(1e-3f));
      ray.origin = center + 2.0f * radius * away;
    }
    glm::vec3 target =
        i % 4 == 0 || targets.empty()
            ? pointIn(bounds)
            : pointIn(targets[size_t(u(rng) * float(targets.size())) % targets.size()]);
    ray.direction = target - ray.origin;
    if (i % 10 == 3) ray.direction[i % 3] = 0.0f;  // parallel to an axis plane
    if (i % 10 == 7) ray.direction = glm::vec3(0.0f, 0.0f, u(rng) < 0.5f ? -1.0f : 1.0f);
    if (glm::length(ray.direction) == 0.0f) ray.direction = glm::vec3(1, 0, 0);
    ray.direction *= 0.25f + 4.0f * u(rng) / glm::length(ray.direction);
    ray.tMin = i % 4 == 1 ? 1e-3f : 0.0f;
    rays[i].tMax =
        i % 3 == 0 ? (0.05f + u(rng)) * 3.0f * radius / glm::length(ray.direction) : kInfinity;
  }
  return rays;
}

// Rejects odd-numbered primitives of alpha-tested geometries.
bool evenPrimitivesOpaque(uint32_t, uint32_t, uint32_t primitive, float, float) {
  return primitive % 2 == 0;
}

struct Agreement {
  int rays = 0, hits = 0, ties = 0, alphaChanged = 0;
};

void expectSameClosestHit(const TraceHit& bvh, const TraceHit& brute, size_t rayIndex,
                          Agreement& agreement) {
  ASSERT_EQ(bvh.hit, brute.hit) << "ray " << rayIndex;
  if (!bvh.hit) return;
  ++agreement.hits;
  EXPECT_NEAR(bvh.t, brute.t, 1e-4f * brute.t) << "ray " << rayIndex;
  const bool sameTriangle = bvh.instance == brute.instance && bvh.geometry == brute.geometry &&
                            bvh.primitive == brute.primitive;
  if (!sameTriangle) {
    // Two triangles at (nearly) the same distance, e.g. a shared edge: either answer is right.
    EXPECT_NEAR(bvh.t, brute.t, 1e-5f * brute.t) << "ray " << rayIndex << " hit another triangle";
    ++agreement.ties;
    return;
  }
  EXPECT_NEAR(bvh.b1, brute.b1, 1e-3f) << "ray " << rayIndex;
  EXPECT_NEAR(bvh.b2, brute.b2, 1e-3f) << "ray " << rayIndex;
  EXPECT_EQ(bvh.frontFacing, brute.frontFacing) << "ray " << rayIndex;
}

Agreement compareWithBruteForce(const Scene& scene, const std::vector<RayQuery>& rays,
                                const SceneBvhOptions& options = {}) {
  SceneBvh bvh = buildSceneBvh(scene, options);
  CpuTracer tracer(bvh);
  const AlphaTest alpha = evenPrimitivesOpaque;
  Agreement agreement;
  for (size_t i = 0; i < rays.size(); ++i) {
    const Ray& ray = rays[i].ray;
    const float tMax = rays[i].tMax;
    ++agreement.rays;
    expectSameClosestHit(tracer.closestHit(ray, tMax), closestHitBruteForce(scene, ray, tMax), i,
                         agreement);
    TraceHit alphaHit = tracer.closestHit(ray, tMax, alpha);
    expectSameClosestHit(alphaHit, closestHitBruteForce(scene, ray, tMax, alpha), i, agreement);
    if (alphaHit.hit != tracer.closestHit(ray, tMax).hit) ++agreement.alphaChanged;
    EXPECT_EQ(tracer.anyHit(ray, tMax), anyHitBruteForce(scene, ray, tMax)) << "ray " << i;
    EXPECT_EQ(tracer.anyHit(ray, tMax, alpha), anyHitBruteForce(scene, ray, tMax, alpha))
        << "ray " << i;
    if (::testing::Test::HasFatalFailure()) break;
  }
  return agreement;
}

// ---- traversal --------------------------------------------------------------------------------

TEST(CpuTrace, MatchesBruteForceOnRandomScenes) {
  Agreement total;
  for (uint32_t seed : {1u, 2u, 3u}) {
    SCOPED_TRACE("scene seed " + std::to_string(seed));
    Scene scene = randomScene(seed);
    Agreement a = compareWithBruteForce(scene, randomRays(scene, 3500, seed * 101));
    total.rays += a.rays;
    total.hits += a.hits;
    total.ties += a.ties;
    total.alphaChanged += a.alphaChanged;
    if (HasFatalFailure()) return;
  }
  std::printf("[ bvh ] %d rays, %d closest hits, %d ties, alpha test changed %d answers\n",
              total.rays, total.hits, total.ties, total.alphaChanged);
  EXPECT_GE(total.rays, 10000);
  // The test means something only if rays hit things and the alpha test matters.
  EXPECT_GT(total.hits, total.rays / 2);
  EXPECT_LT(total.hits, 2 * total.rays * 95 / 100);
  EXPECT_GT(total.alphaChanged, total.rays / 100);
}

// The traversal stack packs a leaf's triangle count into 4 bits (shared/scene_layout.h): the
// largest leaves it allows still find every closest hit, and larger ones are refused.
TEST(CpuTrace, LargestStackableLeavesMatchBruteForce) {
  Scene scene = randomScene(4);
  SceneBvhOptions options;
  options.blas.maxLeafSize = 16;
  options.blas.traversalCost = 8.0f;  // nodes made dear: the SAH then keeps full leaves
  uint32_t largestLeaf = 0;
  for (const gpu::GpuBvhNode& node : buildSceneBvh(scene, options).blasNodes)
    largestLeaf = std::max({largestLeaf, node.leftCount, node.rightCount});
  EXPECT_GT(largestLeaf, 8u) << "no leaf uses the count bits beyond the default leaf size";
  Agreement a = compareWithBruteForce(scene, randomRays(scene, 2000, 404), options);
  EXPECT_GT(a.hits, a.rays / 2);
  options.blas.maxLeafSize = 17;
  EXPECT_THROW(buildSceneBvh(scene, options), Error);
}

TEST(CpuTrace, MatchesBruteForceOnABuiltinScene) {
  // Foliage: instanced meshes and alpha-tested leaves.
  std::optional<Scene> scene = makeBuiltinScene("foliage");
  if (!scene) GTEST_SKIP() << "built-in scene 'foliage' not available";
  Agreement a = compareWithBruteForce(*scene, randomRays(*scene, 600, 77));
  EXPECT_GT(a.hits, a.rays / 4);
}

TEST(CpuTrace, EmptyScenesAreNeverHit) {
  Scene scene;
  scene.materials.resize(1);
  SceneBvh noInstances = buildSceneBvh(scene);
  ASSERT_EQ(noInstances.tlasNodes.size(), 1u);
  Ray ray{glm::vec3(0.0f), glm::vec3(0.3f, -1.0f, 0.2f)};
  EXPECT_FALSE(CpuTracer(noInstances).closestHit(ray, kInfinity).hit);
  EXPECT_FALSE(CpuTracer(noInstances).anyHit(ray, kInfinity));
  scene.meshes.resize(1);  // a mesh without geometry, placed once
  scene.instances.push_back({0, glm::mat4(1.0f), "empty"});
  SceneBvh emptyMesh = buildSceneBvh(scene);
  EXPECT_FALSE(CpuTracer(emptyMesh).closestHit(ray, kInfinity).hit);
  EXPECT_TRUE(emptyMesh.meshBounds[0].empty());
}

// glTF: a triangle's front is where it winds counter-clockwise, i.e. where its normal
// cross(v1 - v0, v2 - v0) points; a node with a negative determinant reverses that, which the
// world-space vertices already express.
bool seesFront(const glm::mat4& objectToWorld, const Geometry& g, uint32_t primitive,
               const glm::vec3& direction) {
  glm::vec3 v[3];
  for (int k = 0; k < 3; ++k)
    v[k] = glm::vec3(objectToWorld * glm::vec4(g.positions[g.indices[primitive * 3 + k]], 1.0f));
  return glm::dot(glm::cross(v[1] - v[0], v[2] - v[0]), direction) < 0.0f;
}

TEST(CpuTrace, FrontFacingFollowsWindingAndMirroring) {
  Scene scene;
  scene.materials.resize(1);
  scene.meshes.resize(1);
  scene.meshes[0].geometries.push_back(gridGeometry(2, 0));  // counter-clockwise seen from +z
  scene.instances.push_back({0, glm::mat4(1.0f), "plain"});
  glm::mat4 mirrored = glm::scale(glm::translate(glm::mat4(1.0f), glm::vec3(0, 0, -5)),
                                  glm::vec3(-1.0f, 1.0f, 1.0f));
  scene.instances.push_back({0, mirrored, "mirrored"});
  SceneBvh bvh = buildSceneBvh(scene);
  CpuTracer tracer(bvh);
  const Geometry& grid = scene.meshes[0].geometries[0];
  struct Case {
    Ray ray;
    uint32_t instance;
    float t;
  };
  const Case cases[] = {
      {{glm::vec3(0.1f, 0.2f, 3.0f), glm::vec3(0, 0, -1)}, 0, 3.0f},   // plain, from the front
      {{glm::vec3(0.1f, 0.2f, -1.0f), glm::vec3(0, 0, 2)}, 0, 0.5f},   // plain, from behind
      {{glm::vec3(0.1f, 0.2f, -1.0f), glm::vec3(0, 0, -2)}, 1, 2.0f},  // mirrored, from above
      {{glm::vec3(0.1f, 0.2f, -9.0f), glm::vec3(0, 0, 1)}, 1, 4.0f},   // mirrored, from below
  };
  for (const Case& c : cases) {
    TraceHit hit = tracer.closestHit(c.ray, kInfinity);
    ASSERT_TRUE(hit.hit);
    EXPECT_EQ(hit.instance, c.instance);
    EXPECT_FLOAT_EQ(hit.t, c.t);  // in units of the unnormalised direction
    TraceHit brute = closestHitBruteForce(scene, c.ray, kInfinity);
    EXPECT_EQ(hit.frontFacing, brute.frontFacing);
    EXPECT_EQ(hit.frontFacing, seesFront(scene.instances[hit.instance].transform, grid,
                                         hit.primitive, c.ray.direction))
        << "instance " << hit.instance << ", direction z " << c.ray.direction.z
        << ": frontFacing disagrees with glTF's counter-clockwise rule. If every case fails, "
           "check the sign in shared/ray_triangle.h (det > 0 is counter-clockwise seen from "
           "the ray origin there).";
  }
}

TEST(CpuTrace, TlasRebuildFollowsMovedInstances) {
  Scene scene;
  scene.materials.resize(1);
  scene.meshes.resize(1);
  scene.meshes[0].geometries.push_back(gridGeometry(4, 0));
  scene.instances.push_back({0, glm::translate(glm::mat4(1.0f), glm::vec3(0, 0, 0)), "near"});
  scene.instances.push_back({0, glm::translate(glm::mat4(1.0f), glm::vec3(0, 0, -3)), "far"});
  SceneBvh bvh = buildSceneBvh(scene);
  Ray ray{glm::vec3(0.1f, 0.1f, 5.0f), glm::vec3(0, 0, -1)};
  EXPECT_EQ(CpuTracer(bvh).closestHit(ray, kInfinity).instance, 0u);

  // Move the near grid out of the way: the far one is hit, in the BVH and in the scene.
  glm::mat4 moved = glm::translate(glm::mat4(1.0f), glm::vec3(10, 0, 0));
  setInstanceTransform(bvh.instances[0], moved);
  scene.instances[0].transform = moved;
  bvh.tlasNodes = buildTlas(bvh.instances, bvh.meshBounds);
  TraceHit hit = CpuTracer(bvh).closestHit(ray, kInfinity);
  ASSERT_TRUE(hit.hit);
  EXPECT_EQ(hit.instance, 1u);
  EXPECT_FLOAT_EQ(hit.t, 8.0f);
  EXPECT_EQ(closestHitBruteForce(scene, ray, kInfinity).instance, 1u);

  // Move it back in front, rotated and scaled: hit again, at its new depth.
  glm::mat4 back = glm::scale(glm::translate(glm::mat4(1.0f), glm::vec3(0, 0, 2)), glm::vec3(3));
  setInstanceTransform(bvh.instances[0], back);
  scene.instances[0].transform = back;
  bvh.tlasNodes = buildTlas(bvh.instances, bvh.meshBounds);
  hit = CpuTracer(bvh).closestHit(ray, kInfinity);
  EXPECT_EQ(hit.instance, 0u);
  EXPECT_FLOAT_EQ(hit.t, 3.0f);
}

// The refit plan visits every interior node once, each after its interior children.
void expectPlanCoversTheTree(std::span<const gpu::GpuBvhNode> tlas, const TlasRefitPlan& plan) {
  std::vector<int> levelOf(tlas.size(), -1);
  for (uint32_t l = 0; l < plan.levels(); ++l)
    for (uint32_t k = plan.levelStart[l]; k < plan.levelStart[l + 1]; ++k) {
      ASSERT_EQ(levelOf[plan.nodes[k]], -1) << "node " << plan.nodes[k] << " planned twice";
      levelOf[plan.nodes[k]] = int(l);
    }
  for (uint32_t node = 0; node < tlas.size(); ++node) {
    ASSERT_GE(levelOf[node], 0) << "node " << node << " not planned";
    for (auto [index, count] : {std::pair{tlas[node].leftIndex, tlas[node].leftCount},
                                std::pair{tlas[node].rightIndex, tlas[node].rightCount}})
      if (count == 0 && index != gpu::BVH_INVALID) EXPECT_LT(levelOf[index], levelOf[node]);
  }
}

// A TLAS built once and refitted (refitTlas, the GPU refit's reference) after every instance
// moved, one hidden at the build shows and others hide: traversal gives the brute force's
// answer on the moved scene.
TEST(CpuTrace, TlasRefitFollowsMovedShownAndHiddenInstances) {
  std::mt19937 rng(2024);
  Scene scene = randomScene(7);
  const uint32_t meshesWithTriangles = 3;  // randomScene's soup, sphere and grid
  for (uint32_t i = 0; i < 40; ++i)
    scene.instances.push_back({i % meshesWithTriangles, randomTransform(rng, i % 7 == 0), ""});
  scene.instances[0].transform = glm::scale(scene.instances[0].transform, glm::vec3(0.0f));
  SceneBvh bvh = buildSceneBvh(scene);
  ASSERT_TRUE(bvh.instances[0].flags & gpu::GPU_INSTANCE_HIDDEN);
  std::vector<gpu::GpuBvhNode> tlas = buildRefittableTlas(bvh.instances, bvh.meshBounds);
  const TlasRefitPlan plan = planTlasRefit(tlas);
  expectPlanCoversTheTree(tlas, plan);
  EXPECT_GT(plan.levels(), 3u);

  for (size_t i = 0; i < scene.instances.size(); ++i) {
    glm::mat4 moved = randomTransform(rng, i % 5 == 0);
    if (i % 9 == 4) moved = glm::scale(moved, glm::vec3(0.0f));  // hidden from now on
    scene.instances[i].transform = moved;
    setInstanceTransform(bvh.instances[i], moved);
  }
  refitTlas(tlas, plan, bvh.instances, bvh.meshBounds);
  bvh.tlasNodes = tlas;

  const CpuTracer tracer(bvh);
  const BruteForceTracer bruteForce(scene);
  Agreement agreement;
  int hitsOnTheShownInstance = 0;
  const std::vector<RayQuery> rays = randomRays(scene, 3000, 99);
  for (size_t i = 0; i < rays.size(); ++i) {
    const TraceHit hit = tracer.closestHit(rays[i].ray, rays[i].tMax);
    expectSameClosestHit(hit, bruteForce.closestHit(rays[i].ray, rays[i].tMax), i, agreement);
    EXPECT_EQ(tracer.anyHit(rays[i].ray, rays[i].tMax),
              bruteForce.anyHit(rays[i].ray, rays[i].tMax))
        << "ray " << i;
    hitsOnTheShownInstance += hit.hit && hit.instance == 0;
    if (HasFatalFailure()) return;
  }
  EXPECT_GT(agreement.hits, int(rays.size()) / 3);
  EXPECT_GT(hitsOnTheShownInstance, 0) << "the instance hidden at the build is never hit";
}

// Two clusters of 32 small spheres, 24 apart, whose members swap places over `steps` steps:
// member k of each cluster travels to a random slot of the other, so the refitted tree's
// subtrees, built over neighbours, end up spanning both clusters and the gap between them.
struct SwappingClusters {
  static constexpr uint32_t kPerCluster = 32;
  Scene scene;
  std::vector<glm::vec3> start, end;  // per instance

  explicit SwappingClusters(uint32_t seed) {
    std::mt19937 rng(seed);
    scene.materials.resize(1);
    scene.meshes.resize(1);
    scene.meshes[0].geometries.push_back(geometryOf(bumpySphere(8, 0.5f), 0));
    std::vector<glm::vec3> slots[2];
    for (int cluster = 0; cluster < 2; ++cluster)
      for (uint32_t k = 0; k < kPerCluster; ++k)
        slots[cluster].push_back(glm::vec3(cluster ? 12.0f : -12.0f, 0.0f, 0.0f) +
                                 1.5f * glm::vec3(k % 4, (k / 4) % 4, k / 16));
    for (int cluster = 0; cluster < 2; ++cluster) {
      std::vector<glm::vec3> targets = slots[1 - cluster];
      std::shuffle(targets.begin(), targets.end(), rng);
      for (uint32_t k = 0; k < kPerCluster; ++k) {
        start.push_back(slots[cluster][k]);
        end.push_back(targets[k]);
        scene.instances.push_back({0, glm::translate(glm::mat4(1.0f), start.back()), ""});
      }
    }
  }
  // Places every instance a fraction t of the way, in the scene and in `bvh`.
  void place(float t, SceneBvh& bvh) {
    for (size_t i = 0; i < scene.instances.size(); ++i) {
      scene.instances[i].transform = glm::translate(glm::mat4(1.0f), glm::mix(start[i], end[i], t));
      setInstanceTransform(bvh.instances[i], scene.instances[i].transform);
    }
  }
};

// The rebuild policy (updateRefittedTlas, what GpuScene runs at every move): while two clusters
// swap places, a tree only refitted degrades far beyond the default limit of 1.5; with the
// policy it is rebuilt over the current placement (the cost of a fresh build, ratio 1), ends
// closer to a fresh build's cost than the refit alone, and traversal still gives the brute
// force's answers. Small jitter, by less than an instance's size, never triggers a rebuild.
TEST(CpuTrace, TlasRebuildPolicyRebuildsADegradedRefit) {
  constexpr double kLimit = 1.5;  // GpuSceneOptions::tlasRebuildRatio's default
  constexpr int kSteps = 8;
  SwappingClusters clusters(7);
  SceneBvh bvh = buildSceneBvh(clusters.scene);
  std::vector<gpu::GpuBvhNode> refitOnly, rebuilt;
  TlasRefitState refitOnlyState, rebuiltState;
  buildRefittedTlas(refitOnly, refitOnlyState, bvh.instances, bvh.meshBounds);
  buildRefittedTlas(rebuilt, rebuiltState, bvh.instances, bvh.meshBounds);
  double worstRefitRatio = 0.0, worstPolicyRatio = 0.0, freshCost = 0.0;
  for (int step = 1; step <= kSteps; ++step) {
    clusters.place(float(step) / kSteps, bvh);
    EXPECT_FALSE(updateRefittedTlas(refitOnly, refitOnlyState, bvh.instances, bvh.meshBounds, 0));
    const bool rebuiltNow =
        updateRefittedTlas(rebuilt, rebuiltState, bvh.instances, bvh.meshBounds, kLimit);
    // The true measure, too expensive for every frame: the cost of a fresh build here.
    std::vector<gpu::GpuBvhNode> fresh;
    TlasRefitState freshState;
    buildRefittedTlas(fresh, freshState, bvh.instances, bvh.meshBounds);
    freshCost = freshState.builtCost;
    if (rebuiltNow) {
      EXPECT_EQ(rebuiltState.costRatio, 1.0);
      EXPECT_EQ(tlasSahCost(rebuilt), freshCost) << "step " << step << ": not rebuilt here";
      EXPECT_EQ(rebuilt.size(), refitOnly.size());
    }
    worstRefitRatio = std::max(worstRefitRatio, refitOnlyState.costRatio);
    worstPolicyRatio = std::max(worstPolicyRatio, rebuiltState.costRatio);
    std::printf(
        "step %d: cost ratio refitted %.2f, with the policy %.2f (%u rebuilds); cost / a fresh "
        "build's: refitted %.2f, with the policy %.2f\n",
        step, refitOnlyState.costRatio, rebuiltState.costRatio, rebuiltState.rebuilds,
        tlasSahCost(refitOnly) / freshCost, tlasSahCost(rebuilt) / freshCost);
  }
  EXPECT_GT(worstRefitRatio, 2.0 * kLimit) << "the swapped clusters' refit";
  EXPECT_GT(refitOnlyState.costRatio, kLimit) << "the swapped clusters' refit at the end";
  EXPECT_EQ(refitOnlyState.rebuilds, 0u);
  EXPECT_GE(rebuiltState.rebuilds, 1u);
  EXPECT_LE(worstPolicyRatio, kLimit) << "a step ended with a degraded tree kept";
  EXPECT_LT(tlasSahCost(rebuilt), tlasSahCost(refitOnly)) << "fresh build " << freshCost;

  bvh.tlasNodes = rebuilt;
  const CpuTracer tracer(bvh);
  const BruteForceTracer bruteForce(clusters.scene);
  Agreement agreement;
  const std::vector<RayQuery> rays = randomRays(clusters.scene, 2000, 5);
  for (size_t i = 0; i < rays.size(); ++i) {
    expectSameClosestHit(tracer.closestHit(rays[i].ray, rays[i].tMax),
                         bruteForce.closestHit(rays[i].ray, rays[i].tMax), i, agreement);
    EXPECT_EQ(tracer.anyHit(rays[i].ray, rays[i].tMax),
              bruteForce.anyHit(rays[i].ray, rays[i].tMax))
        << "ray " << i;
    if (HasFatalFailure()) return;
  }
  EXPECT_GT(agreement.hits, int(rays.size()) / 4);

  // Jitter: every sphere (diameter 1) moves up to 0.35 along each axis from its slot.
  std::mt19937 rng(11);
  SceneBvh still = buildSceneBvh(SwappingClusters(7).scene);
  TlasRefitState jitterState;
  std::vector<gpu::GpuBvhNode> jittered;
  buildRefittedTlas(jittered, jitterState, still.instances, still.meshBounds);
  double worstJitterRatio = 0.0;
  for (int step = 0; step < kSteps; ++step) {
    for (size_t i = 0; i < still.instances.size(); ++i)
      setInstanceTransform(
          still.instances[i],
          glm::translate(glm::mat4(1.0f), clusters.start[i] + randomPoint(rng, -0.35f, 0.35f)));
    updateRefittedTlas(jittered, jitterState, still.instances, still.meshBounds, kLimit);
    worstJitterRatio = std::max(worstJitterRatio, jitterState.costRatio);
  }
  std::printf("jitter: worst cost ratio %.2f\n", worstJitterRatio);
  EXPECT_EQ(jitterState.rebuilds, 0u) << "worst cost ratio " << worstJitterRatio;
}

// ---- scene arrays -----------------------------------------------------------------------------

TEST(SceneBvh, ArraysDescribeTheScene) {
  Scene scene = randomScene(5);
  SceneBvh bvh = buildSceneBvh(scene);
  ASSERT_EQ(bvh.blasRoot.size(), scene.meshes.size());
  ASSERT_EQ(bvh.instances.size(), scene.instances.size());
  EXPECT_EQ(bvh.triangles.size(), scene.uniqueTriangleCount());
  size_t vertices = 0, geometries = 0;
  for (size_t m = 0; m < scene.meshes.size(); ++m) {
    EXPECT_EQ(bvh.geometryBase[m], geometries);
    for (const Geometry& g : scene.meshes[m].geometries) {
      const gpu::GpuGeometry& gg = bvh.geometries[geometries++];
      EXPECT_EQ(gg.vertexOffset, vertices);
      EXPECT_EQ(gg.triangleCount, g.triangleCount());
      EXPECT_EQ(gg.material, g.material);
      for (size_t i = 0; i < g.indices.size(); ++i)
        ASSERT_EQ(bvh.indices[gg.firstIndex + i], g.indices[i]);
      for (size_t v = 0; v < g.positions.size(); ++v) {
        ASSERT_EQ(bvh.positions[vertices + v], g.positions[v]);
        ASSERT_EQ(bvh.tangents[vertices + v],
                  g.tangents.empty() ? glm::vec4(1, 0, 0, 1) : g.tangents[v]);
      }
      vertices += g.positions.size();
    }
  }
  EXPECT_EQ(bvh.positions.size(), vertices);
  EXPECT_EQ(bvh.normals.size(), vertices);
  EXPECT_EQ(bvh.uvs.size(), vertices);

  // Every triangle copy matches the scene triangle it names, with the alpha flag of its
  // material, and sits in a leaf of its own mesh's BLAS.
  for (size_t m = 0; m < scene.meshes.size(); ++m) {
    std::vector<uint32_t> stack{bvh.blasRoot[m]};
    while (!stack.empty()) {
      const gpu::GpuBvhNode& node = bvh.blasNodes[stack.back()];
      stack.pop_back();
      for (auto [index, count] : {std::pair{node.leftIndex, node.leftCount},
                                  std::pair{node.rightIndex, node.rightCount}}) {
        if (count == 0) {
          if (index != gpu::BVH_INVALID) stack.push_back(index);
          continue;
        }
        for (uint32_t k = index; k < index + count; ++k) {
          const gpu::GpuTriangle& tri = bvh.triangles[k];
          uint32_t local = tri.geometry & ~gpu::GPU_TRIANGLE_ALPHA_TESTED;
          ASSERT_LT(local, scene.meshes[m].geometries.size());
          const Geometry& g = scene.meshes[m].geometries[local];
          ASSERT_LT(tri.primitive, g.triangleCount());
          EXPECT_EQ(tri.v0, g.positions[g.indices[tri.primitive * 3]]);
          EXPECT_EQ(tri.v1, g.positions[g.indices[tri.primitive * 3 + 1]]);
          EXPECT_EQ(tri.v2, g.positions[g.indices[tri.primitive * 3 + 2]]);
          bool alpha = scene.materials[g.material].alphaMode != AlphaMode::Opaque;
          EXPECT_EQ((tri.geometry & gpu::GPU_TRIANGLE_ALPHA_TESTED) != 0, alpha);
        }
      }
    }
  }

  // Instances: rows of the transforms, inverse rows, per-mesh references, flags 0.
  for (size_t i = 0; i < scene.instances.size(); ++i) {
    const gpu::GpuInstance& gi = bvh.instances[i];
    const glm::mat4& m = scene.instances[i].transform;
    EXPECT_EQ(gi.mesh, scene.instances[i].mesh);
    EXPECT_EQ(gi.blasRoot, bvh.blasRoot[gi.mesh]);
    EXPECT_EQ(gi.geometryBase, bvh.geometryBase[gi.mesh]);
    EXPECT_EQ(gi.flags, 0u);
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 4; ++c) {
        EXPECT_EQ(gi.objectToWorld[r][c], m[c][r]);
        float product = 0.0f;  // (worldToObject * objectToWorld)[r][c] in 3x4 affine form
        for (int k = 0; k < 3; ++k) product += gi.worldToObject[r][k] * m[c][k];
        if (c == 3) product += gi.worldToObject[r][3];
        EXPECT_NEAR(product, r == c ? 1.0f : 0.0f, 1e-4f);
      }
  }
  const SceneBvhStats& stats = bvh.stats;
  EXPECT_EQ(stats.bytes.blasNodes, bvh.blasNodes.size() * 64);
  EXPECT_EQ(stats.bytes.triangles, bvh.triangles.size() * 48);
  EXPECT_EQ(stats.bytes.instances, bvh.instances.size() * 112);
  EXPECT_GT(stats.bytes.total(), 0u);
}

// Issue 22 asks for a faster build at an SAH cost within 2 % of the builder's before it
// (commit 2df13e8: BLAS 30.236, TLAS 14.606 on `city`, docs/ray-tracing.md "Build times").
TEST(SceneBvh, CitySahCostStaysWithinTwoPercentOfTheEarlierBuilder) {
  std::optional<Scene> city = makeBuiltinScene("city");
  if (!city) GTEST_SKIP() << "built-in scene 'city' not available";
  for (uint32_t threads : {1u, 2u}) {
    SceneBvhOptions options;
    options.blas.threadCount = threads;
    const SceneBvhStats stats = buildSceneBvh(*city, options).stats;
    EXPECT_LE(stats.blasSahCost, 1.02 * 30.236) << threads << " thread(s)";
    EXPECT_LE(stats.tlasSahCost, 1.02 * 14.606) << threads << " thread(s)";
  }
}

TEST(SceneBvh, RejectsUnusableScenes) {
  Scene scene = randomScene(6);
  {
    Scene bad = scene;
    bad.meshes[0].geometries[0].indices[4] = 1u << 30;
    EXPECT_THROW(buildSceneBvh(bad), Error);
  }
  {
    Scene bad = scene;
    bad.meshes[1].geometries[0].positions[3].x = std::numeric_limits<float>::quiet_NaN();
    EXPECT_THROW(buildSceneBvh(bad), Error);
  }
  {
    Scene bad = scene;
    bad.instances[2].transform[3][0] = std::numeric_limits<float>::infinity();
    EXPECT_THROW(buildSceneBvh(bad), Error);
  }
  {
    // A singular transform (scale 0, how glTF animations hide objects) hides the instance: it
    // stays in the instance array, out of the TLAS.
    Scene flat = scene;
    flat.instances[2].transform = glm::scale(glm::mat4(1.0f), glm::vec3(1, 0, 1));
    SceneBvh bvh = buildSceneBvh(flat);
    ASSERT_EQ(bvh.instances.size(), flat.instances.size());
    EXPECT_NE(bvh.instances[2].flags & gpu::GPU_INSTANCE_HIDDEN, 0u);
    EXPECT_EQ(bvh.instances[1].flags & gpu::GPU_INSTANCE_HIDDEN, 0u);
    for (const gpu::GpuBvhNode& node : bvh.tlasNodes) {
      EXPECT_FALSE(node.leftCount > 0 && node.leftIndex == 2u);
      EXPECT_FALSE(node.rightCount > 0 && node.rightIndex == 2u);
    }
  }
  {
    Scene bad = scene;
    bad.instances[1].mesh = 99;
    EXPECT_THROW(buildSceneBvh(bad), Error);
  }
}

// ---- the wide compressed BLAS (rt/wide_bvh.h) -------------------------------------------------

// Walks a collapsed tree, checking its encoding (scene_layout.h, GpuWideBvhNode) and that every
// child's decoded box contains the exact box of the primitives under it.
class WideChecker {
 public:
  WideChecker(const WideBvh& wide, const Primitives& input) : wide_(wide), input_(input) {}

  void check() {
    seen_.assign(input_.boxes.size(), 0);
    subtree(0, 1);
    EXPECT_EQ(wide_.primitiveOrder.size(), input_.boxes.size());
    for (size_t i = 0; i < seen_.size(); ++i)
      EXPECT_EQ(seen_[i], 1) << "primitive " << i << " reached " << int(seen_[i]) << " times";
    EXPECT_LE(wide_.maxDepth, gpu::BVH_WIDE_STACK_SIZE);
    EXPECT_GT(checkedChildren_, 0);
  }
  int checkedChildren() const { return checkedChildren_; }

 private:
  // The exact box of everything under wide node `n`.
  Aabb subtree(uint32_t n, uint32_t depth) {
    EXPECT_LE(depth, wide_.maxDepth);
    const gpu::GpuWideBvhNode& node = wide_.nodes.at(n);
    const uint32_t interiorMask = node.exponentsAndMask >> 24;
    uint32_t interiorSeen = 0, triangleBits = 0;
    Aabb all;
    for (uint32_t slot = 0; slot < 8; ++slot) {
      const uint32_t meta = wideByte(node.meta, slot);
      const bool interior = (interiorMask >> slot) & 1u;
      if (meta == 0) {
        EXPECT_FALSE(interior) << "an empty slot marked interior";
        continue;
      }
      Aabb exact;
      if (interior) {
        EXPECT_EQ(meta, gpu::BVH_WIDE_INTERIOR_META + slot);
        exact = subtree(node.childBase + interiorSeen++, depth + 1);
      } else {
        const uint32_t offset = meta & 31u, unary = meta >> 5;
        EXPECT_TRUE(unary == 1 || unary == 3 || unary == 7) << "meta " << meta;
        const uint32_t count = uint32_t(std::popcount(unary));
        EXPECT_LE(offset + count, 24u);
        EXPECT_EQ(triangleBits & (unary << offset), 0u) << "leaves overlap";
        triangleBits |= unary << offset;
        for (uint32_t k = 0; k < count; ++k) {
          const uint32_t p = wide_.primitiveOrder.at(node.triangleBase + offset + k);
          ++seen_.at(p);
          exact.extend(input_.boxes[p]);
        }
      }
      const Aabb decoded = decodeWideChildBox(node, slot);
      EXPECT_TRUE(contains(decoded.min, decoded.max, exact))
          << "node " << n << " slot " << slot << ": decoded (" << decoded.min.x << ", "
          << decoded.min.y << ", " << decoded.min.z << ")-(" << decoded.max.x << ", "
          << decoded.max.y << ", " << decoded.max.z << ") misses exact (" << exact.min.x << ", "
          << exact.min.y << ", " << exact.min.z << ")-(" << exact.max.x << ", " << exact.max.y
          << ", " << exact.max.z << ")";
      ++checkedChildren_;
      all.extend(exact);
    }
    EXPECT_EQ(uint32_t(std::popcount(interiorMask)), interiorSeen);
    return all;
  }

  const WideBvh& wide_;
  const Primitives& input_;
  std::vector<uint8_t> seen_;
  int checkedChildren_ = 0;
};

WideBvh buildWide(const Primitives& input) {
  return collapseToWide(buildBvh(input.boxes, input.centroids, leafSize(3)));
}

// Conservativeness of the quantisation, where rounding bites: tiny triangles far from the
// origin, flat and point-like inputs, huge spreads, and every tree size up to a few thousand.
TEST(WideBvh, QuantisedBoxesContainTheirChildrenExactly) {
  int children = 0;
  for (size_t n : {1u, 2u, 3u, 4u, 9u, 25u, 100u, 1000u, 5000u}) {
    SCOPED_TRACE(std::to_string(n) + " triangles");
    Primitives soup = primitivesOf(triangleSoup(n, uint32_t(n) + 11));
    WideBvh wide = buildWide(soup);
    WideChecker checker(wide, soup);
    checker.check();
    children += checker.checkedChildren();
  }
  // 1 cm triangles 1 km from the origin (a grid step of about 2^-16 against coordinates of
  // 2^10: the float sum origin + q * 2^e rounds at the level of the box itself).
  std::vector<Triangle> far = triangleSoup(3000, 5, 3.0f, 0.01f);
  for (Triangle& t : far)
    for (glm::vec3* p : {&t.a, &t.b, &t.c}) *p += glm::vec3(1000.0f, -1000.0f, 1000.0f);
  // Flat (z = const), needle and point-like triangles, and a spread of 1e-3 to 1e6.
  std::vector<Triangle> odd = triangleSoup(500, 6);
  for (Triangle& t : odd) t.a.z = t.b.z = t.c.z = 2.0f;
  std::vector<Triangle> points(200, Triangle{glm::vec3(1.5f), glm::vec3(1.5f), glm::vec3(1.5f)});
  odd.insert(odd.end(), points.begin(), points.end());
  std::vector<Triangle> spread = triangleSoup(2000, 7, 2e6f, 1e-3f);
  for (const std::vector<Triangle>* input : {&far, &odd, &spread}) {
    Primitives primitives = primitivesOf(*input);
    WideBvh wide = buildWide(primitives);
    WideChecker checker(wide, primitives);
    checker.check();
    children += checker.checkedChildren();
  }
  std::printf("[ bvh ] wide: %d quantised child boxes checked\n", children);
  EXPECT_GT(children, 5000);
}

TEST(WideBvh, RefusesLeavesAboveThreeTriangles) {
  Primitives soup = primitivesOf(triangleSoup(400, 3));
  BvhBuildOptions options = leafSize(8);
  options.traversalCost = 8.0f;  // full leaves
  EXPECT_THROW(collapseToWide(buildBvh(soup.boxes, soup.centroids, options)), Error);
}

SceneBvhOptions wideOptions() {
  SceneBvhOptions options;
  options.layout = BvhLayout::Wide;
  return options;
}

TEST(CpuTraceWide, MatchesBruteForceOnRandomScenes) {
  Agreement total;
  for (uint32_t seed : {1u, 2u, 3u}) {
    SCOPED_TRACE("scene seed " + std::to_string(seed));
    Scene scene = randomScene(seed);
    Agreement a = compareWithBruteForce(scene, randomRays(scene, 3500, seed * 101), wideOptions());
    total.rays += a.rays;
    total.hits += a.hits;
    total.ties += a.ties;
    total.alphaChanged += a.alphaChanged;
    if (HasFatalFailure()) return;
  }
  std::printf("[ bvh ] wide: %d rays, %d closest hits, %d ties, alpha test changed %d answers\n",
              total.rays, total.hits, total.ties, total.alphaChanged);
  EXPECT_GT(total.hits, total.rays / 2);
  EXPECT_GT(total.alphaChanged, total.rays / 100);
}

// Tiny triangles 1 km from the origin, rays aimed at their vertices and edge midpoints: where
// a non-conservative quantised box would cull hits that the watertight test finds.
TEST(CpuTraceWide, EdgeRaysFarFromTheOriginMatchBruteForce) {
  std::vector<Triangle> far = triangleSoup(2000, 9, 3.0f, 0.01f);
  for (Triangle& t : far)
    for (glm::vec3* p : {&t.a, &t.b, &t.c}) *p += glm::vec3(1000.0f, -1000.0f, 1000.0f);
  Scene scene;
  scene.materials.resize(1);
  Mesh mesh;
  mesh.geometries.push_back(geometryOf(far, 0));
  scene.meshes.push_back(mesh);
  scene.instances.push_back({0, glm::mat4(1.0f), "far"});
  std::mt19937 rng(10);
  std::vector<RayQuery> rays;
  for (size_t i = 0; i < 3000; ++i) {
    const Triangle& t = far[i % far.size()];
    const glm::vec3 corners[3] = {t.a, t.b, t.c};
    const glm::vec3 target =
        i % 2 ? corners[i % 3] : 0.5f * (corners[i % 3] + corners[(i + 1) % 3]);
    RayQuery q;
    q.ray.origin = target + glm::normalize(randomPoint(rng, -1.0f, 1.0f)) * 2.0f;
    q.ray.direction = target - q.ray.origin;
    q.tMax = kInfinity;
    rays.push_back(q);
  }
  Agreement a = compareWithBruteForce(scene, rays, wideOptions());
  std::printf("[ bvh ] wide, far edges: %d rays, %d hits\n", a.rays, a.hits);
  EXPECT_GT(a.hits, a.rays / 4);
}

// The two layouts give the same answers on real scenes: the same triangle (or a tie within
// 1e-5 relative t) with the same t and barycentrics, identical visibility, with and without
// the alpha test.
void expectLayoutsAgree(const Scene& scene, size_t rayCount, uint32_t seed) {
  SceneBvh binary = buildSceneBvh(scene);
  SceneBvh wide = buildSceneBvh(scene, wideOptions());
  ASSERT_EQ(wide.layout, BvhLayout::Wide);
  ASSERT_TRUE(wide.blasNodes.empty());
  CpuTracer binaryTracer(binary), wideTracer(wide);
  const std::vector<RayQuery> rays = randomRays(scene, rayCount, seed);
  Agreement agreement;
  int visibilityDiffers = 0;
  for (size_t i = 0; i < rays.size(); ++i) {
    const Ray& ray = rays[i].ray;
    const float tMax = rays[i].tMax;
    for (const AlphaTest& alpha : {AlphaTest(), AlphaTest(evenPrimitivesOpaque)}) {
      ++agreement.rays;
      const TraceHit w = wideTracer.closestHit(ray, tMax, alpha);
      const TraceHit b = binaryTracer.closestHit(ray, tMax, alpha);
      expectSameClosestHit(w, b, i, agreement);
      if (w.hit && b.hit && w.primitive == b.primitive && w.instance == b.instance &&
          w.geometry == b.geometry)
        EXPECT_EQ(w.t, b.t) << "ray " << i << ": same triangle, same arithmetic";
      visibilityDiffers +=
          wideTracer.anyHit(ray, tMax, alpha) != binaryTracer.anyHit(ray, tMax, alpha);
    }
    if (::testing::Test::HasFatalFailure()) return;
  }
  EXPECT_EQ(visibilityDiffers, 0);
  std::printf(
      "[ bvh ] %s: wide %zu nodes (%.2f MiB), binary %zu nodes (%.2f MiB); %d queries, "
      "%d hits, %d ties, all agree\n",
      scene.name.c_str(), wide.blasWideNodes.size(), double(wide.stats.bytes.blasNodes) / (1 << 20),
      binary.blasNodes.size(), double(binary.stats.bytes.blasNodes) / (1 << 20), agreement.rays,
      agreement.hits, agreement.ties);
  EXPECT_GT(agreement.hits, agreement.rays / 5);
}

class CpuTraceWideScenes : public ::testing::TestWithParam<std::string> {};
TEST_P(CpuTraceWideScenes, MatchesBinary) {
  std::optional<Scene> scene = makeBuiltinScene(GetParam());
  if (!scene) GTEST_SKIP() << "built-in scene '" << GetParam() << "' not available";
  expectLayoutsAgree(*scene, 4000, 31);
}
// cornell, sunroom: real rooms; foliage: instancing and alpha-tested leaves; city: a large
// instanced scene (441 k unique triangles).
INSTANTIATE_TEST_SUITE_P(Builtin, CpuTraceWideScenes,
                         ::testing::Values("cornell", "sunroom", "foliage", "city"));

// A soup (overlapping triangles everywhere) and the random scenes' rotated, non-uniformly
// scaled and mirrored instances.
TEST(CpuTraceWide, MatchesBinaryOnSoupAndTransformedInstances) {
  Scene soup;
  soup.name = "soup";
  soup.materials.resize(2);
  soup.materials[1].alphaMode = AlphaMode::Mask;
  Mesh mesh;
  mesh.geometries.push_back(geometryOf(triangleSoup(20000, 12, 10.0f, 0.6f), 0));
  mesh.geometries.push_back(geometryOf(triangleSoup(5000, 13, 10.0f, 0.6f), 1));
  soup.meshes.push_back(mesh);
  soup.instances.push_back({0, glm::mat4(1.0f), "soup"});
  expectLayoutsAgree(soup, 4000, 5);
  for (uint32_t seed : {6u, 7u}) expectLayoutsAgree(randomScene(seed), 3000, seed);
}

// ---- throughput (printed, never asserted) -----------------------------------------------------

// 10k instances of a few meshes (boxes up to 6 wide) scattered in a city-sized square.
std::vector<gpu::GpuInstance> scatteredInstances(std::vector<Aabb>& meshBounds) {
  std::mt19937 rng(4);
  meshBounds.assign(4, Aabb{});
  for (Aabb& b : meshBounds) {
    b.extend(randomPoint(rng, -3.0f, 0.0f));
    b.extend(randomPoint(rng, 0.0f, 3.0f));
  }
  std::vector<gpu::GpuInstance> instances(10000);
  for (size_t i = 0; i < instances.size(); ++i) {
    glm::mat4 m = glm::translate(glm::mat4(1.0f), 500.0f * glm::vec3(randomPoint(rng, -1, 1).x, 0,
                                                                     randomPoint(rng, -1, 1).z));
    m = glm::rotate(m, float(i), glm::vec3(0, 1, 0));
    setInstanceTransform(instances[i], m);
    instances[i].mesh = uint32_t(i % meshBounds.size());
  }
  return instances;
}

// Best of `repeats` wall times of f, in ms (the machine is shared).
template <typename F>
double bestMs(int repeats, F&& f) {
  double best = 1e30;
  for (int r = 0; r < repeats; ++r) {
    const auto start = std::chrono::steady_clock::now();
    f();
    best = std::min(
        best, std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                  .count());
  }
  return best;
}

// What GpuScene's rebuild policy costs the CPU per move on 10k instances: the check (a refit
// and the SAH cost, at every setInstanceTransforms) and a rebuild (when the check says so).
TEST(BvhBenchmark, PrintsTlasRebuildPolicyCost) {
  std::vector<Aabb> meshBounds;
  std::vector<gpu::GpuInstance> instances = scatteredInstances(meshBounds);
  std::vector<gpu::GpuBvhNode> tlas;
  TlasRefitState state;
  const double rebuildMs =
      bestMs(5, [&] { buildRefittedTlas(tlas, state, instances, meshBounds); });
  const double refitMs = bestMs(20, [&] { refitTlas(tlas, state.plan, instances, meshBounds); });
  double cost = 0.0;
  const double costMs = bestMs(20, [&] { cost = tlasSahCost(tlas); });
  const double checkMs =
      bestMs(20, [&] { updateRefittedTlas(tlas, state, instances, meshBounds, 0.0); });
  EXPECT_EQ(state.costRatio, 1.0);  // nothing moved
  std::printf(
      "[ bvh ] TLAS rebuild policy, %zu instances: check %.3f ms (refit %.3f ms, SAH cost %.3f "
      "ms), rebuild %.2f ms (SAH cost %.2f)\n",
      instances.size(), checkMs, refitMs, costMs, rebuildMs, cost);
}

void printBuild(const char* what, const Primitives& input, uint32_t threads) {
  BvhBuildOptions options;
  options.threadCount = threads;
  BvhBuildStats best;
  for (int repeat = 0; repeat < 3; ++repeat) {  // best of three: the machine is shared
    BvhBuildStats stats = buildBvh(input.boxes, input.centroids, options).stats;
    if (repeat == 0 || stats.seconds < best.seconds) best = stats;
  }
  std::printf(
      "[ bvh ] %-28s %zu triangles, %u thread(s): %6.1f ms, %5.2f M triangles/s, "
      "SAH cost %.2f, %u nodes, %u leaves, depth %u\n",
      what, input.boxes.size(), threads, best.seconds * 1e3, best.primitivesPerSecond * 1e-6,
      best.sahCost, best.nodeCount, best.leafCount, best.maxDepth);
}

// Issue 22's aim: `city` (441 k unique triangles) built at 5 M triangles/s or more on two
// threads, timed as bench-rays times it (rt::buildSceneBvh; GpuScene adds a TLAS of 1.7 k
// instances). Disabled: a timing on a shared machine is no pass/fail test. Measured on 2-core
// development machines (docs/benchmarks.md, "BVH build"): 2026-11-28, idle, 42.3 ms, 10.4 M
// triangles/s; 2026-11-27, with other sessions' compiles on the cores, 93.7 ms, 4.70 M/s
// (2.37 M/s before commit 87bde46). Run it with --gtest_also_run_disabled_tests on a quiet
// machine.
TEST(BvhBenchmark, DISABLED_CityBuildsAtFiveMillionTrianglesPerSecondOnTwoThreads) {
  std::optional<Scene> city = makeBuiltinScene("city");
  if (!city) GTEST_SKIP() << "built-in scene 'city' not available";
  SceneBvhOptions options;
  options.blas.threadCount = options.tlas.threadCount = 2;
  std::vector<double> seconds;
  for (int i = 0; i < 9; ++i) {
    const auto start = std::chrono::steady_clock::now();
    SceneBvh bvh = buildSceneBvh(*city, options);
    seconds.push_back(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  std::sort(seconds.begin(), seconds.end());
  const double perSecond = double(city->uniqueTriangleCount()) / seconds[seconds.size() / 2];
  std::printf("[ bvh ] city on 2 threads: median %.1f ms, %.2f M triangles/s\n",
              seconds[seconds.size() / 2] * 1e3, perSecond * 1e-6);
  EXPECT_GE(perSecond, 5e6);
}

TEST(BvhBenchmark, PrintsBuildThroughput) {
  Primitives soup = primitivesOf(triangleSoup(1000000, 42, 100.0f, 0.5f));
  Primitives sphere = primitivesOf(bumpySphere(708));
  for (uint32_t threads : {1u, 2u}) {
    printBuild("random soup", soup, threads);
    printBuild("tessellated bumpy sphere", sphere, threads);
  }
  if (std::optional<Scene> city = makeBuiltinScene("city")) {
    SceneBvh bvh = buildSceneBvh(*city);
    const SceneBvhStats& s = bvh.stats;
    std::printf(
        "[ bvh ] scene 'city': %zu meshes, %llu unique triangles, %zu instances: "
        "%.1f ms (BLAS %.1f ms, %.2f M triangles/s, SAH %.2f; TLAS %.2f ms, SAH %.2f), "
        "%.1f MiB\n",
        city->meshes.size(), (unsigned long long)s.triangleCount, bvh.instances.size(),
        s.seconds * 1e3, s.blasSeconds * 1e3, s.trianglesPerSecond * 1e-6, s.blasSahCost,
        s.tlasSeconds * 1e3, s.tlasSahCost, double(s.bytes.total()) / (1 << 20));
  }
  // The per-frame TLAS.
  std::vector<Aabb> meshBounds;
  std::vector<gpu::GpuInstance> instances = scatteredInstances(meshBounds);
  double best = 1e9;
  BvhBuildStats stats;
  for (int repeat = 0; repeat < 5; ++repeat) {
    auto start = std::chrono::steady_clock::now();
    std::vector<gpu::GpuBvhNode> tlas =
        buildTlas(instances, meshBounds, tlasBuildOptions(), &stats);
    best = std::min(
        best, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    ASSERT_EQ(stats.leafCount, instances.size());
  }
  std::printf("[ bvh ] TLAS over %zu instances: %.2f ms, SAH cost %.2f, depth %u\n",
              instances.size(), best * 1e3, stats.sahCost, stats.maxDepth);
}

}  // namespace
}  // namespace bounce::rt
