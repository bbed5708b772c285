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
  // same instance, geometry and primitive and |t_hw - t_sw| <= kRelativeTolerance * t_sw.
  // Visibility rays stop at any hit, so shadow rays compare hit/miss only (sameHit unset).
  uint64_t bothHit = 0;
  std::optional<double> sameHit;
  // Of the rays both hit, those with another primitive (or instance, geometry) at a distance
  // within the tolerance: ties such as shared edges or coplanar overlapping triangles, where
  // either answer is right.
  uint64_t tiedOtherPrimitive = 0;
  // The other disagreements among rays both hit: the same primitive at a t further apart than
  // the tolerance (and the largest |t_hw - t_sw| / t_sw of those), and another primitive nearer
  // to the origin in the hardware's or in the software's answer.
  uint64_t samePrimitiveOtherT = 0;
  double largestRelativeTGap = 0.0;
  uint64_t hardwareNearer = 0;
  uint64_t softwareNearer = 0;
  static constexpr double kRelativeTolerance = 1e-4;
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
