// Ray queries on the CPU. CpuTracer walks the GPU arrays of a SceneBvh exactly the way the GLSL
// traversal must (the contract at the top of scene_bvh.h): tests and reference tools use it to
// check the BVH and to predict what the GPU returns. The brute-force functions ignore every
// BVH array and test each triangle of each instance of the Scene itself: the ground truth for
// both.
#pragma once
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "rt/scene_bvh.h"
#include "scene/scene.h"
#include "shared/scene_layout.h"

namespace bounce::rt {

struct Ray {
  glm::vec3 origin{0.0f};
  glm::vec3 direction{0.0f, 0.0f, -1.0f};  // need not be normalised; t is in its units
  float tMin = 0.0f;                       // hits count for t in (tMin, tMax)
};

struct TraceHit {
  bool hit = false;
  float t = 0.0f;
  uint32_t instance = gpu::BVH_INVALID;
  uint32_t geometry = gpu::BVH_INVALID;   // global: instance.geometryBase + local geometry
  uint32_t primitive = gpu::BVH_INVALID;  // triangle index within the geometry
  float b1 = 0.0f;                        // barycentric weight of the triangle's second vertex
  float b2 = 0.0f;                        // ... and of its third
  bool frontFacing = false;  // glTF front face (counter-clockwise), mirrored instances flipped
};

// Decides whether a candidate hit on an alpha-tested triangle counts (true = opaque there).
// Called only for triangles flagged GPU_TRIANGLE_ALPHA_TESTED; an empty function accepts all.
using AlphaTest = std::function<bool(uint32_t instance, uint32_t globalGeometry, uint32_t primitive,
                                     float b1, float b2)>;

// The arrays a traversal reads; they must outlive the tracer.
struct TraceArrays {
  std::span<const gpu::GpuBvhNode> tlasNodes;
  std::span<const gpu::GpuBvhNode> blasNodes;  // BvhLayout::Binary
  std::span<const gpu::GpuTriangle> triangles;
  std::span<const gpu::GpuInstance> instances;
  BvhLayout layout = BvhLayout::Binary;
  std::span<const gpu::GpuWideBvhNode> blasWideNodes;  // BvhLayout::Wide
};

class CpuTracer {
 public:
  explicit CpuTracer(const TraceArrays& arrays) : arrays_(arrays) {}
  explicit CpuTracer(const SceneBvh& bvh)
      : arrays_{bvh.tlasNodes, bvh.blasNodes, bvh.triangles,
                bvh.instances, bvh.layout,    bvh.blasWideNodes} {}

  TraceHit closestHit(const Ray& ray, float tMax, const AlphaTest& alphaTest = nullptr) const;
  bool anyHit(const Ray& ray, float tMax, const AlphaTest& alphaTest = nullptr) const;

 private:
  template <bool kAnyHit>
  TraceHit traverse(const Ray& ray, float tMax, const AlphaTest& alphaTest) const;
  // BvhLayout::Wide: the 2-wide TLAS loop, each instance's wide BLAS run to completion.
  template <bool kAnyHit>
  TraceHit traverseWide(const Ray& ray, float tMax, const AlphaTest& alphaTest) const;
  // One instance's wide BLAS; returns true when kAnyHit found a hit (then in `result`).
  template <bool kAnyHit>
  bool traverseWideBlas(uint32_t instanceIndex, const Ray& ray, float& tMax,
                        const AlphaTest& alphaTest, TraceHit& result) const;

  TraceArrays arrays_;
};

// The brute-force reference, independent of the BVH code: every triangle of every instance,
// read from the Scene itself. The only shortcut is a conservative instance-level cull (a ray
// segment that misses an instance's world box, inflated by 1e-3 of its size and tested in
// double precision, cannot hit its triangles), which makes million-triangle scenes affordable
// in tests. Construct once per scene; the Scene must outlive it.
class BruteForceTracer {
 public:
  explicit BruteForceTracer(const Scene& scene);
  TraceHit closestHit(const Ray& ray, float tMax, const AlphaTest& alphaTest = nullptr) const;
  bool anyHit(const Ray& ray, float tMax, const AlphaTest& alphaTest = nullptr) const;

 private:
  struct PreparedInstance {
    gpu::GpuInstance transform;
    Aabb worldBounds;
    bool mirrored;
  };
  template <bool kAnyHit>
  TraceHit trace(const Ray& ray, float tMax, const AlphaTest& alphaTest) const;

  const Scene& scene_;
  std::vector<uint32_t> geometryBase_;
  std::vector<PreparedInstance> instances_;
};

// One-shot versions (prepare the scene on every call). Slow: tests only.
TraceHit closestHitBruteForce(const Scene& scene, const Ray& ray, float tMax,
                              const AlphaTest& alphaTest = nullptr);
bool anyHitBruteForce(const Scene& scene, const Ray& ray, float tMax,
                      const AlphaTest& alphaTest = nullptr);

}  // namespace bounce::rt
