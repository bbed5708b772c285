// bounce render: renders a scene headless with the real-time hybrid frame (vbuffer, gbuffer,
// shadows, sky, composite, tonemap; DESIGN.md §4) for --frames frames and writes the final
// frame, or every frame, as images; --view shows any pass's debug view instead, and the
// ray-cast views primary-albedo|normal|depth|instance|geometry remain for checking a scene.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <set>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "common_options.h"
#include "core/error.h"
#include "frame/animation_player.h"
#include "frame/hybrid_frame.h"
#include "frame/presets.h"
#include "passes/primary_view.h"
#include "progress.h"
#include "rt/gpu_scene.h"
#include "scene/animation.h"
#include "suggest.h"
#include "tools/image_io.h"
#include "tools/output_file.h"
#include "verbs.h"

namespace bounce::app {

namespace {

constexpr const char* kDefaultResolution = "640x360";

struct RenderOptions {
  CommonOptions common;
  std::string view = "tonemap";
  bool listViews = false;
  std::string out = "out/render.png";
  // Wide integer types so that negative or huge values reach our own range checks (with a
  // clear message) instead of a conversion error; std::nullopt: not given, the preset's value.
  int64_t frames = 8;
  std::string gi = "evolve";  // seed 000's full diffuse GI
  std::string di = "restir";  // ReSTIR DI (DiSettings)
  bool diUnbiased = false;
  int64_t diBrdfCandidates = 1;
  // auto|on|off; empty: the settings' (auto; on with --di-unbiased)
  std::string diCandidateVisibility;
  std::string diDenoiser;  // svgf|reblur|none; empty: the settings' (none)
  std::string vbuffer = "raster";
  std::optional<int64_t> giDivisor;
  std::string restirSecondVertex;
  bool restirUnbiased = false;
  std::optional<int64_t> restirValidationPeriod;
  std::optional<int64_t> restirMaxSampleAge;
  std::optional<int64_t> giDenoiseHistory;
  std::optional<float> restirHistoryBrightening;
  bool noGiDenoise = false;
  std::string denoiser;  // evolve|svgf|reblur|hybrid|none; empty: the settings' (evolve)
  std::optional<int64_t> materialTextureSide;
  bool noOccluderVisibility = false;
  std::string preset;
  std::string timings;
  std::optional<float> exposureStops;  // not given: the settings' exposure (automatic or fixed)
  std::optional<float> skyAmbient;
  std::optional<int64_t> shadowDivisor;
  std::optional<int64_t> reflectionDivisor;  // not given: the preset's
  std::string reflectionReuse;               // on|off; empty: the preset's
  std::string reflectionDenoise;             // "on", "off"; empty: the settings' (on)
  bool lambert = false;
  bool noTaa = false;
  // Motion and time.
  bool animate = false;
  std::string cameraPath;
  float fps = 30.0f;
  std::optional<float> timeOfDay;
  float dayCycle = 0.0f;
};

constexpr int64_t kMaxFrames = 1000000;

// The options that only ReSTIR GI (--gi evolve) reads.
const std::vector<std::string>& restirOptions() {
  static const std::vector<std::string> names = {"--gi-divisor",
                                                 "--restir-second-vertex",
                                                 "--restir-unbiased",
                                                 "--restir-max-sample-age",
                                                 "--restir-validation-period",
                                                 "--restir-history-brightening",
                                                 "--no-gi-denoise",
                                                 "--gi-denoise-history",
                                                 "--denoiser",
                                                 "--no-occluder-visibility"};
  return names;
}

// What the ray-cast views (primary-*) read: one camera ray per pixel, no frame.
const std::set<std::string>& primaryViewOptions() {
  static const std::set<std::string> names = {"--scene",  "--camera",   "--sun",  "--sky", "--res",
                                              "--device", "--validate", "--view", "--out"};
  return names;
}

// --out: an image file gets the last frame; a directory, written with a trailing '/', gets
// every frame as frame_NNNN.png.
bool outIsDirectory(const std::string& out) {
  return !out.empty() && out.back() == '/';
}

std::string frameImagePath(const std::string& directory, uint32_t frame) {
  return (std::filesystem::path(directory) / fmt::format("frame_{:04}.png", frame)).string();
}

// Options that cannot be honoured together are refused, never resolved in silence.
void refuseConflicts(const RenderOptions& o) {
  const GivenOptions& given = o.common.given;
  given.refuseTogether("--camera", "--camera-path",
                       "the camera path sets the camera of every frame");
  given.refuseTogether("--time-of-day", "--sun", "the time of day sets the sun");
  given.refuseTogether("--day-cycle", "--sun", "the day cycle moves the sun");
  given.refuseTogether("--restir-unbiased", "--restir-second-vertex",
                       "the unbiased configuration continues the path at the 2nd vertex");
  given.refuseTogether("--list-views", "--out", "--list-views prints names and renders nothing");
  given.refuseTogether("--list-views", "--timings",
                       "--list-views prints names and renders nothing");
  if (o.gi != "evolve")
    for (const std::string& option : restirOptions())
      if (given.has(option))
        fail(
            "--gi {} and {} cannot be used together: {} sets ReSTIR GI, which only --gi evolve "
            "runs",
            o.gi, option, option);
  if (o.reflectionDivisor == 0 && o.reflectionDenoise == "on")
    fail(
        "--reflection-divisor 0 and --reflection-denoise on cannot be used together: without "
        "reflection rays there is nothing to denoise");
  if (o.gi == "none" && given.has("--gi-texture-side"))
    fail(
        "--gi none and --gi-texture-side cannot be used together: without GI no ray reads "
        "textures at a coarse mip");
  if (primaryViewFromName(o.view))
    for (const std::string& option : given.names)
      if (!primaryViewOptions().count(option))
        fail(
            "--view {} and {} cannot be used together: the ray-cast views draw the scene's "
            "surfaces with one camera ray per pixel, without the real-time frame",
            o.view, option);
}

// Every output path checked before any scene is loaded or frame rendered.
void checkOutputs(const RenderOptions& o) {
  if (o.listViews) return;
  if (outIsDirectory(o.out)) {
    if (primaryViewFromName(o.view))
      fail("--out '{}': a ray-cast view is one image; give a .png or .exr file name", o.out);
    requireWritableDirectory("--out", o.out);
  } else {
    if (std::filesystem::is_directory(o.out))
      fail("--out '{}': is a directory; give an image file name, or '{}/' for every frame", o.out,
           o.out);
    requireExtension("--out", o.out, {"png", "exr"});
    requireWritableFile("--out", o.out);
  }
  if (!o.timings.empty()) requireWritableFile("--timings", o.timings);
}

// Usage errors first, then the outputs: all before any work.
void checkArguments(const RenderOptions& o) {
  o.common.checkArguments();
  requireOneOf("--gi", o.gi, splitNames(giModeNames()));
  requireOneOf("--di", o.di, splitNames(diModeNames()));
  if (o.diUnbiased && o.di != "restir")
    fail(
        "--di {} and --di-unbiased cannot be used together: the bias correction is in spatial "
        "reuse, which only --di restir runs",
        o.di);
  if (!o.diCandidateVisibility.empty()) {
    requireOneOf("--di-candidate-visibility", o.diCandidateVisibility, {"auto", "on", "off"});
    if (o.diUnbiased && o.diCandidateVisibility != "on")
      fail(
          "--di-unbiased and --di-candidate-visibility {} cannot be used together: the "
          "ray-traced bias correction needs the candidates' shadow ray (on)",
          o.diCandidateVisibility);
  }
  if (!o.diDenoiser.empty()) {
    requireOneOf("--di-denoiser", o.diDenoiser, splitNames(diDenoiserNames()));
    if (o.di != "restir" && o.diDenoiser != "none")
      fail("--di-denoiser {} needs --di restir (it filters ReSTIR DI's signal)", o.diDenoiser);
  }
  requireOneOf("--vbuffer", o.vbuffer, {"raster", "trace"});
  if (!o.reflectionReuse.empty())
    requireOneOf("--reflection-reuse", o.reflectionReuse, {"on", "off"});
  if (!o.preset.empty()) requireOneOf("--preset", o.preset, splitNames(presetNames()));
  if (!o.restirSecondVertex.empty())
    requireOneOf("--restir-second-vertex", o.restirSecondVertex, {"nee", "path", "cache"});
  if (!o.reflectionDenoise.empty())
    requireOneOf("--reflection-denoise", o.reflectionDenoise, {"on", "off"});
  if (o.frames < 1 || o.frames > kMaxFrames)
    fail("--frames {}: expected 1 to {} frames", o.frames, kMaxFrames);
  if (!(o.fps > 0.0f) || !std::isfinite(o.fps)) fail("--fps {}: must be positive", o.fps);
  if (o.timeOfDay && !(*o.timeOfDay >= 0.0f && *o.timeOfDay <= 24.0f))
    fail("--time-of-day {}: expected hours in [0, 24]", *o.timeOfDay);
  if (!(o.dayCycle >= 0.0f) || !std::isfinite(o.dayCycle))
    fail("--day-cycle {}: must be >= 0 seconds", o.dayCycle);
  refuseConflicts(o);
  checkOutputs(o);
}

int renderPrimaryView(const RenderOptions& options, PrimaryViewKind view) {
  Resolution res = options.common.res.empty() ? parseResolution(kDefaultResolution)
                                              : options.common.resolution();
  Scene scene = options.common.loadScene();
  std::unique_ptr<vk::Context> context = options.common.createContext();
  GpuScene gpuScene(*context, scene, options.common.gpuSceneOptions());
  PrimaryViewPass pass(*context, gpuScene);
  vk::GpuTimer timer(*context);
  ImageRGBA32F image = pass.render(effectiveCamera(scene), res.width, res.height, view, &timer);
  writeImage(options.out, image);
  double ms = timer.available() ? timer.read().at(0).milliseconds : 0.0;
  std::printf("%s: %s %ux%u on %s: primary-view %.3f ms -> %s\n", scene.name.c_str(),
              options.view.c_str(), res.width, res.height, context->info().name.c_str(), ms,
              options.out.c_str());
  return exitCodeFor(*context);
}

RestirGiSecondVertex secondVertexFromName(const std::string& name) {
  if (name == "nee") return RestirGiSecondVertex::Nee;
  if (name == "path") return RestirGiSecondVertex::Path;
  return RestirGiSecondVertex::Cache;
}

// A whole number option as a settings field: negative or huge values refused, not wrapped.
uint32_t wholeNumber(const char* option, int64_t value) {
  if (value < 0 || value > int64_t(std::numeric_limits<uint32_t>::max()))
    fail("{} {}: expected a whole number >= 0", option, value);
  return uint32_t(value);
}

// Applies one option to the settings and checks the result with the library's validate(), so
// that a value out of range is refused naming the option (the library's message names the
// field) while each range stays defined once, in the library. The settings were valid before,
// so whatever validate() finds now is this option's doing.
template <typename Value, typename Apply>
void applyOption(HybridSettings& settings, const char* option, const Value& value, Apply apply) {
  apply(settings);
  try {
    validate(settings);
  } catch (const Error& e) {
    fail("{} {}: {}", option, value, e.what());
  }
}

// The --restir-* and --gi-* overrides, after the preset (RestirGiSettings documents each).
void applyRestirOptions(const RenderOptions& o, HybridSettings& settings) {
  RestirGiSettings& gi = settings.restirGi;
  if (o.restirUnbiased) gi = RestirGiSettings::unbiased();
  if (o.giDivisor)
    applyOption(settings, "--gi-divisor", *o.giDivisor, [&](HybridSettings& s) {
      s.restirGi.divisor = wholeNumber("--gi-divisor", *o.giDivisor);
    });
  if (!o.restirSecondVertex.empty()) gi.secondVertex = secondVertexFromName(o.restirSecondVertex);
  if (o.restirValidationPeriod)
    gi.validationPeriod = wholeNumber("--restir-validation-period", *o.restirValidationPeriod);
  if (o.restirMaxSampleAge)
    applyOption(settings, "--restir-max-sample-age", *o.restirMaxSampleAge, [&](HybridSettings& s) {
      s.restirGi.maxSampleAge = wholeNumber("--restir-max-sample-age", *o.restirMaxSampleAge);
    });
  if (o.restirHistoryBrightening)
    applyOption(
        settings, "--restir-history-brightening", *o.restirHistoryBrightening,
        [&](HybridSettings& s) { s.restirGi.historyBrightening = *o.restirHistoryBrightening; });
  if (o.giDenoiseHistory)
    applyOption(settings, "--gi-denoise-history", *o.giDenoiseHistory, [&](HybridSettings& s) {
      s.restirGi.denoiseMaxHistory =
          float(wholeNumber("--gi-denoise-history", *o.giDenoiseHistory));
    });
  if (o.noGiDenoise) gi.temporalDenoise = gi.spatialDenoise = false;
  if (o.denoiser == "svgf") gi.denoiser = GiDenoiser::Svgf;
  if (o.denoiser == "none") gi.denoiser = GiDenoiser::None;
  if (o.denoiser == "evolve") gi.denoiser = GiDenoiser::Evolve;
  if (o.denoiser == "reblur") gi.denoiser = GiDenoiser::Reblur;
  if (o.denoiser == "hybrid") gi.denoiser = GiDenoiser::Hybrid;
  if (o.noOccluderVisibility) gi.occluderVisibility = false;
}

// Preset first, then --res, then the rest of the options, each checked as it is applied.
HybridSettings settingsFrom(const RenderOptions& o) {
  HybridSettings settings;
  if (!o.preset.empty()) {
    settings = presetSettings(*presetFromName(o.preset));
  } else {
    Resolution res = parseResolution(kDefaultResolution);
    settings.width = res.width;
    settings.height = res.height;
  }
  if (!o.common.res.empty())
    applyOption(settings, "--res", o.common.res, [&](HybridSettings& s) {
      Resolution res = o.common.resolution();
      s.width = res.width;
      s.height = res.height;
    });
  settings.gi = *giModeFromName(o.gi);
  settings.vbuffer = *vbufferModeFromName(o.vbuffer);
  settings.di.mode = *diModeFromName(o.di);
  if (o.diUnbiased) {  // DiSettings::unbiasedConfiguration() on the preset's settings
    settings.di.unbiased = true;
    settings.di.candidateVisibility = DiCandidateVisibility::On;
  }
  if (!o.diCandidateVisibility.empty())
    settings.di.candidateVisibility = *diCandidateVisibilityFromName(o.diCandidateVisibility);
  settings.di.brdfCandidates = uint32_t(o.diBrdfCandidates);
  if (!o.diDenoiser.empty()) settings.di.denoiser = *diDenoiserFromName(o.diDenoiser);
  validate(settings);  // the preset's values, for the chosen GI
  applyRestirOptions(o, settings);
  if (o.materialTextureSide)
    applyOption(settings, "--gi-texture-side", *o.materialTextureSide, [&](HybridSettings& s) {
      // One flag for the two ray sets that read materials at x2: ReSTIR GI's and the cache's.
      s.restirGi.materialTextureSide = s.cache.materialTextureSide =
          wholeNumber("--gi-texture-side", *o.materialTextureSide);
    });
  if (o.exposureStops)
    applyOption(settings, "--exposure", *o.exposureStops, [&](HybridSettings& s) {
      s.autoExposure = false;
      s.exposureStops = *o.exposureStops;
    });
  if (o.skyAmbient)
    applyOption(settings, "--sky-ambient", *o.skyAmbient,
                [&](HybridSettings& s) { s.skyAmbientStrength = *o.skyAmbient; });
  if (o.shadowDivisor)
    applyOption(settings, "--shadow-divisor", *o.shadowDivisor, [&](HybridSettings& s) {
      s.shadows.divisor = wholeNumber("--shadow-divisor", *o.shadowDivisor);
    });
  if (o.reflectionDivisor)
    applyOption(settings, "--reflection-divisor", *o.reflectionDivisor, [&](HybridSettings& s) {
      s.reflections.divisor = wholeNumber("--reflection-divisor", *o.reflectionDivisor);
    });
  if (!o.reflectionReuse.empty()) settings.reflections.reuse = o.reflectionReuse == "on";
  if (!o.reflectionDenoise.empty())
    settings.reflectionDenoise.enabled = o.reflectionDenoise == "on";
  settings.lambert = o.lambert;
  settings.taa.enabled = !o.noTaa;  // on by default here (the library's default is off)
  return settings;
}

struct TimingRow {
  uint32_t frame;
  vk::PassTiming pass;
};

struct StatisticRow {
  uint32_t frame;
  GiStatistic statistic;
};

// Median GPU milliseconds of each pass over the frames (in the passes' recording order), and
// of their sum per frame: robust to the first frames' warm-up and to the odd slow frame.
std::vector<std::pair<std::string, double>> medianPassTimes(const std::vector<TimingRow>& rows,
                                                            uint32_t frames) {
  std::vector<std::string> order;
  std::map<std::string, std::vector<double>> perPass;
  std::vector<double> total(frames, 0.0);
  for (const TimingRow& row : rows) {
    if (!perPass.count(row.pass.name)) order.push_back(row.pass.name);
    perPass[row.pass.name].push_back(row.pass.milliseconds);
    if (row.pass.name.rfind("debug-view:", 0) != 0) total[row.frame] += row.pass.milliseconds;
  }
  auto median = [](std::vector<double> v) {
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    return v.empty() ? 0.0 : v[v.size() / 2];
  };
  std::vector<std::pair<std::string, double>> result;
  for (const std::string& name : order) result.emplace_back(name, median(perPass[name]));
  result.emplace_back("frame (without debug views)", median(total));
  return result;
}

// What a run measured, for --timings.
struct RenderRecord {
  std::vector<TimingRow> timings;
  std::vector<StatisticRow> statistics;
  std::vector<double> frameWallSeconds;
};

void writeTimingsJson(const RenderOptions& o, const RenderRecord& record, const Scene& scene,
                      const HybridSettings& settings, const vk::Context& context,
                      uint32_t diPipelines) {
  nlohmann::json j;
  j["scene"] = scene.name;
  j["scene_source"] = o.common.scene;
  j["device"] = context.info().name;
  j["device_type"] = context.info().type;
  // On a CPU device the timestamps measure the emulation of a GPU, not a GPU.
  j["gpu_times_meaningful"] = !isCpuDevice(context);
  j["width"] = settings.width;
  j["height"] = settings.height;
  // Compute pipelines ReSTIR DI compiled (seed 002's budget: ReSTIR + denoise at most 15).
  j["di_pipelines"] = diPipelines;
  j["timings"] = nlohmann::json::array();
  for (const TimingRow& row : record.timings)
    j["timings"].push_back(
        {{"frame", row.frame}, {"pass", row.pass.name}, {"ms", row.pass.milliseconds}});
  j["statistics"] = nlohmann::json::array();
  for (const StatisticRow& row : record.statistics)
    j["statistics"].push_back(
        {{"frame", row.frame}, {"name", row.statistic.name}, {"value", row.statistic.value}});
  j["frame_wall_ms"] = nlohmann::json::array();
  for (double seconds : record.frameWallSeconds) j["frame_wall_ms"].push_back(1e3 * seconds);
  // Paths are bytes, not always UTF-8: replace an invalid sequence rather than throw.
  writeTextFile(o.timings, j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n");
}

// What moves: --animate plays the scene's own animation (with a slow orbit where it has no
// camera path), --camera-path replaces the camera motion, --time-of-day / --day-cycle drive
// the sun. Empty when none is given: a still frame, as before.
SceneAnimation animationFrom(const RenderOptions& options, const Scene& scene) {
  SceneAnimation animation;
  if (options.animate) animation = playedAnimation(scene, !options.common.camera.empty());
  if (!options.cameraPath.empty()) animation.camera = loadCameraPath(options.cameraPath);
  if (options.timeOfDay || options.dayCycle > 0.0f)
    animation.timeOfDay = TimeOfDayTrack{options.timeOfDay.value_or(12.0f), options.dayCycle};
  return animation;
}

// The frame graph's names, in declaration order.
int listViews(HybridFrame& frame) {
  std::printf("passes:\n");
  for (const std::string& name : frame.passNames()) std::printf("  %s\n", name.c_str());
  std::printf("resources:\n");
  for (const std::string& name : frame.resourceNames()) std::printf("  %s\n", name.c_str());
  std::printf("ray-cast views: %s\n", primaryViewNames());
  return 0;
}

// --view must name a pass or resource of this frame (known once the frame is declared).
void checkView(HybridFrame& frame, const std::string& view) {
  std::vector<std::string> names = frame.passNames();
  for (const std::string& name : frame.resourceNames()) names.push_back(name);
  for (const std::string& name : splitNames(primaryViewNames())) names.push_back(name);
  if (std::find(names.begin(), names.end(), view) == names.end())
    fail(
        "--view '{}': not a pass or resource of this frame nor a ray-cast view{}; --list-views "
        "prints them",
        view, didYouMean(view, names));
}

void printSummary(const RenderOptions& o, const RenderRecord& record, const Scene& scene,
                  const HybridSettings& settings, const vk::Context& context, double startupSeconds,
                  double framesSeconds) {
  const uint32_t frames = uint32_t(o.frames);
  std::printf("%s: %s %ux%u, %u frame(s) on %s -> %s\n", scene.name.c_str(), o.view.c_str(),
              settings.width, settings.height, frames, context.info().name.c_str(), o.out.c_str());
  std::printf(
      "  wall time %.2f s: start-up %.2f s (scene, shaders, resources), %u frame(s) in "
      "%.2f s (%.1f ms per frame)\n",
      startupSeconds + framesSeconds, startupSeconds, frames, framesSeconds,
      1e3 * framesSeconds / frames);
  if (isCpuDevice(context)) {
    std::printf("  GPU time per pass: not meaningful on a CPU device (%s emulates the GPU)%s\n",
                context.info().name.c_str(),
                o.timings.empty() ? "" : "; --timings records them anyway");
  } else {
    std::printf("  GPU time per pass, median over the frames:\n");
    for (const auto& [name, ms] : medianPassTimes(record.timings, frames))
      std::printf("  %-28s %8.3f ms\n", name.c_str(), ms);
  }
  for (const StatisticRow& s : record.statistics)
    if (s.frame + 1 == frames)
      std::printf("  %-28s %g\n", s.statistic.name.c_str(), s.statistic.value);
}

int renderHybridFrame(const RenderOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  HybridSettings settings = settingsFrom(options);
  Scene scene = options.common.loadScene();
  SceneAnimation animation = animationFrom(options, scene);
  std::unique_ptr<vk::Context> context = options.common.createContext();
  GpuScene gpuScene(*context, scene, options.common.gpuSceneOptions());
  HybridFrame frame(*context, gpuScene, scene, settings);
  if (options.listViews) return listViews(frame);
  checkView(frame, options.view);
  frame.requestDebugView(options.view);
  AnimationPlayer player(scene, std::move(animation));
  const bool everyFrame = outIsDirectory(options.out);
  const uint32_t frames = uint32_t(options.frames);

  RenderRecord record;
  ProgressLine progress;
  const auto firstFrame = std::chrono::steady_clock::now();
  for (uint32_t i = 0; i < frames; ++i) {
    const auto frameStart = std::chrono::steady_clock::now();
    Camera camera = player.apply(frame, float(i) / options.fps);
    for (vk::PassTiming& t : frame.render(camera)) record.timings.push_back({i, std::move(t)});
    for (GiStatistic& s : frame.giStatistics()) record.statistics.push_back({i, std::move(s)});
    if (everyFrame) writeImage(frameImagePath(options.out, i), frame.debugViewImage(options.view));
    record.frameWallSeconds.push_back(secondsSince(frameStart));
    const double elapsed = secondsSince(firstFrame);
    const double perFrame = elapsed / double(i + 1);
    progress.draw(double(i + 1) / frames,
                  fmt::format("{}/{} frames  {:.0f} ms/frame", i + 1, frames, 1e3 * perFrame),
                  elapsed, perFrame * double(frames - i - 1));
  }
  progress.finish();
  if (!everyFrame) writeImage(options.out, frame.debugViewImage(options.view));
  if (!options.timings.empty())
    writeTimingsJson(options, record, scene, settings, *context, frame.diPipelineCount());
  const double startupSeconds = std::chrono::duration<double>(firstFrame - start).count();
  printSummary(options, record, scene, settings, *context, startupSeconds,
               secondsSince(firstFrame));
  return exitCodeFor(*context);
}

int runRender(const RenderOptions& options) {
  checkArguments(options);
  if (std::optional<PrimaryViewKind> view = primaryViewFromName(options.view))
    return renderPrimaryView(options, *view);
  return renderHybridFrame(options);
}

}  // namespace

void addRenderVerb(CLI::App& app, VerbAction& action) {
  auto options = std::make_shared<RenderOptions>();
  CLI::App* cmd = app.add_subcommand("render", "Render a scene headless with the real-time frame");
  options->common.addSceneOptions(*cmd, "sunroom");
  options->common.addResolution(*cmd, "");
  cmd->get_option("--res")->description(
      std::string("Image size WxH (default: the preset's, else ") + kDefaultResolution + ")");
  options->common.addDeviceOptions(*cmd);
  cmd->add_option("--preset", options->preset,
                  std::string("Settings preset: ") + presetNames() +
                      " (1170x540 / 1920x1080, shadows at half res); --res overrides its size");
  cmd->add_option("--frames", options->frames, "Frames to render (temporal passes converge)")
      ->capture_default_str();
  cmd->add_option("--vbuffer", options->vbuffer,
                  "How the vbuffer finds each pixel's triangle: raster (default) or trace (one "
                  "camera ray per pixel centre; faster on GPUs with little raster hardware such "
                  "as the H100/H200)")
      ->capture_default_str();
  cmd->add_option("--gi", options->gi, std::string("Diffuse GI mode: ") + giModeNames())
      ->capture_default_str();
  cmd->add_option("--di", options->di,
                  std::string("Direct light of every light but the sun (docs/di.md): ") +
                      diModeNames() +
                      " (restir: resampling with temporal and spatial reuse; uniform: the same "
                      "candidates without reuse; off: KHR lights unshadowed, as before)")
      ->capture_default_str();
  cmd->add_flag("--di-unbiased", options->diUnbiased,
                "ReSTIR DI's ray-traced bias correction in spatial reuse (a shadow ray per "
                "neighbour)");
  cmd->add_option("--di-brdf-candidates", options->diBrdfCandidates,
                  "ReSTIR DI's BRDF-sampled candidates per pixel, 0 or 1 (a ray that finds "
                  "emissive triangles in glossy reflections)")
      ->check(CLI::Range(0, 1))
      ->capture_default_str();
  cmd->add_option("--di-candidate-visibility", options->diCandidateVisibility,
                  "ReSTIR DI's shadow ray for each pixel's new candidate (RTXDI's initial "
                  "visibility): off (the default: a ray per pixel less; di-shade's final ray is "
                  "fed back instead), on, or auto (on with the light grid, from 512 lights); on "
                  "with --di-unbiased");
  cmd->add_option("--di-denoiser", options->diDenoiser,
                  std::string("Denoiser of ReSTIR DI's signal (di-denoise-*, docs/di.md): ") +
                      diDenoiserNames() + " (default: none)");
  cmd->add_option("--gi-divisor", options->giDivisor,
                  "ReSTIR GI resolution = render resolution / N (1 to 16; default: the "
                  "preset's, 4 mobile, 2 desktop)");
  cmd->add_option("--restir-second-vertex", options->restirSecondVertex,
                  "What the 2nd path vertex adds besides NEE: nee, path (a continued path: "
                  "unbiased, slow) or cache (the clipmap cache, default)");
  cmd->add_flag("--restir-unbiased", options->restirUnbiased,
                "The unbiased configuration: full-resolution GI, temporal reuse only, a "
                "continued path at the 2nd vertex, no denoisers");
  cmd->add_option("--restir-max-sample-age", options->restirMaxSampleAge,
                  "Drop ReSTIR GI history samples older than this many frames (0: no limit, the "
                  "default; see docs/gi/restir-gi.md, slow boiling)");
  cmd->add_option("--restir-validation-period", options->restirValidationPeriod,
                  "Validation rays every N frames (0: off, the default; seed 000 uses 3, for "
                  "light or geometry that jumps: see docs/gi/restir-gi.md)");
  cmd->add_option("--restir-history-brightening", options->restirHistoryBrightening,
                  "Cut ReSTIR GI history where a neighbourhood's fresh candidates stay brighter "
                  "than their running mean by this ratio (0: off, the default; 1.3 with "
                  "--restir-validation-period 3 for jumping light: see docs/gi/restir-gi.md)");
  cmd->add_flag("--no-gi-denoise", options->noGiDenoise, "Turn the GI denoisers off");
  cmd->add_option("--gi-denoise-history", options->giDenoiseHistory,
                  "Longest history of gi-temporal-denoise in frames, 1 to 1024 (default 64; a "
                  "static view keeps converging that long: docs/gi/restir-gi.md)");
  cmd->add_option("--denoiser", options->denoiser,
                  "Denoiser of the diffuse GI: evolve (gi-temporal/spatial-denoise, the "
                  "default), svgf (SVGF), reblur (ReBLUR-style), hybrid (SVGF or ReBLUR per "
                  "pixel; all three: docs/denoise.md) or none")
      ->check(CLI::IsMember({"evolve", "svgf", "reblur", "hybrid", "none"}));
  cmd->add_flag("--no-occluder-visibility", options->noOccluderVisibility,
                "Pixels beside an occluder reuse ReSTIR GI samples without a visibility test and "
                "are blurred like the others (light leaks into gaps; for comparisons)");
  cmd->add_option("--gi-texture-side", options->materialTextureSide,
                  "GI and cache rays read textures at the mip at most this many texels wide "
                  "(default 16, seed 000's coarse mip; 0: full resolution)");
  cmd->add_option("--view", options->view,
                  std::string("What to write: any pass or resource of the frame (its first "
                              "written image), as --list-views prints them for the chosen --gi "
                              "and --preset, or a ray-cast view: ") +
                      primaryViewNames())
      ->capture_default_str();
  cmd->add_flag("--list-views", options->listViews,
                "Print the passes and resources the frame declares for these settings (what "
                "--view accepts) and exit");
  cmd->add_option("--out", options->out,
                  "Output image (.png sRGB, .exr linear) of the last frame, or a directory "
                  "written with a trailing '/' (out/frames/) that gets every frame as "
                  "frame_NNNN.png; checked writable before any work")
      ->capture_default_str();
  cmd->add_option("--timings", options->timings,
                  "Write per-pass GPU times, GI statistics and wall time of every frame to this "
                  "JSON file (gpu_times_meaningful: false on a CPU device)");
  cmd->add_option("--exposure", options->exposureStops,
                  "Fixed exposure in stops: radiance x 2^STOPS before the tone curve (-64 to 64; "
                  "default: the settings' exposure)");
  cmd->add_option("--sky-ambient", options->skyAmbient,
                  "Weight of the placeholder ambient (unoccluded sky light) >= 0; 0 (the "
                  "default) = direct light only");
  cmd->add_option(
      "--shadow-divisor", options->shadowDivisor,
      "Trace shadows at render resolution / N (1 = full res; default: the preset's, 2)");
  cmd->add_option("--reflection-divisor", options->reflectionDivisor,
                  "Trace reflections at render resolution / N (1 = full res; 0 = no reflection "
                  "rays, specular light from the diffuse GI; default: the preset's, 2)");
  cmd->add_option("--reflection-reuse", options->reflectionReuse,
                  "ReSTIR-style reuse of glossy reflection samples across frames and neighbours "
                  "(reflections-temporal, -spatial, -resolve): on (the default) or off (the "
                  "traced signal as it is)");
  cmd->add_option("--reflection-denoise", options->reflectionDenoise,
                  "on (the default): reflections-denoise-temporal and -spatial filter the traced "
                  "reflections; off: reflections-upsample reads the one noisy sample per pixel");
  cmd->add_flag("--lambert", options->lambert, "Shade every material as pure Lambert");
  cmd->add_flag("--no-taa", options->noTaa,
                "No temporal anti-aliasing: one sample at each pixel centre, tonemap reads the "
                "composite (for comparisons with `bounce reference --pixel-centre`); by default "
                "the primary visibility is jittered and `taa` resolves it (the view `taa`)");
  cmd->add_flag("--animate", options->animate,
                "Play the scene's animation over the frames (glTF animations; built-in scenes' "
                "scripted motion, e.g. sunroom's swinging panel and sliding cube; a slow camera "
                "sway and dolly where the scene has no camera path or --camera is given). "
                "Frame i is at time i / --fps; a camera cut resets temporal history");
  cmd->add_option("--camera-path", options->cameraPath,
                  "Camera path JSON: {\"keyframes\": [{\"time\": s, \"position\": [x,y,z], "
                  "\"target\": [x,y,z], \"vfov\": deg, \"cut\": false}, ...], \"loop\": true, "
                  "\"interpolation\": \"catmull-rom\"|\"linear\"}; a cut key resets temporal "
                  "history");
  cmd->add_option("--fps", options->fps, "Animation time step: frame i is at i / fps seconds")
      ->capture_default_str();
  cmd->add_option("--time-of-day", options->timeOfDay,
                  "Solar time in hours [0, 24] (45 deg N, equinox: sunrise 6, noon 12, sunset "
                  "18; the noon sun comes from the scene's sun azimuth); below the horizon it is "
                  "night (no sun, a dim constant sky)");
  cmd->add_option("--day-cycle", options->dayCycle,
                  "Seconds of animation time per 24 h: the time of day advances from "
                  "--time-of-day (default 12) over the frames");
  cmd->callback([&action, options, cmd] {
    options->common.given.record(*cmd);
    action = [options] { return runRender(*options); };
  });
}

}  // namespace bounce::app
