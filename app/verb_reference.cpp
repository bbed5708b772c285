// bounce reference: the ground-truth path tracer (src/reference/path_tracer.h). Renders a scene
// progressively to --spp samples per pixel (or until --time-limit), writes EXR (linear, scene-
// referred) or PNG (sRGB, no tone curve, optionally scaled by --exposure), and prints the samples
// reached, the time and the device.
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <memory>
#include <string>

#include "common_options.h"
#include "core/error.h"
#include "reference/path_tracer.h"
#include "rt/gpu_scene.h"
#include "tools/image_io.h"
#include "verbs.h"

namespace bounce::app {

namespace {

struct ReferenceVerbOptions {
  CommonOptions common;
  // Wide integer types so that negative or huge values reach our own range checks (with a
  // clear message) instead of a conversion error.
  std::optional<int64_t> spp;
  int64_t maxBounces = 16;
  int64_t seed = 1;
  bool lambert = false;
  bool pixelCentre = false;
  double timeLimit = 0.0;
  double exposureStops = 0.0;
  std::string out = "out/reference.exr";
};

constexpr uint32_t kDefaultSpp = 64;
constexpr uint32_t kUnlimitedSpp = 1u << 24;  // --time-limit without --spp

uint32_t checkedRange(int64_t value, int64_t lo, int64_t hi, const char* option) {
  if (value < lo || value > hi) fail("{} {}: expected {}..{}", option, value, lo, hi);
  return uint32_t(value);
}

// "[#########---------------------]  30%  29 spp  3.1 s  ETA 7.2 s" on one line, redrawn in place.
void drawProgress(const ReferenceProgress& p) {
  constexpr int kWidth = 30;
  double fraction = double(p.samplesDone) / double(p.samplesTarget);
  double eta = fraction > 0.0 ? p.seconds * (1.0 - fraction) / fraction : 0.0;
  if (p.timeLimitSeconds > 0.0) {
    fraction = std::max(fraction, std::min(p.seconds / p.timeLimitSeconds, 1.0));
    eta = std::min(eta, std::max(p.timeLimitSeconds - p.seconds, 0.0));
  }
  int filled = int(std::round(fraction * kWidth));
  std::string bar(size_t(filled), '#');
  bar.append(size_t(kWidth - filled), '-');
  std::fprintf(stderr, "\r[%s] %3d%%  %u spp  %.1f s  ETA %.1f s   ", bar.c_str(),
               int(std::round(100.0 * fraction)), p.samplesDone, p.seconds, eta);
  std::fflush(stderr);
}

int runReference(const ReferenceVerbOptions& o) {
  ReferenceOptions options;
  Resolution res = o.common.resolution();
  options.width = res.width;
  options.height = res.height;
  if (o.spp) {
    options.samplesPerPixel = checkedRange(*o.spp, 1, kUnlimitedSpp, "--spp");
  } else {
    options.samplesPerPixel = o.timeLimit > 0.0 ? kUnlimitedSpp : kDefaultSpp;
  }
  options.maxBounces = checkedRange(o.maxBounces, 0, 1024, "--max-bounces");
  options.seed = checkedRange(o.seed, 0, std::numeric_limits<uint32_t>::max(), "--seed");
  options.lambert = o.lambert;
  options.pixelCentre = o.pixelCentre;
  if (!(o.timeLimit >= 0.0) || !std::isfinite(o.timeLimit))
    fail("--time-limit {}: expected seconds >= 0", o.timeLimit);
  options.timeLimitSeconds = o.timeLimit;
  if (!isLdrExtension(o.out) && !isHdrExtension(o.out))
    fail("--out '{}': expected a .exr or .png file", o.out);
  if (!std::isfinite(o.exposureStops) || std::abs(o.exposureStops) > 64.0)
    fail("--exposure {}: expected stops in [-64, 64]", o.exposureStops);

  Scene scene = o.common.loadScene();
  std::unique_ptr<vk::Context> context = o.common.createContext();
  GpuScene gpuScene(*context, scene);
  ReferencePathTracer tracer(*context, gpuScene, scene);
  const bool progress = ::isatty(STDERR_FILENO) != 0;
  if (progress) options.onProgress = drawProgress;
  ReferenceResult result = tracer.render(effectiveCamera(scene), options);
  if (progress) std::fputc('\n', stderr);

  std::filesystem::path outPath(o.out);
  if (outPath.has_parent_path()) std::filesystem::create_directories(outPath.parent_path());
  writeImage(o.out, result.image, float(std::exp2(o.exposureStops)));

  const double msPerSpp = result.gpuMilliseconds > 0.0
                              ? result.gpuMilliseconds / result.samplesPerPixel
                              : 1e3 * result.seconds / result.samplesPerPixel;
  std::printf(
      "%s: reference %ux%u, %u spp, max %u bounces%s, seed %u: %.2f s (%.2f ms/spp) on %s -> %s\n",
      scene.name.c_str(), options.width, options.height, result.samplesPerPixel, options.maxBounces,
      options.lambert ? ", lambert" : "", options.seed, result.seconds, msPerSpp,
      context->info().name.c_str(), o.out.c_str());
  if (result.stoppedByTimeLimit)
    std::printf("stopped by --time-limit %.3g s after %u spp\n", options.timeLimitSeconds,
                result.samplesPerPixel);
  if (result.droppedSamples > 0)
    std::fprintf(stderr, "bounce: warning: %llu NaN/infinite samples were dropped\n",
                 static_cast<unsigned long long>(result.droppedSamples));
  return exitCodeFor(*context);
}

}  // namespace

void addReferenceVerb(CLI::App& app, VerbAction& action) {
  auto options = std::make_shared<ReferenceVerbOptions>();
  CLI::App* cmd =
      app.add_subcommand("reference", "Render ground truth with the progressive GPU path tracer");
  options->common.addSceneOptions(*cmd, "cornell");
  options->common.addResolution(*cmd, "640x360");
  options->common.addDeviceOptions(*cmd);
  cmd->add_option("--spp", options->spp,
                  "Samples per pixel (default 64; with --time-limit alone: until the limit)");
  cmd->add_option("--max-bounces", options->maxBounces,
                  "Scattering events per path (1 = direct lighting only)")
      ->capture_default_str();
  cmd->add_option("--seed", options->seed, "Random seed (same seed, same device: same image)")
      ->capture_default_str();
  cmd->add_flag(
      "--lambert", options->lambert,
      "Every material pure Lambert with its base colour (textures, emission, alpha kept)");
  cmd->add_flag("--pixel-centre", options->pixelCentre,
                "Camera rays through pixel centres only (no anti-aliasing), to compare pixel for "
                "pixel with `bounce render`");
  cmd->add_option("--time-limit", options->timeLimit,
                  "Stop after the batch that passes this many seconds; reports the spp reached");
  cmd->add_option("--out", options->out, "Output image (.exr linear, .png sRGB)")
      ->capture_default_str();
  cmd->add_option("--exposure", options->exposureStops,
                  "PNG only: scale by 2^STOPS before the sRGB encoding (no tone curve)")
      ->capture_default_str();
  cmd->callback([&action, options] { action = [options] { return runReference(*options); }; });
}

}  // namespace bounce::app
