// bounce render: renders a scene headless with the real-time hybrid frame (vbuffer, gbuffer,
// shadows, sky, composite, tonemap; DESIGN.md §4) for --frames frames and writes the final
// frame, or every frame, as images; --view shows any pass's debug view instead, and the
// ray-cast views primary-albedo|normal|depth|instance|geometry remain for checking a scene.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <optional>

#include <fmt/format.h>

#include "common_options.h"
#include "core/error.h"
#include "frame/animation_player.h"
#include "frame/hybrid_frame.h"
#include "frame/presets.h"
#include "passes/primary_view.h"
#include "rt/gpu_scene.h"
#include "scene/animation.h"
#include "tools/image_io.h"
#include "verbs.h"

namespace bounce::app {

namespace {

constexpr const char* kDefaultResolution = "640x360";

struct RenderOptions {
  CommonOptions common;
  std::string view = "tonemap";
  bool listViews = false;
  std::string out = "out/render.png";
  uint32_t frames = 8;
  std::string gi = "evolve";  // seed 000's full diffuse GI
  std::string vbuffer = "raster";
  // ReSTIR GI overrides (0 / empty: the preset's value).
  uint32_t giDivisor = 0;
  std::string restirSecondVertex;
  bool restirUnbiased = false;
  int restirValidationPeriod = -1;
  int restirMaxSampleAge = -1;  // -1: the settings' default
  float restirHistoryBrightening = -1.0f;
  bool noGiDenoise = false;
  int materialTextureSide = -1;  // -1: the settings' default
  bool noOccluderVisibility = false;
  std::string preset;
  std::string timings;
  float exposure = 0.03f;
  float skyAmbient = HybridSettings{}.skyAmbientStrength;
  uint32_t shadowDivisor = 0;                 // 0: the preset's
  std::optional<uint32_t> reflectionDivisor;  // unset: the preset's
  bool lambert = false;
  // Motion and time.
  bool animate = false;
  std::string cameraPath;
  float fps = 30.0f;
  std::optional<float> timeOfDay;
  float dayCycle = 0.0f;
};

void createParentDirectory(const std::string& path) {
  std::filesystem::path p(path);
  if (p.has_parent_path()) std::filesystem::create_directories(p.parent_path());
}

int renderPrimaryView(const RenderOptions& options, PrimaryViewKind view) {
  Resolution res = options.common.res.empty() ? parseResolution(kDefaultResolution)
                                              : options.common.resolution();
  Scene scene = options.common.loadScene();
  std::unique_ptr<vk::Context> context = options.common.createContext();
  GpuScene gpuScene(*context, scene);
  PrimaryViewPass pass(*context, gpuScene);
  vk::GpuTimer timer(*context);
  ImageRGBA32F image = pass.render(effectiveCamera(scene), res.width, res.height, view, &timer);
  createParentDirectory(options.out);
  writeImage(options.out, image);
  double ms = timer.available() ? timer.read().at(0).milliseconds : 0.0;
  std::printf("%s: %s %ux%u on %s: primary-view %.3f ms -> %s\n", scene.name.c_str(),
              options.view.c_str(), res.width, res.height, context->info().name.c_str(), ms,
              options.out.c_str());
  return exitCodeFor(*context);
}

std::optional<RestirGiSecondVertex> secondVertexFromName(const std::string& name) {
  if (name == "nee") return RestirGiSecondVertex::Nee;
  if (name == "path") return RestirGiSecondVertex::Path;
  if (name == "cache") return RestirGiSecondVertex::Cache;
  return std::nullopt;
}

// The --restir-* and --gi-* overrides, after the preset (RestirGiSettings documents each).
void applyRestirOptions(const RenderOptions& options, RestirGiSettings& gi) {
  if (options.restirUnbiased) gi = RestirGiSettings::unbiased();
  if (options.giDivisor != 0) gi.divisor = options.giDivisor;
  if (!options.restirSecondVertex.empty()) {
    std::optional<RestirGiSecondVertex> v = secondVertexFromName(options.restirSecondVertex);
    if (!v)
      fail("--restir-second-vertex '{}': expected nee, path or cache", options.restirSecondVertex);
    gi.secondVertex = *v;
  }
  if (options.restirValidationPeriod >= 0)
    gi.validationPeriod = uint32_t(options.restirValidationPeriod);
  if (options.restirMaxSampleAge != -1) {
    if (options.restirMaxSampleAge < 0)
      fail("--restir-max-sample-age {}: expected 0 (no limit) or more frames",
           options.restirMaxSampleAge);
    gi.maxSampleAge = uint32_t(options.restirMaxSampleAge);
  }
  if (options.restirHistoryBrightening >= 0.0f)
    gi.historyBrightening = options.restirHistoryBrightening;
  if (options.noGiDenoise) gi.temporalDenoise = gi.spatialDenoise = false;
  if (options.noOccluderVisibility) gi.occluderVisibility = false;
}

// Preset first, then --res, then the rest of the options.
HybridSettings settingsFrom(const RenderOptions& options) {
  HybridSettings settings;
  if (!options.preset.empty()) {
    std::optional<Preset> preset = presetFromName(options.preset);
    if (!preset) fail("--preset '{}': expected one of {}", options.preset, presetNames());
    settings = presetSettings(*preset);
  } else {
    Resolution res = parseResolution(kDefaultResolution);
    settings.width = res.width;
    settings.height = res.height;
  }
  if (!options.common.res.empty()) {
    Resolution res = options.common.resolution();
    settings.width = res.width;
    settings.height = res.height;
  }
  std::optional<GiMode> gi = giModeFromName(options.gi);
  if (!gi) fail("--gi '{}': expected one of {}", options.gi, giModeNames());
  settings.gi = *gi;
  std::optional<VBufferMode> vbuffer = vbufferModeFromName(options.vbuffer);
  if (!vbuffer) fail("--vbuffer '{}': expected raster or trace", options.vbuffer);
  settings.vbuffer = *vbuffer;
  applyRestirOptions(options, settings.restirGi);
  if (options.materialTextureSide != -1) {
    if (options.materialTextureSide < 0)
      fail("--gi-texture-side {}: expected 0 (full resolution) or more texels",
           options.materialTextureSide);
    // One flag for the two ray sets that read materials at x2: ReSTIR GI's and the cache's.
    settings.restirGi.materialTextureSide = settings.cache.materialTextureSide =
        uint32_t(options.materialTextureSide);
  }
  if (!(options.exposure > 0.0f) || !std::isfinite(options.exposure))
    fail("--exposure {}: must be positive", options.exposure);
  settings.exposureStops = std::log2(options.exposure);
  settings.skyAmbientStrength = options.skyAmbient;
  if (options.shadowDivisor != 0) settings.shadows.divisor = options.shadowDivisor;
  if (options.reflectionDivisor) settings.reflections.divisor = *options.reflectionDivisor;
  settings.lambert = options.lambert;
  validate(settings);  // the library's ranges, before any work
  return settings;
}

// --out: a file with an image extension gets the last frame; anything else is a directory
// that gets every frame.
bool outIsDirectory(const std::string& out) {
  return imageExtension(out).empty();
}

std::string frameImagePath(const std::string& directory, uint32_t frame) {
  return (std::filesystem::path(directory) / fmt::format("frame_{:04}.png", frame)).string();
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

void writeTimingsJson(const std::string& path, const std::vector<TimingRow>& rows,
                      const std::vector<StatisticRow>& statistics, const std::string& sceneName,
                      const HybridSettings& settings, const std::string& device) {
  createParentDirectory(path);
  std::ofstream f(path);
  if (!f) fail("--timings '{}': cannot write the file", path);
  f << fmt::format(
      "{{\n  \"scene\": \"{}\",\n  \"device\": \"{}\",\n  \"width\": {},\n"
      "  \"height\": {},\n  \"timings\": [\n",
      sceneName, device, settings.width, settings.height);
  for (size_t i = 0; i < rows.size(); ++i)
    f << fmt::format("    {{\"frame\": {}, \"pass\": \"{}\", \"ms\": {:.4f}}}{}\n", rows[i].frame,
                     rows[i].pass.name, rows[i].pass.milliseconds, i + 1 < rows.size() ? "," : "");
  f << "  ],\n  \"statistics\": [\n";
  for (size_t i = 0; i < statistics.size(); ++i)
    f << fmt::format("    {{\"frame\": {}, \"name\": \"{}\", \"value\": {}}}{}\n",
                     statistics[i].frame, statistics[i].statistic.name,
                     statistics[i].statistic.value, i + 1 < statistics.size() ? "," : "");
  f << "  ]\n}\n";
}

// What moves: --animate plays the scene's own animation (with a slow orbit where it has no
// camera path), --camera-path replaces the camera motion, --time-of-day / --day-cycle drive
// the sun. Empty when none is given: a still frame, as before.
SceneAnimation animationFrom(const RenderOptions& options, const Scene& scene) {
  if (!(options.fps > 0.0f)) fail("--fps {}: must be positive", options.fps);
  if (options.timeOfDay && !(*options.timeOfDay >= 0.0f && *options.timeOfDay <= 24.0f))
    fail("--time-of-day {}: expected hours in [0, 24]", *options.timeOfDay);
  if (!(options.dayCycle >= 0.0f)) fail("--day-cycle {}: must be >= 0 seconds", options.dayCycle);
  SceneAnimation animation;
  if (options.animate) {
    animation = scene.animation;
    // A --camera given on the command line is where the default sway starts, rather than being
    // overridden by the scene's own path.
    if (!animation.camera || !options.common.camera.empty())
      animation.camera = swayCameraPath(effectiveCamera(scene), 4.0f, 0.3f, 8.0f);
  }
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

int renderHybridFrame(const RenderOptions& options) {
  if (options.frames == 0) fail("--frames 0: render at least one frame");
  HybridSettings settings = settingsFrom(options);
  Scene scene = options.common.loadScene();
  SceneAnimation animation = animationFrom(options, scene);
  std::unique_ptr<vk::Context> context = options.common.createContext();
  GpuScene gpuScene(*context, scene);
  HybridFrame frame(*context, gpuScene, scene, settings);
  if (options.listViews) return listViews(frame);
  frame.requestDebugView(options.view);
  AnimationPlayer player(scene, std::move(animation));
  bool everyFrame = outIsDirectory(options.out);
  if (everyFrame) std::filesystem::create_directories(options.out);

  std::vector<TimingRow> timings;
  std::vector<StatisticRow> statistics;
  for (uint32_t i = 0; i < options.frames; ++i) {
    Camera camera = player.apply(frame, float(i) / options.fps);
    for (vk::PassTiming& t : frame.render(camera)) timings.push_back({i, std::move(t)});
    for (GiStatistic& s : frame.giStatistics()) statistics.push_back({i, std::move(s)});
    if (everyFrame) writeImage(frameImagePath(options.out, i), frame.debugViewImage(options.view));
  }
  if (!everyFrame) {
    createParentDirectory(options.out);
    writeImage(options.out, frame.debugViewImage(options.view));
  }
  if (!options.timings.empty())
    writeTimingsJson(options.timings, timings, statistics, scene.name, settings,
                     context->info().name);
  std::printf("%s: %s %ux%u, %u frame(s) on %s -> %s\n", scene.name.c_str(), options.view.c_str(),
              settings.width, settings.height, options.frames, context->info().name.c_str(),
              options.out.c_str());
  std::printf("  GPU time per pass, median over the frames:\n");
  for (const auto& [name, ms] : medianPassTimes(timings, options.frames))
    std::printf("  %-28s %8.3f ms\n", name.c_str(), ms);
  for (const StatisticRow& s : statistics)
    if (s.frame + 1 == options.frames)
      std::printf("  %-28s %g\n", s.statistic.name.c_str(), s.statistic.value);
  return exitCodeFor(*context);
}

int runRender(const RenderOptions& options) {
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
                  "Output image (.png sRGB, .exr linear) of the last frame, or a directory that "
                  "gets every frame as frame_NNNN.png")
      ->capture_default_str();
  cmd->add_option("--timings", options->timings,
                  "Write per-pass GPU times of every frame to this JSON file");
  cmd->add_option("--exposure", options->exposure, "Radiance multiplier before the tone curve")
      ->capture_default_str();
  cmd->add_option("--sky-ambient", options->skyAmbient,
                  "Weight of the placeholder ambient (unoccluded sky light); 0 = direct light only")
      ->capture_default_str();
  cmd->add_option(
      "--shadow-divisor", options->shadowDivisor,
      "Trace shadows at render resolution / N (1 = full res; default: the preset's, 2)");
  cmd->add_option("--reflection-divisor", options->reflectionDivisor,
                  "Trace reflections at render resolution / N (1 = full res; 0 = no reflection "
                  "rays, specular light from the diffuse GI; default: the preset's, 2)");
  cmd->add_flag("--lambert", options->lambert, "Shade every material as pure Lambert");
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
  cmd->callback([&action, options] { action = [options] { return runRender(*options); }; });
}

}  // namespace bounce::app
