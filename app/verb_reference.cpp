// bounce reference: the ground-truth path tracer (src/reference/path_tracer.h). Renders a scene
// progressively to --spp samples per pixel (or until --time-limit), writes EXR (linear, scene-
// referred) or PNG (sRGB, no tone curve, optionally scaled by --exposure), and prints the samples
// reached, the time and the device. Ctrl-C stops it and writes the image traced so far (exit
// code 130).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <memory>
#include <string>

#include "common_options.h"
#include "core/error.h"
#include "interrupt.h"
#include "progress.h"
#include "reference/path_tracer.h"
#include "rt/gpu_scene.h"
#include "scene/time_of_day.h"
#include "tools/image_io.h"
#include "tools/output_file.h"
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
  std::optional<float> timeOfDay;
  std::string out = "out/reference.exr";
};

constexpr uint32_t kDefaultSpp = 64;
constexpr uint32_t kUnlimitedSpp = 1u << 24;  // --time-limit without --spp

uint32_t checkedRange(int64_t value, int64_t lo, int64_t hi, const char* option) {
  if (value < lo || value > hi) fail("{} {}: expected {}..{}", option, value, lo, hi);
  return uint32_t(value);
}

// "[#########---------------------]  30%  29 spp  3.1 s  ETA 7.2 s" on one line, redrawn in place.
void drawProgress(ProgressLine& line, const ReferenceProgress& p) {
  double fraction = double(p.samplesDone) / double(p.samplesTarget);
  double eta = fraction > 0.0 ? p.seconds * (1.0 - fraction) / fraction : 0.0;
  if (p.timeLimitSeconds > 0.0) {
    fraction = std::max(fraction, std::min(p.seconds / p.timeLimitSeconds, 1.0));
    eta = std::min(eta, std::max(p.timeLimitSeconds - p.seconds, 0.0));
  }
  line.draw(fraction, std::to_string(p.samplesDone) + " spp", p.seconds, eta);
}

ReferenceOptions tracerOptions(const ReferenceVerbOptions& o) {
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
  return options;
}

// Usage errors and the output file, before the scene is loaded or a sample traced.
void checkArguments(const ReferenceVerbOptions& o) {
  o.common.checkArguments();
  requireExtension("--out", o.out, {"png", "exr"});
  if (!std::isfinite(o.exposureStops) || std::abs(o.exposureStops) > 64.0)
    fail("--exposure {}: expected stops in [-64, 64]", o.exposureStops);
  if (o.common.given.has("--exposure") && isHdrExtension(o.out))
    fail(
        "--exposure and --out '{}' cannot be used together: an EXR holds linear radiance "
        "unscaled; --exposure scales PNG output only",
        o.out);
  o.common.given.refuseTogether("--time-of-day", "--sun", "the time of day sets the sun");
  if (o.timeOfDay && !(*o.timeOfDay >= 0.0f && *o.timeOfDay <= 24.0f))
    fail("--time-of-day {}: expected hours in [0, 24]", *o.timeOfDay);
  requireWritableFile("--out", o.out);
}

int runReference(const ReferenceVerbOptions& o) {
  ReferenceOptions options = tracerOptions(o);
  checkArguments(o);

  Scene scene = o.common.loadScene();
  // The sun and sky `bounce render --time-of-day` gives the same scene (its frame 0).
  if (o.timeOfDay) {
    const Sun daySun = scene.sun;
    const Sky daySky = scene.sky;
    applyTimeOfDay(*o.timeOfDay, daySun, daySky, scene.sun, scene.sky);
  }
  std::unique_ptr<vk::Context> context = o.common.createContext();
  GpuScene gpuScene(*context, scene, o.common.gpuSceneOptions());
  ReferencePathTracer tracer(*context, gpuScene, scene);
  ProgressLine progress;
  if (progress.enabled())
    options.onProgress = [&progress](const ReferenceProgress& p) { drawProgress(progress, p); };
  // From here Ctrl-C keeps what was traced (a second one ends the program at once).
  InterruptRequest interrupt;
  options.cancel = &interrupt.flag();
  std::fprintf(stderr, "reference: tracing %ux%u on %s; Ctrl-C stops and writes the image so far\n",
               options.width, options.height, context->info().name.c_str());
  ReferenceResult result = tracer.render(effectiveCamera(scene), options);
  progress.finish();

  const ImageMetadata metadata = {{"bounce.spp", std::to_string(result.samplesPerPixel)},
                                  {"bounce.interrupted", result.cancelled ? "true" : "false"},
                                  {"bounce.scene", o.common.scene}};
  writeImage(o.out, result.image, float(std::exp2(o.exposureStops)), metadata);

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
  const int exitCode = exitCodeFor(*context);
  if (result.cancelled) {
    std::fprintf(stderr, "bounce: interrupted after %u of %u spp; wrote %s%s\n",
                 result.samplesPerPixel, options.samplesPerPixel, o.out.c_str(),
                 isHdrExtension(o.out) ? " (its bounce.spp attribute says so too)" : "");
    return kInterruptedExit;
  }
  return exitCode;
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
  cmd->add_option("--time-of-day", options->timeOfDay,
                  "Solar time in hours [0, 24], as `bounce render --time-of-day` (below the "
                  "horizon: no sun, a dim constant sky)");
  cmd->add_option("--out", options->out,
                  "Output image (.exr linear, .png sRGB); checked writable before any work")
      ->capture_default_str();
  cmd->add_option("--exposure", options->exposureStops,
                  "PNG only: scale by 2^STOPS before the sRGB encoding (no tone curve)")
      ->capture_default_str();
  cmd->callback([&action, options, cmd] {
    options->common.given.record(*cmd);
    action = [options] { return runReference(*options); };
  });
}

}  // namespace bounce::app
