#include "rt/scene_bvh.h"

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <mutex>
#include <thread>

#include <glm/gtc/packing.hpp>

#include "core/error.h"
#include "rt/huge_pages.h"
#include "rt/task_pool.h"
#include "rt/wide_bvh.h"

namespace bounce::rt {
namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// Meshes at least this large are built one at a time with all threads; smaller ones are built
// side by side, one thread each.
constexpr uint64_t kLargeMeshTriangles = 64 * 1024;

bool finite(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

uint32_t resolveThreads(uint32_t requested) {
  return requested ? requested : std::max(1u, std::thread::hardware_concurrency());
}

// ---- geometry streams -------------------------------------------------------------------------

void checkGeometry(const Scene& scene, size_t meshIndex, size_t geometryIndex) {
  const Mesh& mesh = scene.meshes[meshIndex];
  const Geometry& g = mesh.geometries[geometryIndex];
  auto where = [&] {
    return fmt::format("scene BVH: mesh {} ('{}') geometry {}", meshIndex, mesh.name,
                       geometryIndex);
  };
  const size_t n = g.positions.size();
  if (g.normals.size() != n || g.uvs.size() != n ||
      (!g.tangents.empty() && g.tangents.size() != n) ||
      (!g.colors.empty() && g.colors.size() != n))
    fail(
        "{}: vertex streams differ in length ({} positions, {} normals, {} uvs, {} tangents, {} "
        "colours)",
        where(), n, g.normals.size(), g.uvs.size(), g.tangents.size(), g.colors.size());
  if (g.indices.size() % 3 != 0)
    fail("{}: index count {} is not a multiple of 3", where(), g.indices.size());
  for (uint32_t index : g.indices)
    if (index >= n) fail("{}: index {} out of range ({} vertices)", where(), index, n);
  for (const glm::vec3& p : g.positions)
    if (!finite(p)) fail("{}: a vertex position is NaN or infinite", where());
  if (g.material >= scene.materials.size())
    fail("{}: material {} does not exist ({} materials)", where(), g.material,
         scene.materials.size());
}

bool hasVertexColors(const Scene& scene) {
  for (const Mesh& mesh : scene.meshes)
    for (const Geometry& g : mesh.geometries)
      if (!g.colors.empty()) return true;
  return false;
}

// RGBA8 unorm keeps a colour in 4 bytes per vertex (a float vec4 would take 16); COLOR_0 is
// most often 8-bit in the file anyway.
void appendColors(const Geometry& g, std::vector<uint32_t>& out) {
  if (g.colors.empty()) {
    out.insert(out.end(), g.positions.size(), 0xFFFFFFFFu);
    return;
  }
  for (const glm::vec4& c : g.colors) out.push_back(glm::packUnorm4x8(c));
}

// Records where each geometry's streams start in the flattened arrays and reserves them;
// checks every geometry first, so that nothing later reads through a bad index.
void placeGeometries(const Scene& scene, SceneBvh& out) {
  size_t vertices = 0, indices = 0;
  for (size_t m = 0; m < scene.meshes.size(); ++m) {
    out.geometryBase.push_back(uint32_t(out.geometries.size()));
    for (size_t gi = 0; gi < scene.meshes[m].geometries.size(); ++gi) {
      checkGeometry(scene, m, gi);
      const Geometry& g = scene.meshes[m].geometries[gi];
      out.geometries.push_back(
          {uint32_t(indices), uint32_t(vertices), g.triangleCount(), g.material});
      vertices += g.positions.size();
      indices += g.indices.size();
      if (vertices >= gpu::BVH_INVALID || indices >= gpu::BVH_INVALID)
        fail("scene BVH: {} vertices and {} indices exceed 32-bit offsets", vertices, indices);
    }
  }
  reserveLarge(out.positions, vertices);
  reserveLarge(out.normals, vertices);
  reserveLarge(out.uvs, vertices);
  reserveLarge(out.tangents, vertices);
  reserveLarge(out.indices, indices);
  if (hasVertexColors(scene)) reserveLarge(out.colors, vertices);
}

// Appends every geometry's streams in mesh order, one task per stream: the copies share no
// data with each other or with the BLAS builds, so they run beside them.
void submitStreamCopies(const Scene& scene, SceneBvh& out, TaskPool& pool) {
  auto forEachGeometry = [&scene](auto append) {
    for (const Mesh& mesh : scene.meshes)
      for (const Geometry& g : mesh.geometries) append(g);
  };
  auto copy = [forEachGeometry](auto member, auto& stream) {
    return [forEachGeometry, member, &stream] {
      forEachGeometry([&](const Geometry& g) {
        const auto& from = g.*member;
        stream.insert(stream.end(), from.begin(), from.end());
      });
    };
  };
  pool.submit(copy(&Geometry::indices, out.indices));
  pool.submit(copy(&Geometry::positions, out.positions));
  pool.submit(copy(&Geometry::normals, out.normals));
  pool.submit(copy(&Geometry::uvs, out.uvs));
  pool.submit([forEachGeometry, &out] {
    forEachGeometry([&](const Geometry& g) {
      if (g.tangents.empty())
        out.tangents.insert(out.tangents.end(), g.positions.size(), glm::vec4(1, 0, 0, 1));
      else
        out.tangents.insert(out.tangents.end(), g.tangents.begin(), g.tangents.end());
    });
  });
  if (out.colors.capacity() > 0)
    pool.submit([forEachGeometry, &out] {
      forEachGeometry([&](const Geometry& g) { appendColors(g, out.colors); });
    });
}

// ---- one BLAS per mesh ------------------------------------------------------------------------

// A mesh's triangles are numbered across its geometries in order: triangle t belongs to the
// geometry g with firstTriangle[g] <= t < firstTriangle[g + 1].
struct MeshTriangles {
  std::vector<uint32_t> firstTriangle;  // per geometry, plus the total at the end
  uint32_t count() const { return firstTriangle.back(); }
};

MeshTriangles numberTriangles(const Mesh& mesh) {
  // GpuTriangle::geometry keeps the local geometry index in 31 bits.
  if (mesh.geometries.size() >= gpu::GPU_TRIANGLE_ALPHA_TESTED)
    fail("scene BVH: mesh '{}' has {} geometries", mesh.name, mesh.geometries.size());
  MeshTriangles t;
  t.firstTriangle.push_back(0);
  uint64_t total = 0;
  for (const Geometry& g : mesh.geometries) {
    total += g.triangleCount();
    if (total >= gpu::BVH_INVALID) fail("scene BVH: mesh '{}' has over 2^32 triangles", mesh.name);
    t.firstTriangle.push_back(uint32_t(total));
  }
  return t;
}

struct MeshBlas {
  Bvh bvh;  // with BvhLayout::Wide, only its stats are kept (the nodes are collapsed into wide)
  WideBvh wide;
  MeshTriangles triangles;
  Aabb bounds;
  // Leaf order of the layout built: indices of the mesh's triangles.
  const std::vector<uint32_t>& order(BvhLayout layout) const {
    return layout == BvhLayout::Wide ? wide.primitiveOrder : bvh.primitiveOrder;
  }
  size_t nodeCount(BvhLayout layout) const {
    return layout == BvhLayout::Wide ? wide.nodes.size() : bvh.nodes.size();
  }
};

// Working memory of one BLAS build, handed from build to build (ScratchShelf).
struct MeshScratch {
  BvhScratch bvh;
  std::vector<Aabb> boxes;
  std::vector<glm::vec3> centroids;
};

// Scratches of the builds in flight: a build takes one (or a new one) and puts it back.
class ScratchShelf {
 public:
  std::unique_ptr<MeshScratch> take() {
    std::lock_guard lock(mutex_);
    if (free_.empty()) return std::make_unique<MeshScratch>();
    std::unique_ptr<MeshScratch> s = std::move(free_.back());
    free_.pop_back();
    return s;
  }
  void give(std::unique_ptr<MeshScratch> s) {
    std::lock_guard lock(mutex_);
    free_.push_back(std::move(s));
  }

 private:
  std::mutex mutex_;
  std::vector<std::unique_ptr<MeshScratch>> free_;
};

MeshBlas buildMeshBlas(const Mesh& mesh, const BvhBuildOptions& options, BvhLayout layout,
                       MeshScratch& scratch) {
  MeshBlas blas;
  blas.triangles = numberTriangles(mesh);
  std::vector<Aabb>& boxes = scratch.boxes;
  std::vector<glm::vec3>& centroids = scratch.centroids;
  if (boxes.capacity() < blas.triangles.count()) {
    boxes = {};
    centroids = {};
    reserveLarge(boxes, blas.triangles.count());
    reserveLarge(centroids, blas.triangles.count());
  }
  boxes.resize(blas.triangles.count());
  centroids.resize(boxes.size());
  size_t t = 0;
  for (const Geometry& g : mesh.geometries) {
    for (size_t i = 0; i < g.indices.size(); i += 3, ++t) {
      const glm::vec3& a = g.positions[g.indices[i]];
      const glm::vec3& b = g.positions[g.indices[i + 1]];
      const glm::vec3& c = g.positions[g.indices[i + 2]];
      boxes[t].min = glm::min(a, glm::min(b, c));
      boxes[t].max = glm::max(a, glm::max(b, c));
      centroids[t] = boxes[t].center();  // the box centre, as Wald 2007 bins
      blas.bounds.extend(boxes[t]);
    }
  }
  blas.bvh = buildBvh(boxes, centroids, options, &scratch.bvh);
  if (layout == BvhLayout::Wide) {
    blas.wide = collapseToWide(blas.bvh);
    blas.bvh.nodes = {};
    blas.bvh.primitiveOrder = {};
  }
  return blas;
}

uint64_t meshTriangleCount(const Mesh& mesh) {
  uint64_t triangles = 0;
  for (const Geometry& g : mesh.geometries) triangles += g.triangleCount();
  return triangles;
}

// Where each mesh's triangles start in the shared triangle array (known before any BLAS is
// built, so each build can write its triangles at once), and the array itself.
void placeTriangles(const Scene& scene, SceneBvh& out) {
  uint64_t triangles = 0;
  for (const Mesh& mesh : scene.meshes) {
    out.blasTriangleBase.push_back(uint32_t(triangles));
    triangles += meshTriangleCount(mesh);
    // The traversal stack packs a leaf's first triangle into 26 bits (shared/scene_layout.h).
    if (triangles >= gpu::BVH_MAX_SCENE_TRIANGLES)
      fail("scene BVH: {} triangles; at most {} fit the traversal's stack entries", triangles,
           gpu::BVH_MAX_SCENE_TRIANGLES - 1);
  }
  resizeLarge(out.triangles, triangles);
}

// Writes one mesh's triangles into the shared array, in its BLAS leaf order.
void writeTriangles(const Scene& scene, size_t meshIndex, const MeshBlas& blas, SceneBvh& out) {
  const Mesh& mesh = scene.meshes[meshIndex];
  const std::vector<uint32_t>& first = blas.triangles.firstTriangle;
  const std::vector<uint32_t>& order = blas.order(out.layout);
  if (order.size() != blas.triangles.count())
    fail("scene BVH: mesh {} ('{}'): its BLAS lists {} of its {} triangles", meshIndex, mesh.name,
         order.size(), blas.triangles.count());
  gpu::GpuTriangle* triangles = out.triangles.data() + out.blasTriangleBase[meshIndex];
  for (size_t i = 0; i < order.size(); ++i) {
    const uint32_t t = order[i];
    const uint32_t g =
        uint32_t(std::upper_bound(first.begin(), first.end(), t) - first.begin() - 1);
    const Geometry& geometry = mesh.geometries[g];
    const uint32_t primitive = t - first[g];
    const uint32_t* index = &geometry.indices[size_t(primitive) * 3];
    const bool alphaTested = scene.materials[geometry.material].alphaMode != AlphaMode::Opaque;
    triangles[i] = {.v0 = geometry.positions[index[0]],
                    .primitive = primitive,
                    .v1 = geometry.positions[index[1]],
                    .geometry = g | (alphaTested ? gpu::GPU_TRIANGLE_ALPHA_TESTED : 0u),
                    .v2 = geometry.positions[index[2]],
                    .padding = 0u};
  }
}

// Builds every mesh's BLAS and writes its triangles. Large meshes are built one at a time with
// all threads; the others side by side, one thread each, largest first so that no long build
// starts last. Work already queued on the pool (the stream copies) runs beside them.
std::vector<MeshBlas> buildAllBlas(const Scene& scene, const BvhBuildOptions& options,
                                   SceneBvh& out, TaskPool& pool) {
  const size_t meshCount = scene.meshes.size();
  std::vector<MeshBlas> blas(meshCount);
  std::vector<std::pair<uint64_t, size_t>> small;  // (triangles, mesh)
  BvhBuildOptions single = options;
  single.threadCount = 1;
  ScratchShelf shelf;
  auto build = [&](size_t m, const BvhBuildOptions& buildOptions) {
    std::unique_ptr<MeshScratch> scratch = shelf.take();
    blas[m] = buildMeshBlas(scene.meshes[m], buildOptions, out.layout, *scratch);
    shelf.give(std::move(scratch));
  };
  for (size_t m = 0; m < meshCount; ++m) {
    const uint64_t triangles = meshTriangleCount(scene.meshes[m]);
    if (triangles >= kLargeMeshTriangles) {
      build(m, options);
      writeTriangles(scene, m, blas[m], out);
    } else {
      small.push_back({triangles, m});
    }
  }
  std::stable_sort(small.begin(), small.end(),
                   [](const auto& a, const auto& b) { return a.first > b.first; });
  // Each build is deterministic on its own, so the schedule cannot change the result.
  pool.parallelFor(uint32_t(small.size()), [&](uint32_t i) {
    const size_t m = small[i].second;
    build(m, single);
    writeTriangles(scene, m, blas[m], out);
  });
  return blas;
}

// Copies one mesh's BLAS nodes into the shared array: node indices become absolute, leaves
// point into the shared triangle array.
void appendBlasNodes(const MeshBlas& blas, uint32_t nodeOffset, uint32_t triangleOffset,
                     SceneBvh& out) {
  if (out.layout == BvhLayout::Wide) {
    gpu::GpuWideBvhNode* nodes = out.blasWideNodes.data() + nodeOffset;
    for (size_t i = 0; i < blas.wide.nodes.size(); ++i) {
      gpu::GpuWideBvhNode node = blas.wide.nodes[i];
      node.childBase += nodeOffset;
      node.triangleBase += triangleOffset;
      nodes[i] = node;
    }
    return;
  }
  auto relocate = [&](uint32_t& index, uint32_t count) {
    if (count > 0)
      index += triangleOffset;
    else if (index != gpu::BVH_INVALID)
      index += nodeOffset;
  };
  gpu::GpuBvhNode* nodes = out.blasNodes.data() + nodeOffset;
  for (size_t i = 0; i < blas.bvh.nodes.size(); ++i) {
    gpu::GpuBvhNode node = blas.bvh.nodes[i];
    relocate(node.leftIndex, node.leftCount);
    relocate(node.rightIndex, node.rightCount);
    nodes[i] = node;
  }
}

void concatenateBlasNodes(const std::vector<MeshBlas>& blas, TaskPool& pool, SceneBvh& out) {
  std::vector<uint32_t> nodeOffset(blas.size());
  uint64_t nodes = 0;
  for (size_t m = 0; m < blas.size(); ++m) {
    nodeOffset[m] = uint32_t(nodes);
    nodes += blas[m].nodeCount(out.layout);
    // The traversal stack packs a node index into 30 bits (shared/scene_layout.h).
    if (nodes >= gpu::BVH_STACK_LEAF)
      fail("scene BVH: {} BLAS nodes; at most {} fit the traversal's stack entries", nodes,
           gpu::BVH_STACK_LEAF - 1);
  }
  if (out.layout == BvhLayout::Wide)
    resizeLarge(out.blasWideNodes, nodes);
  else
    resizeLarge(out.blasNodes, nodes);
  out.blasRoot = nodeOffset;
  pool.parallelFor(uint32_t(blas.size()), [&](uint32_t m) {
    appendBlasNodes(blas[m], nodeOffset[m], out.blasTriangleBase[m], out);
  });
}

void recordBlasStats(const std::vector<MeshBlas>& blas, BvhLayout layout, SceneBvhStats& stats) {
  double weightedSah = 0.0;
  for (const MeshBlas& b : blas) {
    const double triangles = double(b.bvh.stats.primitiveCount);
    stats.triangleCount += b.bvh.stats.primitiveCount;
    stats.maxBlasDepth = std::max(
        stats.maxBlasDepth, layout == BvhLayout::Wide ? b.wide.maxDepth : b.bvh.stats.maxDepth);
    weightedSah += b.bvh.stats.sahCost * triangles;
  }
  if (stats.triangleCount > 0) stats.blasSahCost = weightedSah / double(stats.triangleCount);
}

template <typename T>
size_t bytesOf(const std::vector<T>& v) {
  return v.size() * sizeof(T);
}

}  // namespace

const char* bvhLayoutName(BvhLayout layout) {
  return layout == BvhLayout::Wide ? "wide" : "binary";
}

BvhLayout parseBvhLayout(const std::string& name) {
  if (name == "binary") return BvhLayout::Binary;
  if (name == "wide") return BvhLayout::Wide;
  fail("BVH layout '{}': expected binary or wide", name);
}

// ---- instances --------------------------------------------------------------------------------

void setInstanceTransform(gpu::GpuInstance& instance, const glm::mat4& objectToWorld) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 3; ++r)
      if (!std::isfinite(objectToWorld[c][r]))
        fail("instance transform has a NaN or infinite entry");
  const glm::mat3 linear(objectToWorld);
  const float det = glm::determinant(linear);
  const glm::mat3 inverseLinear = glm::inverse(linear);
  const glm::vec3 inverseTranslation = -(inverseLinear * glm::vec3(objectToWorld[3]));
  bool invertible = det != 0.0f && std::isfinite(det) && finite(inverseTranslation);
  for (int c = 0; c < 3; ++c) invertible = invertible && finite(inverseLinear[c]);
  if (!invertible) {
    // Scaled to nothing: hidden (GPU_INSTANCE_HIDDEN), not an error, so that an animation
    // may pass through scale 0.
    for (int r = 0; r < 3; ++r)
      instance.objectToWorld[r] = instance.worldToObject[r] = glm::vec4(0);
    instance.flags |= gpu::GPU_INSTANCE_HIDDEN;
    return;
  }
  instance.flags &= ~gpu::GPU_INSTANCE_HIDDEN;
  // Rows of the 3x4 matrices; glm stores columns.
  for (int r = 0; r < 3; ++r) {
    instance.objectToWorld[r] = glm::vec4(objectToWorld[0][r], objectToWorld[1][r],
                                          objectToWorld[2][r], objectToWorld[3][r]);
    instance.worldToObject[r] = glm::vec4(inverseLinear[0][r], inverseLinear[1][r],
                                          inverseLinear[2][r], inverseTranslation[r]);
  }
}

gpu::GpuInstance makeGpuInstance(const glm::mat4& objectToWorld, uint32_t mesh,
                                 const SceneBvh& bvh) {
  if (mesh >= bvh.blasRoot.size())
    fail("instance refers to mesh {} ({} meshes)", mesh, bvh.blasRoot.size());
  gpu::GpuInstance instance{};
  setInstanceTransform(instance, objectToWorld);
  instance.blasRoot = bvh.blasRoot[mesh];
  instance.geometryBase = bvh.geometryBase[mesh];
  instance.mesh = mesh;
  return instance;
}

// Arvo 1990 ("Transforming axis-aligned bounding boxes"): the transformed box's half extent is
// |M| times the original's, its centre M times the centre.
Aabb instanceWorldBounds(const gpu::GpuInstance& instance, const Aabb& meshBounds) {
  const glm::vec3 center = meshBounds.center();
  const glm::vec3 halfExtent = 0.5f * meshBounds.extent();
  Aabb box;
  for (int r = 0; r < 3; ++r) {
    const glm::vec4& row = instance.objectToWorld[r];
    const float worldCenter = row.x * center.x + row.y * center.y + row.z * center.z + row.w;
    const float worldHalfExtent = std::abs(row.x) * halfExtent.x + std::abs(row.y) * halfExtent.y +
                                  std::abs(row.z) * halfExtent.z;
    // Rays meet the mesh in object space, through the rounded worldToObject; widen the world
    // box by a few float ulps of its coordinates so the TLAS never culls such a hit at the edge.
    const float pad = 1e-5f * (std::abs(worldCenter) + worldHalfExtent);
    box.min[r] = worldCenter - worldHalfExtent - pad;
    box.max[r] = worldCenter + worldHalfExtent + pad;
  }
  return box;
}

std::vector<gpu::GpuBvhNode> buildTlas(std::span<const gpu::GpuInstance> instances,
                                       std::span<const Aabb> meshBounds,
                                       const BvhBuildOptions& options, BvhBuildStats* stats,
                                       bool keepHidden) {
  if (options.maxLeafSize != 1) fail("TLAS build: maxLeafSize must be 1 (one instance per leaf)");
  std::vector<Aabb> boxes;
  std::vector<glm::vec3> centroids;
  std::vector<uint32_t> instanceOfPrimitive;
  boxes.reserve(instances.size());
  centroids.reserve(instances.size());
  instanceOfPrimitive.reserve(instances.size());
  for (size_t i = 0; i < instances.size(); ++i) {
    const gpu::GpuInstance& instance = instances[i];
    if (instance.mesh >= meshBounds.size())
      fail("TLAS build: instance {} refers to mesh {} ({} meshes)", i, instance.mesh,
           meshBounds.size());
    const Aabb& bounds = meshBounds[instance.mesh];
    const bool hidden = instance.flags & gpu::GPU_INSTANCE_HIDDEN;
    if (bounds.empty() || (hidden && !keepHidden)) continue;  // nothing to hit
    boxes.push_back(instanceWorldBounds(instance, bounds));
    centroids.push_back(boxes.back().center());
    instanceOfPrimitive.push_back(uint32_t(i));
  }
  BvhBuildOptions tlasOptions = options;
  tlasOptions.measureTree = options.measureTree && stats != nullptr;
  Bvh bvh = buildBvh(boxes, centroids, tlasOptions);
  for (gpu::GpuBvhNode& node : bvh.nodes) {
    if (node.leftCount > 0)
      node.leftIndex = instanceOfPrimitive[bvh.primitiveOrder[node.leftIndex]];
    if (node.rightCount > 0)
      node.rightIndex = instanceOfPrimitive[bvh.primitiveOrder[node.rightIndex]];
  }
  if (stats) *stats = bvh.stats;
  return std::move(bvh.nodes);
}

std::vector<gpu::GpuBvhNode> buildRefittableTlas(std::span<const gpu::GpuInstance> instances,
                                                 std::span<const Aabb> meshBounds) {
  return buildTlas(instances, meshBounds, tlasBuildOptions(), nullptr, true);
}

namespace {

// Breadth first from the root (levels in order of depth), then the levels deepest first.
// `children(node, out)` appends a node's interior children.
template <typename Children>
RefitPlan planLevels(uint32_t root, Children children) {
  RefitPlan plan;
  std::vector<std::vector<uint32_t>> levels{{root}};
  while (true) {
    std::vector<uint32_t> next;
    for (uint32_t node : levels.back()) children(node, next);
    if (next.empty()) break;
    levels.push_back(std::move(next));
  }
  for (auto level = levels.rbegin(); level != levels.rend(); ++level) {
    plan.levelStart.push_back(uint32_t(plan.nodes.size()));
    plan.nodes.insert(plan.nodes.end(), level->begin(), level->end());
  }
  plan.levelStart.push_back(uint32_t(plan.nodes.size()));
  return plan;
}

}  // namespace

RefitPlan planBinaryRefit(std::span<const gpu::GpuBvhNode> nodes, uint32_t root) {
  if (root >= nodes.size()) return {};
  return planLevels(root, [&](uint32_t node, std::vector<uint32_t>& out) {
    for (auto [index, count] : {std::pair{nodes[node].leftIndex, nodes[node].leftCount},
                                std::pair{nodes[node].rightIndex, nodes[node].rightCount}})
      if (count == 0 && index != gpu::BVH_INVALID) out.push_back(index);
  });
}

RefitPlan planWideRefit(std::span<const gpu::GpuWideBvhNode> nodes, uint32_t root) {
  if (root >= nodes.size()) return {};
  return planLevels(root, [&](uint32_t node, std::vector<uint32_t>& out) {
    const uint32_t interior = nodes[node].exponentsAndMask >> 24;
    for (uint32_t k = 0; k < uint32_t(std::popcount(interior)); ++k)
      out.push_back(nodes[node].childBase + k);
  });
}

TlasRefitPlan planTlasRefit(std::span<const gpu::GpuBvhNode> tlas) {
  return planBinaryRefit(tlas, 0);
}

namespace {

Aabb refittedChild(std::span<const gpu::GpuBvhNode> tlas, uint32_t index, uint32_t count,
                   std::span<const gpu::GpuInstance> instances, std::span<const Aabb> meshBounds) {
  if (count > 0) {
    const gpu::GpuInstance& instance = instances[index];
    if (instance.flags & gpu::GPU_INSTANCE_HIDDEN) return Aabb{};
    return instanceWorldBounds(instance, meshBounds[instance.mesh]);
  }
  Aabb box;
  if (index == gpu::BVH_INVALID) return box;  // an empty root slot stays empty
  box.extend(Aabb{tlas[index].leftMin, tlas[index].leftMax});
  box.extend(Aabb{tlas[index].rightMin, tlas[index].rightMax});
  return box;
}

}  // namespace

void refitTlas(std::span<gpu::GpuBvhNode> tlas, const TlasRefitPlan& plan,
               std::span<const gpu::GpuInstance> instances, std::span<const Aabb> meshBounds) {
  for (uint32_t node : plan.nodes) {
    gpu::GpuBvhNode& n = tlas[node];
    const Aabb left = refittedChild(tlas, n.leftIndex, n.leftCount, instances, meshBounds);
    const Aabb right = refittedChild(tlas, n.rightIndex, n.rightCount, instances, meshBounds);
    n.leftMin = left.min;
    n.leftMax = left.max;
    n.rightMin = right.min;
    n.rightMax = right.max;
  }
}

double tlasSahCost(std::span<const gpu::GpuBvhNode> tlas) {
  return measureBvh(tlas, 0, tlasBuildOptions().traversalCost).sahCost;
}

void buildRefittedTlas(std::vector<gpu::GpuBvhNode>& tlas, TlasRefitState& state,
                       std::span<const gpu::GpuInstance> instances,
                       std::span<const Aabb> meshBounds) {
  tlas = buildRefittableTlas(instances, meshBounds);
  state.plan = planTlasRefit(tlas);
  refitTlas(tlas, state.plan, instances, meshBounds);
  state.builtCost = tlasSahCost(tlas);
  state.costRatio = 1.0;
}

bool updateRefittedTlas(std::vector<gpu::GpuBvhNode>& tlas, TlasRefitState& state,
                        std::span<const gpu::GpuInstance> instances,
                        std::span<const Aabb> meshBounds, double rebuildRatio) {
  refitTlas(tlas, state.plan, instances, meshBounds);
  const double cost = tlasSahCost(tlas);
  state.costRatio = state.builtCost > 0.0 ? cost / state.builtCost
                    : cost > 0.0          ? std::numeric_limits<double>::infinity()
                                          : 1.0;
  if (rebuildRatio <= 0.0 || !(state.costRatio > rebuildRatio)) return false;
  buildRefittedTlas(tlas, state, instances, meshBounds);
  ++state.rebuilds;
  return true;
}

// ---- the whole scene --------------------------------------------------------------------------

SceneBvh buildSceneBvh(const Scene& scene, const SceneBvhOptions& options) {
  const auto start = Clock::now();
  SceneBvh out;
  placeGeometries(scene, out);

  const uint32_t leafLimit = 1u << (30 - gpu::BVH_STACK_LEAF_COUNT_SHIFT);
  if (options.blas.maxLeafSize > leafLimit)
    fail("scene BVH: BLAS leaves of up to {} triangles; the traversal's stack entries hold {}",
         options.blas.maxLeafSize, leafLimit);
  out.layout = options.layout;
  BvhBuildOptions blasOptions = options.blas;
  if (options.layout == BvhLayout::Wide)
    blasOptions.maxLeafSize = std::min(blasOptions.maxLeafSize, gpu::BVH_WIDE_MAX_LEAF_TRIANGLES);
  const auto blasStart = Clock::now();
  std::vector<MeshBlas> blas;
  {
    TaskPool pool(resolveThreads(options.blas.threadCount));
    submitStreamCopies(scene, out, pool);
    placeTriangles(scene, out);
    blas = buildAllBlas(scene, blasOptions, out, pool);
    concatenateBlasNodes(blas, pool, out);
    pool.wait();
  }
  for (const MeshBlas& b : blas) out.meshBounds.push_back(b.bounds);
  out.stats.blasSeconds = secondsSince(blasStart);
  recordBlasStats(blas, options.layout, out.stats);
  blas.clear();

  out.instances.reserve(scene.instances.size());
  for (size_t i = 0; i < scene.instances.size(); ++i) {
    const Instance& instance = scene.instances[i];
    try {
      out.instances.push_back(makeGpuInstance(instance.transform, instance.mesh, out));
    } catch (const Error& e) {
      fail("scene BVH: instance {} ('{}'): {}", i, instance.name, e.what());
    }
  }

  const auto tlasStart = Clock::now();
  BvhBuildStats tlasStats;
  out.tlasNodes = buildTlas(out.instances, out.meshBounds, options.tlas, &tlasStats);
  out.stats.tlasSeconds = secondsSince(tlasStart);

  SceneBvhStats& stats = out.stats;
  stats.blasNodeCount = uint32_t(out.blasNodes.size() + out.blasWideNodes.size());
  stats.tlasNodeCount = uint32_t(out.tlasNodes.size());
  stats.tlasDepth = tlasStats.maxDepth;
  stats.tlasSahCost = tlasStats.sahCost;
  stats.trianglesPerSecond =
      stats.blasSeconds > 0.0 ? double(stats.triangleCount) / stats.blasSeconds : 0.0;
  stats.bytes = {bytesOf(out.blasNodes) + bytesOf(out.blasWideNodes),
                 bytesOf(out.triangles),
                 bytesOf(out.tlasNodes),
                 bytesOf(out.instances),
                 bytesOf(out.geometries),
                 bytesOf(out.indices),
                 bytesOf(out.positions),
                 bytesOf(out.normals),
                 bytesOf(out.uvs),
                 bytesOf(out.tangents),
                 bytesOf(out.colors)};
  stats.seconds = secondsSince(start);
  return out;
}

}  // namespace bounce::rt
