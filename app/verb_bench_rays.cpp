// bounce bench-rays: Mrays/s of primary, sun-shadow and diffuse-bounce rays through the
// software BVH, plus BVH build time, triangles/s and memory.
#include <cstdio>
#include <memory>

#include <nlohmann/json.hpp>

#include "common_options.h"
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
};

nlohmann::json reportJson(const Scene& scene, const std::string& source, const vk::Context& context,
                          const GpuSceneStats& s, const Resolution& res,
                          const std::vector<RayKindResult>& kinds) {
  nlohmann::json j;
  j["scene"] = scene.name;
  j["scene_source"] = source;
  j["device"] = context.info().name;
  j["driver"] = context.info().driver;
  j["resolution"] = {res.width, res.height};
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
  for (const RayKindResult& k : kinds)
    j["rays"][k.kind] = {{"rays", k.rays},
                         {"median_ms", k.medianMilliseconds},
                         {"min_ms", k.minMilliseconds},
                         {"mrays_per_second", k.mraysPerSecond},
                         {"hit_fraction", k.hitFraction}};
  return j;
}

int runBenchRays(const BenchRaysOptions& options) {
  options.common.checkArguments();
  if (!options.json.empty()) requireWritableFile("--json", options.json);
  Resolution res = options.common.resolution();
  Scene scene = options.common.loadScene();
  std::unique_ptr<vk::Context> context = options.common.createContext();
  GpuScene gpuScene(*context, scene, options.common.gpuSceneOptions());
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
  std::vector<RayKindResult> kinds = runRayBench(*context, gpuScene, scene, bench);
  std::printf("%-8s %12s %10s %10s %12s %8s\n", "rays", "count", "median ms", "min ms", "Mrays/s",
              "hit %");
  for (const RayKindResult& k : kinds)
    std::printf("%-8s %12llu %10.3f %10.3f %12.3f %8.1f\n", k.kind.c_str(),
                (unsigned long long)k.rays, k.medianMilliseconds, k.minMilliseconds,
                k.mraysPerSecond, 100.0 * k.hitFraction);
  if (!options.json.empty()) {
    const nlohmann::json report = reportJson(scene, options.common.scene, *context, s, res, kinds);
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
  cmd->callback([&action, options, cmd] {
    options->common.given.record(*cmd);
    action = [options] { return runBenchRays(*options); };
  });
}

}  // namespace bounce::app
