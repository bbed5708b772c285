// bounce bench-rays: Mrays/s of primary, sun-shadow and diffuse-bounce rays through the
// software BVH and/or the hardware tracer (--tracer), plus BVH build time, triangles/s and
// memory, and with both tracers how far their hits agree.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <memory>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "common_options.h"
#include "core/error.h"
#include "passes/ray_bench.h"
#include "rt/gpu_scene.h"
#include "tools/output_file.h"
#include "verbs.h"

namespace bounce::app {

namespace {

struct BenchRaysOptions {
  CommonOptions common;
  uint32_t iterations = 9;
  std::string json;
  std::string tracer = "software";
  bool verbose = false;
  bool buildOnly = false;
  uint32_t buildThreads = 0;
};

nlohmann::json kindsJson(const std::vector<RayKindResult>& kinds) {
  nlohmann::json j = nlohmann::json::object();
  for (const RayKindResult& k : kinds)
    j[k.kind] = {{"rays", k.rays},
                 {"median_ms", k.medianMilliseconds},
                 {"min_ms", k.minMilliseconds},
                 {"mrays_per_second", k.mraysPerSecond},
                 {"hit_fraction", k.hitFraction}};
  return j;
}

nlohmann::json reportJson(const Scene& scene, const std::string& source, const std::string& tracer,
                          const vk::Context& context, const GpuSceneStats& s, const Resolution& res,
                          const RayBenchResult& result) {
  nlohmann::json j;
  j["scene"] = scene.name;
  j["scene_source"] = source;
  j["device"] = context.info().name;
  j["driver"] = context.info().driver;
  j["resolution"] = {res.width, res.height};
  j["tracer"] = tracer;
  j["triangles"] = s.triangles;
  j["unique_triangles"] = s.uniqueTriangles;
  j["bvh_build_seconds"] = s.bvhBuildSeconds;
  j["bvh_build_mtriangles_per_second"] =
      s.bvhBuildSeconds > 0 ? double(s.uniqueTriangles) / s.bvhBuildSeconds * 1e-6 : 0.0;
  j["bvh_layout"] = rt::bvhLayoutName(s.bvhLayout);
  j["bvh_node_bytes"] = s.bvhNodeBytes;
  j["bvh_bytes"] = s.bvhBytes;
  j["texture_bytes"] = s.textureBytes;
  j["gpu_bytes"] = s.totalBytes;
  if (!result.software.empty()) j["rays"] = kindsJson(result.software);
  if (!result.hardware.empty()) {
    const HardwareTracerStats& h = *result.hardwareStats;
    j["hardware"] = {{"rays", kindsJson(result.hardware)},
                     {"blas_count", h.blasCount},
                     {"geometries", h.geometryCount},
                     {"instances", h.instanceCount},
                     {"triangles", h.triangles},
                     {"blas_bytes", h.blasBytes},
                     {"tlas_bytes", h.tlasBytes},
                     {"scratch_bytes", h.scratchBytes},
                     {"build_seconds", h.buildSeconds},
                     {"blas_build_gpu_ms", h.blasGpuMilliseconds},
                     {"tlas_build_gpu_ms", h.tlasGpuMilliseconds}};
  }
  if (!result.hardwareSkipped.empty()) j["hardware_skipped"] = result.hardwareSkipped;
  for (const RayAgreement& a : result.agreement) {
    j["agreement"][a.kind] = {{"rays", a.rays},
                              {"hit_miss_agreement", a.hitMissAgreement},
                              {"both_hit", a.bothHit},
                              {"tied_other_primitive", a.tiedOtherPrimitive},
                              {"same_primitive_other_t", a.samePrimitiveOtherT},
                              {"largest_relative_t_gap", a.largestRelativeTGap},
                              {"hardware_nearer", a.hardwareNearer},
                              {"software_nearer", a.softwareNearer},
                              {"relative_t_tolerance", RayAgreement::kRelativeTolerance},
                              {"judged", a.judged},
                              {"software_matches_brute_force", a.softwareMatchesBruteForce},
                              {"hardware_matches_brute_force", a.hardwareMatchesBruteForce},
                              {"software_largest_plane_t_error", a.softwareLargestPlaneTError},
                              {"hardware_largest_plane_t_error", a.hardwareLargestPlaneTError},
                              {"examples", a.examples}};
    if (a.sameHit) j["agreement"][a.kind]["same_hit"] = *a.sameHit;
  }
  return j;
}

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

// --build-only: the CPU BVH build that GpuScene's constructor runs (buildGpuSceneBvh, the time
// bench-rays reports as "BVH ... build"), `iterations` times, without a device. The machine
// may be shared, so the median is the figure to quote; the SAH costs show that a faster build
// did not buy its speed with a worse tree.
int runBuildOnly(const BenchRaysOptions& options) {
  Scene scene = options.common.loadScene();
  GpuSceneOptions sceneOptions = options.common.gpuSceneOptions();
  sceneOptions.bvhBuildThreads = options.buildThreads;
  const uint64_t unique = scene.uniqueTriangleCount();
  std::vector<double> seconds;
  rt::SceneBvhStats stats;
  for (uint32_t i = 0; i < options.iterations; ++i) {
    rt::TlasRefitState refit;
    const auto start = std::chrono::steady_clock::now();
    rt::SceneBvh bvh = buildGpuSceneBvh(scene, sceneOptions, refit);
    seconds.push_back(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    stats = bvh.stats;
  }
  const double med = median(seconds);
  const double best = *std::min_element(seconds.begin(), seconds.end());
  std::printf("scene %s: %llu unique triangles, BVH %s, %u build thread(s)\n", scene.name.c_str(),
              (unsigned long long)unique, rt::bvhLayoutName(sceneOptions.bvhLayout),
              options.buildThreads ? options.buildThreads
                                   : std::max(1u, std::thread::hardware_concurrency()));
  std::printf(
      "BVH build over %u runs: median %.1f ms (%.2f M triangles/s), best %.1f ms (%.2f M "
      "triangles/s); BLAS SAH cost %.3f, TLAS SAH cost %.3f\n",
      options.iterations, med * 1e3, double(unique) / med * 1e-6, best * 1e3,
      double(unique) / best * 1e-6, stats.blasSahCost, stats.tlasSahCost);
  if (!options.json.empty()) {
    nlohmann::json j;
    j["scene"] = scene.name;
    j["scene_source"] = options.common.scene;
    j["unique_triangles"] = unique;
    j["bvh_layout"] = rt::bvhLayoutName(sceneOptions.bvhLayout);
    j["build_threads"] = options.buildThreads;
    j["bvh_build_seconds"] = seconds;
    j["bvh_build_median_seconds"] = med;
    j["bvh_build_mtriangles_per_second"] = double(unique) / med * 1e-6;
    j["blas_sah_cost"] = stats.blasSahCost;
    j["tlas_sah_cost"] = stats.tlasSahCost;
    writeTextFile(options.json,
                  j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n");
  }
  return 0;
}

int runBenchRays(const BenchRaysOptions& options) {
  options.common.checkArguments();
  if (options.buildOnly) {
    if (options.tracer != "software")
      fail("--build-only and --tracer {} cannot be used together: --build-only traces no rays",
           options.tracer);
    if (!options.json.empty()) requireWritableFile("--json", options.json);
    return runBuildOnly(options);
  }
  requireOneOf("--tracer", options.tracer, {"software", "hardware", "both"});
  const RayTracer tracer = options.tracer == "hardware" ? RayTracer::Hardware
                           : options.tracer == "both"   ? RayTracer::Both
                                                        : RayTracer::Software;
  if (!options.json.empty()) requireWritableFile("--json", options.json);
  Resolution res = options.common.resolution();
  Scene scene = options.common.loadScene();
  std::unique_ptr<vk::Context> context = options.common.createContext();
  // Before the BVH build, which takes a while on large scenes.
  if (tracer == RayTracer::Hardware && !HardwareTracer::supported(*context))
    fail("{}", HardwareTracer::unsupportedMessage(*context));
  GpuSceneOptions sceneOptions = options.common.gpuSceneOptions();
  sceneOptions.bvhBuildThreads = options.buildThreads;
  GpuScene gpuScene(*context, scene, sceneOptions);
  const GpuSceneStats& s = gpuScene.stats();
  std::printf("scene %s: %llu triangles (%llu unique), device %s\n", scene.name.c_str(),
              (unsigned long long)s.triangles, (unsigned long long)s.uniqueTriangles,
              context->info().name.c_str());
  std::printf(
      "BVH %s: build %.3f s (%.2f M triangles/s), nodes %.1f MiB, nodes + triangles %.1f MiB, "
      "textures %.1f MiB, GPU total %.1f MiB\n",
      rt::bvhLayoutName(s.bvhLayout), s.bvhBuildSeconds,
      s.bvhBuildSeconds > 0 ? double(s.uniqueTriangles) / s.bvhBuildSeconds * 1e-6 : 0.0,
      double(s.bvhNodeBytes) / (1 << 20), double(s.bvhBytes) / (1 << 20),
      double(s.textureBytes) / (1 << 20), double(s.totalBytes) / (1 << 20));
  RayBenchOptions bench;
  bench.resolution = res;
  bench.iterations = options.iterations;
  bench.tracer = tracer;
  const RayBenchResult result = runRayBench(*context, gpuScene, scene, bench);
  if (!result.hardwareSkipped.empty())
    std::printf("hardware tracer skipped: %s\n", result.hardwareSkipped.c_str());
  if (result.hardwareStats) {
    const HardwareTracerStats& h = *result.hardwareStats;
    std::printf(
        "hardware acceleration structures: %u BLAS %.1f MiB, TLAS %u instances %.2f MiB, build "
        "%.3f s (GPU %.3f ms)\n",
        h.blasCount, double(h.blasBytes) / (1 << 20), h.instanceCount,
        double(h.tlasBytes) / (1 << 20), h.buildSeconds,
        h.blasGpuMilliseconds + h.tlasGpuMilliseconds);
    if (options.verbose) std::printf("%s\n", result.hardwareDescription.c_str());
  }
  std::printf("%-9s %-8s %12s %10s %10s %12s %8s\n", "tracer", "rays", "count", "median ms",
              "min ms", "Mrays/s", "hit %");
  auto printKinds = [](const char* name, const std::vector<RayKindResult>& kinds) {
    for (const RayKindResult& k : kinds)
      std::printf("%-9s %-8s %12llu %10.3f %10.3f %12.3f %8.1f\n", name, k.kind.c_str(),
                  (unsigned long long)k.rays, k.medianMilliseconds, k.minMilliseconds,
                  k.mraysPerSecond, 100.0 * k.hitFraction);
  };
  printKinds("software", result.software);
  printKinds("hardware", result.hardware);
  if (!result.agreement.empty()) {
    std::printf("%-8s %12s %12s %12s %14s %8s %10s\n", "agree", "rays", "hit/miss %", "both hit",
                "same hit %", "ties", "sw/hw");
    for (size_t k = 0; k < result.agreement.size(); ++k) {
      const RayAgreement& a = result.agreement[k];
      const double ratio =
          result.hardware[k].mraysPerSecond > 0
              ? result.software[k].mraysPerSecond / result.hardware[k].mraysPerSecond
              : 0.0;
      std::printf("%-8s %12llu %12.4f %12llu %14s %8llu %10.3f\n", a.kind.c_str(),
                  (unsigned long long)a.rays, 100.0 * a.hitMissAgreement,
                  (unsigned long long)a.bothHit,
                  a.sameHit ? fmt::format("{:.4f}", 100.0 * *a.sameHit).c_str() : "-",
                  (unsigned long long)a.tiedOtherPrimitive, ratio);
    }
    // Where closest hits differ beyond a tie: the same primitive at another t, or another
    // primitive nearer in one tracer's answer.
    for (const RayAgreement& a : result.agreement)
      if (a.samePrimitiveOtherT + a.hardwareNearer + a.softwareNearer > 0)
        std::printf(
            "%s: %llu same primitive at another t (largest |dt|/t %.2g), another primitive "
            "nearer: %llu hardware, %llu software\n",
            a.kind.c_str(), (unsigned long long)a.samePrimitiveOtherT, a.largestRelativeTGap,
            (unsigned long long)a.hardwareNearer, (unsigned long long)a.softwareNearer);
    // The brute-force tracer's verdict on the first disagreements.
    for (const RayAgreement& a : result.agreement) {
      if (a.judged == 0) continue;
      std::printf(
          "%s: of %llu judged by brute force, software right %llu, hardware right %llu; largest "
          "|t - plane t| / t: software %.2g, hardware %.2g\n",
          a.kind.c_str(), (unsigned long long)a.judged,
          (unsigned long long)a.softwareMatchesBruteForce,
          (unsigned long long)a.hardwareMatchesBruteForce, a.softwareLargestPlaneTError,
          a.hardwareLargestPlaneTError);
      for (const std::string& e : a.examples) std::printf("  %s\n", e.c_str());
    }
  }
  if (!options.json.empty()) {
    const nlohmann::json report =
        reportJson(scene, options.common.scene, options.tracer, *context, s, res, result);
    // Paths are bytes, not always UTF-8: replace an invalid sequence rather than throw.
    writeTextFile(options.json,
                  report.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n");
  }
  return exitCodeFor(*context);
}

}  // namespace

void addBenchRaysVerb(CLI::App& app, VerbAction& action) {
  auto options = std::make_shared<BenchRaysOptions>();
  CLI::App* cmd =
      app.add_subcommand("bench-rays", "Ray-tracing throughput (Mrays/s) and BVH build");
  options->common.addSceneOptions(*cmd, "city");
  options->common.addResolution(*cmd, "1920x1080");
  options->common.addDeviceOptions(*cmd);
  cmd->add_option("--iterations", options->iterations, "Timed repetitions (median reported)")
      ->capture_default_str()
      ->check(CLI::Range(1, 1000));
  cmd->add_option("--json", options->json, "Write the results as JSON");
  cmd->add_option("--tracer", options->tracer,
                  "software (the BVH in shaders/rt/), hardware (VK_KHR_ray_tracing_pipeline) or "
                  "both (times both, compares their hits on the same rays)")
      ->capture_default_str();
  cmd->add_flag("--build-only", options->buildOnly,
                "Only time the CPU BVH build, --iterations times (median reported), with no "
                "device and no rays; docs/benchmarks.md, \"BVH build\"");
  cmd->add_option("--build-threads", options->buildThreads,
                  "Threads of the BVH build; 0 = every core")
      ->capture_default_str()
      ->check(CLI::Range(0, 1024));
  cmd->add_flag("-v,--verbose", options->verbose,
                "Print the hardware tracer's device limits and acceleration-structure details");
  cmd->callback([&action, options, cmd] {
    options->common.given.record(*cmd);
    action = [options] { return runBenchRays(*options); };
  });
}

}  // namespace bounce::app
