// The ray-tracing benchmark behind `bounce bench-rays`: Mrays/s of primary, sun-shadow and
// diffuse-bounce rays through the software BVH and/or the hardware tracer
// (VK_KHR_ray_tracing_pipeline, src/rt/hardware_tracer.h), timed with GPU timestamps, and, with
// both tracers, how far their hits on the same rays agree.
#pragma once
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "rt/gpu_scene.h"
#include "rt/hardware_tracer.h"
#include "scene/scene.h"
#include "scene/scene_options.h"
#include "shared/bench_rays_io.h"
#include "vk/context.h"

namespace bounce {

enum class RayTracer { Software, Hardware, Both };

struct RayKindResult {
  std::string kind;   // "primary", "shadow", "diffuse"
  uint64_t rays = 0;  // per dispatch
  double medianMilliseconds = 0.0;
  double minMilliseconds = 0.0;
  double mraysPerSecond = 0.0;  // from the median
  double hitFraction = 0.0;     // of the rays traced (shadow: fraction occluded)
};

// Software against hardware on the same rays of one kind (the software tracer's rays of one
// untimed run, frame 0, traced again by the hardware tracer).
struct RayAgreement {
  std::string kind;
  uint64_t rays = 0;              // rays compared (pixels with a ray of this kind)
  double hitMissAgreement = 0.0;  // fraction of rays whose hit/miss answers agree
  // Closest-hit kinds (primary, diffuse): among rays both tracers hit, the fraction with the
  // same hit: the same instance, geometry and primitive (a ray meets a triangle at one point,
  // whatever the rounding of the two t's), or a tie (below).
  // Visibility rays stop at any hit, so shadow rays compare hit/miss only (sameHit unset).
  uint64_t bothHit = 0;
  std::optional<double> sameHit;
  // Of the rays both hit, those with another primitive (or instance, geometry) at a distance
  // within the tolerance: ties such as shared edges or coplanar overlapping triangles, where
  // either answer is right.
  uint64_t tiedOtherPrimitive = 0;
  // Of the same hits, those with the same primitive at a t further apart than the tolerance
  // (rounding at small t), and the largest |t_hw - t_sw| / t_sw of those. The disagreements:
  // another primitive nearer to the origin in the hardware's or in the software's answer.
  uint64_t samePrimitiveOtherT = 0;
  double largestRelativeTGap = 0.0;
  uint64_t hardwareNearer = 0;
  uint64_t softwareNearer = 0;
  // The first kMaxJudged rays whose t's differ beyond the tolerance judged by the brute-force
  // tracer (rt::BruteForceTracer, alpha test included): how many of each tracer's answers it gives
  // (the same primitive, or another within the tolerance of its t), and, per tracer, the largest
  // relative distance of its t from the exact double-precision t of the line with its reported
  // triangle's plane.
  uint64_t judged = 0;
  uint64_t softwareMatchesBruteForce = 0;
  uint64_t hardwareMatchesBruteForce = 0;
  double softwareLargestPlaneTError = 0.0;
  double hardwareLargestPlaneTError = 0.0;
  std::vector<std::string> examples;  // the first few judged rays, one line each
  static constexpr double kRelativeTolerance = 1e-4;
  static constexpr uint64_t kMaxJudged = 256;
};

struct RayBenchResult {
  std::vector<RayKindResult> software;  // empty unless the software tracer ran
  std::vector<RayKindResult> hardware;  // empty unless the hardware tracer ran
  std::vector<RayAgreement> agreement;  // with both tracers
  // Tracer Both on a device without hardware ray tracing: the software results only, and why.
  std::string hardwareSkipped;
  std::optional<HardwareTracerStats> hardwareStats;
  std::string hardwareDescription;  // HardwareTracer::describe()
};

struct RayBenchOptions {
  Resolution resolution{1920, 1080};
  uint32_t iterations = 9;
  // Hardware on a device without hardware ray tracing throws bounce::Error
  // (HardwareTracer::unsupportedMessage); Both then runs the software tracer alone.
  RayTracer tracer = RayTracer::Software;
};

RayBenchResult runRayBench(vk::Context& context, const GpuScene& gpuScene, const Scene& scene,
                           const RayBenchOptions& options);

// The agreement of one kind from the two tracers' recorded hits (shared/bench_rays_io.h
// BenchHit, one per pixel); `closest`: compare primitives and distances too.
RayAgreement compareHits(const std::string& kind, std::span<const gpu::BenchHit> software,
                         std::span<const gpu::BenchHit> hardware, bool closest);

}  // namespace bounce
