// bounce bench: seed 000's benchmark. A scripted run per scene (the camera path --animate plays,
// a day-night cycle from before sunrise to after sunset, the scene's moving objects), once per
// preset x GI mode given; per-pass GPU times with a 9-frame rolling average and frame times in
// a JSON report, a stacked-area plot of the pass times (PNG and SVG), a table per run, and a
// contact sheet of tone-mapped frames along the path (docs/benchmarks.md).
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
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
#include "progress.h"
#include "rt/gpu_scene.h"
#include "scene/animation.h"
#include "suggest.h"
#include "tools/image_io.h"
#include "tools/metrics.h"
#include "tools/output_file.h"
#include "tools/soak_check.h"
#include "tools/stacked_plot.h"
#include "verbs.h"

namespace bounce::app {

namespace {

namespace fs = std::filesystem;

constexpr int64_t kMaxFrames = 1000000;
// The frame every tile of the contact sheet is reduced to fit (in width).
constexpr int kContactTileWidth = 320;

struct BenchOptions {
  CommonOptions common;
  std::string presets = "desktop";
  std::string gis = "evolve";
  int64_t frames = 240;
  float fps = 30.0f;
  float timeOfDay = 4.0f;         // two hours before sunrise
  std::optional<float> dayCycle;  // not given: one whole day over the run
  int64_t window = 9;             // seed 000's rolling average
  int64_t contactFrames = 8;
  std::string out = "out/bench";
  std::string runsFile;              // JSON list of runs instead of the --preset x --gi product
  std::vector<std::string> compare;  // bench.json files to draw side by side instead of a run
  // --soak: every frame checked for NaN/Inf, host and device memory for growth (issue 24).
  bool soak = false;
  int64_t soakWarmup = 100;
  double soakResidentGrowthMiB = 8.0;
  bool countRays = true;  // rays per pass, counted on the GPU (HybridFrame::countRays)
};

// A soak whose checks failed (NaN or Inf pixels, memory growth): the report is still written.
constexpr int kSoakFailedExit = 5;

// One preset x GI mode.
struct BenchRun {
  std::string preset;
  std::string gi;
};

// --runs FILE: {"runs": [{"preset": "mobile", "gi": "cache"}, ...]}, each field checked as the
// options are.
std::vector<BenchRun> runsFromFile(const std::string& path) {
  std::ifstream file(path);
  if (!file) fail("--runs '{}': cannot open the file", path);
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(file);
  } catch (const nlohmann::json::exception& e) {
    fail("--runs '{}': not valid JSON: {}", path, e.what());
  }
  if (!j.is_object() || !j.contains("runs") || !j["runs"].is_array() || j["runs"].empty())
    fail("--runs '{}': expected {{\"runs\": [{{\"preset\": ..., \"gi\": ...}}, ...]}}", path);
  std::vector<BenchRun> runs;
  for (const nlohmann::json& run : j["runs"]) {
    if (!run.is_object() || !run.value("preset", nlohmann::json()).is_string() ||
        !run.value("gi", nlohmann::json()).is_string())
      fail("--runs '{}': run {}: expected string fields \"preset\" and \"gi\"", path, runs.size());
    runs.push_back({run["preset"].get<std::string>(), run["gi"].get<std::string>()});
    requireOneOf("--runs preset", runs.back().preset, splitNames(presetNames()));
    requireOneOf("--runs gi", runs.back().gi, splitNames(giModeNames()));
  }
  return runs;
}

std::vector<BenchRun> runsFrom(const BenchOptions& o) {
  if (!o.runsFile.empty()) return runsFromFile(o.runsFile);
  std::vector<BenchRun> runs;
  const std::vector<std::string> presets = splitNames(o.presets), gis = splitNames(o.gis);
  if (presets.empty()) fail("--preset '{}': expected one or more of {}", o.presets, presetNames());
  if (gis.empty()) fail("--gi '{}': expected one or more of {}", o.gis, giModeNames());
  for (const std::string& preset : presets) {
    requireOneOf("--preset", preset, splitNames(presetNames()));
    for (const std::string& gi : gis) {
      requireOneOf("--gi", gi, splitNames(giModeNames()));
      runs.push_back({preset, gi});
    }
  }
  return runs;
}

void checkArguments(const BenchOptions& o) {
  o.common.checkArguments();
  o.common.given.refuseTogether("--runs", "--preset", "the file lists each run's preset");
  o.common.given.refuseTogether("--runs", "--gi", "the file lists each run's GI mode");
  runsFrom(o);
  if (o.frames < 1 || o.frames > kMaxFrames)
    fail("--frames {}: expected 1 to {} frames", o.frames, kMaxFrames);
  if (!(o.fps > 0.0f) || !std::isfinite(o.fps)) fail("--fps {}: must be positive", o.fps);
  if (!(o.timeOfDay >= 0.0f && o.timeOfDay <= 24.0f))
    fail("--time-of-day {}: expected hours in [0, 24]", o.timeOfDay);
  if (o.dayCycle && !(*o.dayCycle >= 0.0f && std::isfinite(*o.dayCycle)))
    fail("--day-cycle {}: must be >= 0 seconds", *o.dayCycle);
  if (o.window < 1 || o.window > 1000) fail("--window {}: expected 1 to 1000 frames", o.window);
  if (o.contactFrames < 1 || o.contactFrames > 64)
    fail("--contact-frames {}: expected 1 to 64", o.contactFrames);
  if (o.soak && (o.soakWarmup < 0 || o.soakWarmup >= o.frames))
    fail(
        "--soak-warmup {}: expected 0 to --frames - 1 ({}), so that frames after the warm-up "
        "are checked",
        o.soakWarmup, o.frames - 1);
  if (!(o.soakResidentGrowthMiB >= 0.0) || !std::isfinite(o.soakResidentGrowthMiB))
    fail("--soak-rss-growth {}: expected MiB >= 0", o.soakResidentGrowthMiB);
  if (o.common.given.has("--sun"))
    fail("bench: --sun cannot be used: the day cycle sets the sun (--time-of-day, --day-cycle)");
  requireWritableDirectory("--out", o.out);
}

// The preset's settings at --res (when given) with the run's GI mode.
HybridSettings settingsFor(const BenchOptions& o, const BenchRun& run) {
  HybridSettings settings = presetSettings(*presetFromName(run.preset));
  settings.gi = *giModeFromName(run.gi);
  if (!o.common.res.empty()) {
    const Resolution res = o.common.resolution();
    settings.width = res.width;
    settings.height = res.height;
  }
  try {
    validate(settings);
  } catch (const Error& e) {
    fail("--preset {} --gi {} --res {}: {}", run.preset, run.gi, o.common.res, e.what());
  }
  return settings;
}

// What moves: the camera path and objects --animate plays, and the sun over the day.
SceneAnimation benchAnimation(const BenchOptions& o, const Scene& scene) {
  SceneAnimation animation = playedAnimation(scene, !o.common.camera.empty());
  const float seconds = float(o.frames) / o.fps;
  animation.timeOfDay = TimeOfDayTrack{o.timeOfDay, o.dayCycle.value_or(seconds)};
  return animation;
}

// Mean over the last `window` values up to and including each one (fewer at the start).
std::vector<double> rollingMean(const std::vector<double>& values, size_t window) {
  std::vector<double> result(values.size());
  double sum = 0.0;
  for (size_t i = 0; i < values.size(); ++i) {
    sum += values[i];
    if (i >= window) sum -= values[i - window];
    result[i] = sum / double(std::min(i + 1, window));
  }
  return result;
}

double mean(const std::vector<double>& v) {
  double sum = 0.0;
  for (double x : v) sum += x;
  return v.empty() ? 0.0 : sum / double(v.size());
}

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

// A pass's GPU milliseconds and rays in every frame (0 in a frame that did not run it).
struct PassSeries {
  std::string name;
  std::vector<double> ms;
  std::vector<double> rays;  // empty when rays were not counted
};

struct RunRecord {
  std::vector<PassSeries> passes;  // in first-recorded order
  std::vector<double> frameGpuMs, frameWallMs, hours;
  std::vector<double> frameRays;  // empty when rays were not counted
  std::vector<uint32_t> contactFrameIndices;
  std::vector<ImageRGBA32F> contactTiles;
  uint64_t deviceBytes = 0, deviceAllocations = 0;  // Bounce's, frame and scene, at the end
  std::optional<SoakCheck> soak;
};

void addTimings(RunRecord& record, uint32_t frame, uint32_t frames,
                const std::vector<vk::PassTiming>& timings) {
  double total = 0.0, rays = 0.0;
  bool counted = false;
  for (const vk::PassTiming& t : timings) {
    // The debug-view copies feed the contact sheet; they are not part of the frame.
    if (t.name.rfind("debug-view:", 0) == 0) continue;
    auto it = std::find_if(record.passes.begin(), record.passes.end(),
                           [&](const PassSeries& p) { return p.name == t.name; });
    if (it == record.passes.end()) {
      record.passes.push_back({t.name, std::vector<double>(frames, 0.0), {}});
      it = record.passes.end() - 1;
    }
    it->ms[frame] += t.milliseconds;
    total += t.milliseconds;
    if (t.rays) {
      if (it->rays.empty()) it->rays.assign(frames, 0.0);
      it->rays[frame] += double(*t.rays);
      rays += double(*t.rays);
      counted = true;
    }
  }
  record.frameGpuMs.push_back(total);
  if (counted) {
    record.frameRays.resize(frame, 0.0);
    record.frameRays.push_back(rays);
  }
}

// The frames of the contact sheet: `count` at even intervals from the first to the last.
std::vector<uint32_t> contactFrameIndices(uint32_t frames, uint32_t count) {
  count = std::min(count, frames);
  std::vector<uint32_t> indices;
  for (uint32_t j = 0; j < count; ++j)
    indices.push_back(count == 1 ? frames - 1
                                 : uint32_t(std::lround(double(j) * (frames - 1) / (count - 1))));
  return indices;
}

// A box-filtered reduction by a whole factor, so that a tile is at most kContactTileWidth wide.
ImageRGBA32F contactTile(const ImageRGBA32F& frame) {
  const int factor = std::max(1, (frame.width + kContactTileWidth - 1) / kContactTileWidth);
  ImageRGBA32F tile(frame.width / factor, frame.height / factor);
  for (int y = 0; y < tile.height; ++y)
    for (int x = 0; x < tile.width; ++x) {
      glm::vec4 sum(0.0f);
      for (int dy = 0; dy < factor; ++dy)
        for (int dx = 0; dx < factor; ++dx) sum += frame.at(x * factor + dx, y * factor + dy);
      tile.set(x, y, sum / float(factor * factor));
    }
  return tile;
}

// Tiles left to right, top to bottom, four to a row.
ImageRGBA32F contactSheet(const std::vector<ImageRGBA32F>& tiles) {
  const int columns = std::min<int>(4, int(tiles.size()));
  const int rows = (int(tiles.size()) + columns - 1) / columns;
  const int w = tiles[0].width, h = tiles[0].height;
  ImageRGBA32F sheet(columns * w, rows * h);
  for (size_t i = 0; i < tiles.size(); ++i)
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        sheet.set(int(i % columns) * w + x, int(i / columns) * h + y, tiles[i].at(x, y));
  return sheet;
}

RunRecord runFrames(const BenchOptions& o, const BenchRun& run, const Scene& scene,
                    vk::Context& context, GpuScene& gpuScene) {
  HybridFrame frame(context, gpuScene, scene, settingsFor(o, run));
  frame.countRays(o.countRays);
  frame.requestDebugView("tonemap");
  // The linear frame before tone mapping: a NaN anywhere in the chain reaches it.
  if (o.soak) frame.requestDebugView("composite");
  const SceneAnimation animation = benchAnimation(o, scene);
  const TimeOfDayTrack day = *animation.timeOfDay;
  AnimationPlayer player(scene, animation);
  const uint32_t frames = uint32_t(o.frames);
  RunRecord record;
  record.contactFrameIndices = contactFrameIndices(frames, uint32_t(o.contactFrames));
  if (o.soak)
    record.soak.emplace(uint32_t(o.soakWarmup), uint64_t(o.soakResidentGrowthMiB * (1 << 20)));
  ProgressLine progress;
  const auto start = std::chrono::steady_clock::now();
  for (uint32_t i = 0; i < frames; ++i) {
    const auto frameStart = std::chrono::steady_clock::now();
    const float t = float(i) / o.fps;
    Camera camera = player.apply(frame, t);
    addTimings(record, i, frames, frame.render(camera));
    record.frameWallMs.push_back(1e3 * secondsSince(frameStart));
    record.hours.push_back(day.hoursAt(t));
    if (record.soak)
      record.soak->add({i, countNonFinitePixels(frame.debugViewImage("composite")),
                        residentSetBytes(), context.liveAllocationBytes(),
                        context.liveAllocationCount(), heapInUseBytes()});
    const auto& picks = record.contactFrameIndices;
    if (std::find(picks.begin(), picks.end(), i) != picks.end()) {
      record.contactTiles.push_back(contactTile(frame.debugViewImage("tonemap")));
      drawLabel(record.contactTiles.back(), 2, 2,
                fmt::format("frame {}, {:.1f} h", i, record.hours.back()));
    }
    const double elapsed = secondsSince(start), perFrame = elapsed / double(i + 1);
    progress.draw(double(i + 1) / frames,
                  fmt::format("{} {}: {}/{} frames", run.preset, run.gi, i + 1, frames), elapsed,
                  perFrame * double(frames - i - 1));
  }
  progress.finish();
  record.deviceBytes = context.liveAllocationBytes();
  record.deviceAllocations = context.liveAllocationCount();
  return record;
}

// Per pass: mean, median and worst rolling average, and its share of the mean frame; with
// rays counted, the median rays per frame, per pixel and the rate (rays over milliseconds,
// both medians, in Grays/s).
nlohmann::json tableJson(const RunRecord& r, size_t window, uint64_t pixels) {
  nlohmann::json table = nlohmann::json::array();
  const double frameMean = mean(r.frameGpuMs);
  auto row = [&](const std::string& name, const std::vector<double>& ms,
                 const std::vector<double>& rays, bool gpu = true) {
    const std::vector<double> rolling = rollingMean(ms, window);
    nlohmann::json row = {{"pass", name},
                          {"mean_ms", mean(ms)},
                          {"median_ms", median(ms)},
                          {"max_rolling_ms", *std::max_element(rolling.begin(), rolling.end())},
                          // Of the frame's GPU time; the host's wall time is no part of it.
                          {"share", gpu && frameMean > 0.0 ? nlohmann::json(mean(ms) / frameMean)
                                                           : nlohmann::json()}};
    if (!rays.empty()) {
      const double medianRays = median(rays), medianMs = median(ms);
      row["median_rays"] = medianRays;
      row["rays_per_pixel"] = medianRays / double(pixels);
      row["grays_per_s"] = medianRays > 0.0 && medianMs > 0.0
                               ? nlohmann::json(medianRays / medianMs * 1e-6)
                               : nlohmann::json();
    }
    table.push_back(row);
  };
  for (const PassSeries& p : r.passes) row(p.name, p.ms, p.rays);
  row("frame (GPU)", r.frameGpuMs, r.frameRays);
  row("frame (wall, host)", r.frameWallMs, {}, false);
  return table;
}

void printTable(const std::string& title, const nlohmann::json& table) {
  std::printf("%s\n  %-32s %10s %10s %12s %7s %10s %8s\n", title.c_str(), "pass", "mean ms",
              "median ms", "max rolling", "share", "rays/px", "Grays/s");
  for (const nlohmann::json& row : table) {
    const std::string share =
        row["share"].is_null() ? "" : fmt::format("{:.1f}%", 100.0 * row["share"].get<double>());
    const bool counted = row.contains("rays_per_pixel");
    const std::string perPixel =
        counted ? fmt::format("{:.3f}", row["rays_per_pixel"].get<double>()) : "";
    const std::string rate = counted && !row["grays_per_s"].is_null()
                                 ? fmt::format("{:.2f}", row["grays_per_s"].get<double>())
                                 : "";
    std::printf("  %-32s %10.3f %10.3f %12.3f %7s %10s %8s\n",
                row["pass"].get<std::string>().c_str(), row["mean_ms"].get<double>(),
                row["median_ms"].get<double>(), row["max_rolling_ms"].get<double>(), share.c_str(),
                perPixel.c_str(), rate.c_str());
  }
}

// The frame at which the day passes `hours` first (sunrise 6, sunset 18), if it does.
std::optional<uint32_t> frameAtHour(const std::vector<double>& hours, double at) {
  for (size_t i = 1; i < hours.size(); ++i) {
    const double a = hours[i - 1], b = hours[i] < a ? hours[i] + 24.0 : hours[i];
    if ((a < at && at <= b) || (a < at + 24.0 && at + 24.0 <= b)) return uint32_t(i);
  }
  return std::nullopt;
}

std::string dayLabel(const std::vector<double>& hours) {
  std::string label = fmt::format("frame (day from {:.1f} h", hours.front());
  if (auto f = frameAtHour(hours, 6.0)) label += fmt::format(", sunrise at {}", *f);
  if (auto f = frameAtHour(hours, 18.0)) label += fmt::format(", sunset at {}", *f);
  return label + ")";
}

// Writes the run's plot and contact sheet and returns its part of the report.
nlohmann::json soakJson(const SoakCheck& soak) {
  auto sample = [](const std::optional<SoakSample>& s) {
    if (!s) return nlohmann::json();
    return nlohmann::json{{"frame", s->frame},
                          {"non_finite_pixels", s->nonFinitePixels},
                          {"resident_bytes", s->residentBytes},
                          {"heap_in_use_bytes", s->heapInUseBytes},
                          {"device_bytes", s->deviceBytes},
                          {"device_allocations", s->deviceAllocations}};
  };
  return {{"passed", soak.passed()},
          {"failures", soak.failures()},
          {"frames", soak.frames()},
          {"warmup_frames", soak.warmupFrames()},
          {"non_finite_frames", soak.nonFiniteFrames()},
          {"first_non_finite", sample(soak.firstNonFinite())},
          {"after_warmup", sample(soak.afterWarmup())},
          {"last", sample(soak.last())},
          {"peak_resident_bytes_after_warmup", soak.peakResidentAfterWarmup()},
          {"resident_slope_bytes_per_frame", soak.residentSlopeBytesPerFrame()}};
}

nlohmann::json reportRun(const BenchOptions& o, const BenchRun& run, const RunRecord& r,
                         const Scene& scene, const HybridSettings& settings,
                         const vk::Context& context) {
  const size_t window = size_t(o.window);
  const std::string stem = run.preset + "-" + run.gi;
  StackedPlot plot;
  plot.title = fmt::format("{} {} --gi {}, {}x{}, {}{}", scene.name, run.preset, run.gi,
                           settings.width, settings.height, context.info().name,
                           isCpuDevice(context) ? " (CPU: emulated GPU times)" : "");
  plot.xLabel = dayLabel(r.hours);
  plot.yLabel = fmt::format("GPU ms ({}-frame rolling average)", window);
  plot.height = std::max(480, 110 + 16 * int(r.passes.size()));
  // Night: the sun below the horizon (time_of_day.h: sunrise 6 h, sunset 18 h).
  for (double h : r.hours) plot.shaded.push_back(h < 6.0 || h > 18.0);
  plot.shadedLabel = "night (sun below the horizon)";
  nlohmann::json j = {{"preset", run.preset},
                      {"gi", run.gi},
                      {"width", settings.width},
                      {"height", settings.height}};
  j["passes"] = nlohmann::json::array();
  for (const PassSeries& p : r.passes) {
    const std::vector<double> rolling = rollingMean(p.ms, window);
    plot.series.push_back({p.name, rolling});
    j["passes"].push_back({{"name", p.name}, {"ms", p.ms}, {"rolling_ms", rolling}});
    if (!p.rays.empty()) j["passes"].back()["rays"] = p.rays;
  }
  if (!r.frameRays.empty()) j["frame_rays"] = r.frameRays;
  j["frame_gpu_ms"] = r.frameGpuMs;
  j["frame_gpu_rolling_ms"] = rollingMean(r.frameGpuMs, window);
  j["frame_wall_ms"] = r.frameWallMs;
  j["hours"] = r.hours;
  j["table"] = tableJson(r, window, uint64_t(settings.width) * settings.height);
  j["device_bytes"] = r.deviceBytes;
  j["device_allocations"] = r.deviceAllocations;
  if (r.soak) j["soak"] = soakJson(*r.soak);
  const fs::path dir(o.out);
  j["plot_png"] = stem + "-passes.png";
  j["plot_svg"] = stem + "-passes.svg";
  j["contact_sheet"] = stem + "-contact.png";
  j["contact_frames"] = r.contactFrameIndices;
  writeTextFile((dir / (stem + "-passes.svg")).string(), stackedPlotSvg(plot));
  writePng((dir / (stem + "-passes.png")).string(), stackedPlotImage(plot));
  writePng((dir / (stem + "-contact.png")).string(), contactSheet(r.contactTiles));
  printTable(fmt::format("{} {} --gi {}, {}x{}, {} frames:", scene.name, run.preset, run.gi,
                         settings.width, settings.height, o.frames),
             j["table"]);
  return j;
}

// ---- comparison: runs side by side ----

// One bar of the comparison plot: a run's median milliseconds per pass.
struct ComparedRun {
  std::string label;
  std::vector<std::pair<std::string, double>> passMedians;
};

// The runs of a bench report; `device` prefixes the labels when reports of several devices meet.
std::vector<ComparedRun> comparedRuns(const nlohmann::json& report, const std::string& source,
                                      bool withDevice) {
  if (!report.is_object() || !report.contains("runs") || !report["runs"].is_array())
    fail("--compare '{}': not a `bounce bench` report (no \"runs\" list)", source);
  std::vector<ComparedRun> runs;
  for (const nlohmann::json& run : report["runs"]) {
    ComparedRun c;
    try {
      c.label = fmt::format("{}{} {}\n{}x{}",
                            withDevice ? report.at("device").get<std::string>() + "\n" : "",
                            run.at("preset").get<std::string>(), run.at("gi").get<std::string>(),
                            run.at("width").get<int>(), run.at("height").get<int>());
      for (const nlohmann::json& row : run.at("table")) {
        const std::string pass = row.at("pass").get<std::string>();
        if (pass.rfind("frame (", 0) == 0) continue;  // the totals, not passes
        c.passMedians.push_back({pass, row.at("median_ms").get<double>()});
      }
    } catch (const nlohmann::json::exception& e) {
      fail("--compare '{}': run {}: {}", source, runs.size(), e.what());
    }
    runs.push_back(std::move(c));
  }
  return runs;
}

// comparison.png/.svg in `dir`: a stacked bar of pass medians per run, passes in the order they
// first appear.
void writeComparison(const std::vector<ComparedRun>& runs, const std::string& title,
                     const fs::path& dir) {
  StackedPlot plot;
  plot.title = title;
  plot.yLabel = "GPU ms (median over the run)";
  plot.xLabel = "run";
  for (const ComparedRun& run : runs) plot.bars.push_back(run.label);
  for (size_t r = 0; r < runs.size(); ++r)
    for (const auto& [pass, ms] : runs[r].passMedians) {
      auto it = std::find_if(plot.series.begin(), plot.series.end(),
                             [&](const PlotSeries& s) { return s.name == pass; });
      if (it == plot.series.end()) {
        plot.series.push_back({pass, std::vector<double>(runs.size(), 0.0)});
        it = plot.series.end() - 1;
      }
      it->values[r] = ms;
    }
  if (plot.series.empty()) fail("bench comparison: the runs have no pass times");
  plot.width = std::max(960, 330 + 170 * int(runs.size()));
  plot.height = std::max(480, 140 + 16 * int(plot.series.size()));
  writeTextFile((dir / "comparison.svg").string(), stackedPlotSvg(plot));
  writePng((dir / "comparison.png").string(), stackedPlotImage(plot));
  std::printf("-> %s\n", (dir / "comparison.png").string().c_str());
}

int compareReports(const BenchOptions& o) {
  for (const char* option : {"--preset", "--gi", "--runs", "--scene", "--soak", "--frames"})
    o.common.given.refuseTogether("--compare", option,
                                  "a comparison draws finished reports and runs nothing");
  requireWritableDirectory("--out", o.out);
  std::vector<nlohmann::json> reports;
  std::set<std::string> devices;
  for (const std::string& path : o.compare) {
    std::ifstream file(path);
    if (!file) fail("--compare '{}': cannot open the file", path);
    try {
      reports.push_back(nlohmann::json::parse(file));
    } catch (const nlohmann::json::exception& e) {
      fail("--compare '{}': not valid JSON: {}", path, e.what());
    }
    devices.insert(reports.back().value("device", std::string("?")));
  }
  std::vector<ComparedRun> runs;
  std::set<std::string> scenes;
  for (size_t i = 0; i < reports.size(); ++i) {
    for (ComparedRun& run : comparedRuns(reports[i], o.compare[i], devices.size() > 1))
      runs.push_back(std::move(run));
    scenes.insert(reports[i].value("scene", std::string("?")));
  }
  std::string sceneList;
  for (const std::string& s : scenes) sceneList += (sceneList.empty() ? "" : ", ") + s;
  std::string deviceList;
  for (const std::string& d : devices) deviceList += (deviceList.empty() ? "" : ", ") + d;
  writeComparison(runs, fmt::format("{} on {}", sceneList, deviceList), o.out);
  return 0;
}

int runBench(const BenchOptions& o) {
  if (!o.compare.empty()) return compareReports(o);
  checkArguments(o);
  const std::vector<BenchRun> runs = runsFrom(o);
  Scene scene = o.common.loadScene();
  std::unique_ptr<vk::Context> context = o.common.createContext();
  GpuScene gpuScene(*context, scene, o.common.gpuSceneOptions());
  nlohmann::json report = {
      {"scene", scene.name},
      {"scene_source", o.common.scene},
      {"device", context->info().name},
      {"device_type", context->info().type},
      // On a CPU device the timestamps measure the emulation of a GPU.
      {"gpu_times_meaningful", !isCpuDevice(*context)},
      {"scene_gpu_bytes", gpuScene.stats().totalBytes},
      {"frames", o.frames},
      {"fps", o.fps},
      {"rolling_window", o.window},
      {"time_of_day_start", o.timeOfDay},
      {"day_cycle_seconds", o.dayCycle.value_or(float(o.frames) / o.fps)},
      {"camera",
       scene.animation.camera && o.common.camera.empty() ? "scene path" : "sway and dolly"}};
  report["runs"] = nlohmann::json::array();
  std::vector<std::string> soakFailures;
  for (const BenchRun& run : runs) {
    const RunRecord record = runFrames(o, run, scene, *context, gpuScene);
    report["runs"].push_back(reportRun(o, run, record, scene, settingsFor(o, run), *context));
    if (record.soak)
      for (const std::string& failure : record.soak->failures())
        soakFailures.push_back(fmt::format("{} --gi {}: {}", run.preset, run.gi, failure));
  }
  if (isCpuDevice(*context))
    std::printf("note: %s is a CPU device: the GPU times measure its emulation of a GPU\n",
                context->info().name.c_str());
  // TLAS rebuilds of the refit's policy (GpuSceneOptions::tlasRebuildRatio), over all runs.
  report["tlas_rebuilds"] = gpuScene.tlasRebuildCount();
  // Host memory: the peak resident set of the whole process (all runs), for growth checks.
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  report["host_peak_rss_bytes"] = int64_t(usage.ru_maxrss) * 1024;  // Linux: kilobytes
  if (report["runs"].size() > 1) {
    std::vector<ComparedRun> compared = comparedRuns(report, "bench", false);
    writeComparison(compared, fmt::format("{} on {}", scene.name, context->info().name), o.out);
    report["comparison_png"] = "comparison.png";
    report["comparison_svg"] = "comparison.svg";
  }
  const std::string json = (fs::path(o.out) / "bench.json").string();
  // Paths are bytes, not always UTF-8: replace an invalid sequence rather than throw.
  writeTextFile(json, report.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n");
  std::printf("-> %s\n", json.c_str());
  for (const std::string& failure : soakFailures)
    std::fprintf(stderr, "bounce: error: bench --soak: %s %s\n", scene.name.c_str(),
                 failure.c_str());
  if (o.soak && soakFailures.empty())
    std::printf("soak passed: every frame finite, no memory growth after frame %lld\n",
                (long long)o.soakWarmup);
  const int validation = exitCodeFor(*context);
  return validation != 0 ? validation : soakFailures.empty() ? 0 : kSoakFailedExit;
}

}  // namespace

void addBenchVerb(CLI::App& app, VerbAction& action) {
  auto options = std::make_shared<BenchOptions>();
  CLI::App* cmd = app.add_subcommand(
      "bench", "Benchmark the real-time frame over a scripted run: per-pass GPU times, plots");
  options->common.addSceneOptions(*cmd, "sunroom");
  options->common.addResolution(*cmd, "");
  cmd->get_option("--res")->description("Image size WxH (default: each preset's)");
  options->common.addDeviceOptions(*cmd);
  cmd->add_option("--preset", options->presets,
                  std::string("Comma-separated presets, one run each: ") + presetNames())
      ->capture_default_str();
  cmd->add_option(
         "--gi", options->gis,
         std::string("Comma-separated GI modes, one run per preset and mode: ") + giModeNames())
      ->capture_default_str();
  cmd->add_option("--runs", options->runsFile,
                  "JSON file of runs instead of --preset x --gi: {\"runs\": [{\"preset\": "
                  "\"mobile\", \"gi\": \"cache\"}, ...]}");
  cmd->add_option("--frames", options->frames, "Frames per run")->capture_default_str();
  cmd->add_option("--fps", options->fps, "Animation time step: frame i is at i / fps seconds")
      ->capture_default_str();
  cmd->add_option("--time-of-day", options->timeOfDay,
                  "Solar time in hours [0, 24] at the first frame (sunrise 6, sunset 18)")
      ->capture_default_str();
  cmd->add_option("--day-cycle", options->dayCycle,
                  "Seconds of animation time per 24 h (default: the run's length, frames / fps: "
                  "one whole day, night to night)");
  cmd->add_option("--window", options->window,
                  "Frames of the rolling average of the pass times (seed 000: 9)")
      ->capture_default_str();
  cmd->add_option("--contact-frames", options->contactFrames,
                  "Tone-mapped frames in the contact sheet, at even intervals along the run")
      ->capture_default_str();
  cmd->add_option("--out", options->out,
                  "Directory for bench.json and, per run, PRESET-GI-passes.png/.svg and "
                  "PRESET-GI-contact.png (created when missing)")
      ->capture_default_str();
  cmd->add_option("--compare", options->compare,
                  "Draw the runs of these bench.json files (other scenes, devices) side by side "
                  "in --out as comparison.png/.svg; runs nothing")
      ->delimiter(',');
  cmd->add_flag("--soak", options->soak,
                "Check every frame for NaN or infinite pixels and host (resident set) and device "
                "memory for growth after the warm-up; exit code 5 when a check fails");
  cmd->add_option("--soak-warmup", options->soakWarmup, "Frames before memory is compared (--soak)")
      ->capture_default_str();
  cmd->add_option("--soak-rss-growth", options->soakResidentGrowthMiB,
                  "MiB the resident set may grow after the warm-up (--soak)")
      ->capture_default_str();
  cmd->add_flag("--count-rays,!--no-count-rays", options->countRays,
                "Count every pass's rays on the GPU (rays per frame, per pixel, Grays/s in the "
                "table and bench.json); adds a barrier after each pass")
      ->capture_default_str();
  cmd->callback([&action, options, cmd] {
    options->common.given.record(*cmd);
    action = [options] { return runBench(*options); };
  });
}

}  // namespace bounce::app
