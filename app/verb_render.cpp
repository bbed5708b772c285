// bounce render: renders a scene headless with the real-time hybrid frame (vbuffer, gbuffer,
// shadows, sky, composite, tonemap; DESIGN.md §4) for --frames frames and writes the final
// frame, or every frame, as images; --view shows any pass's debug view instead, and the
// ray-cast views primary-albedo|normal|depth|instance|geometry remain for checking a scene.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>

#include <fmt/format.h>

#include "common_options.h"
#include "core/error.h"
#include "passes/primary_view.h"
#include "render/gpu_scene.h"
#include "render/hybrid_frame.h"
#include "render/settings.h"
#include "tools/image_io.h"
#include "verbs.h"

namespace bounce::app {

namespace {

constexpr const char* kDefaultResolution = "640x360";

struct RenderOptions {
  CommonOptions common;
  std::string view = "tonemap";
  std::string out = "out/render.png";
  uint32_t frames = 8;
  std::string gi = "none";
  std::string preset;
  std::string timings;
  float exposure = HybridSettings{}.exposure;
  float skyAmbient = HybridSettings{}.skyAmbientStrength;
  uint32_t shadowDivisor = 0;  // 0: the preset's
  bool lambert = false;
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
  if (!(options.exposure > 0.0f)) fail("--exposure {}: must be positive", options.exposure);
  settings.exposure = options.exposure;
  if (!(options.skyAmbient >= 0.0f)) fail("--sky-ambient {}: must be >= 0", options.skyAmbient);
  settings.skyAmbientStrength = options.skyAmbient;
  if (options.shadowDivisor > 8)
    fail("--shadow-divisor {}: expected 1 .. 8", options.shadowDivisor);
  if (options.shadowDivisor != 0) settings.shadowDivisor = options.shadowDivisor;
  settings.lambert = options.lambert;
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

void writeTimingsJson(const std::string& path, const std::vector<TimingRow>& rows,
                      const std::string& sceneName, const HybridSettings& settings,
                      const std::string& device) {
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
  f << "  ]\n}\n";
}

int renderHybridFrame(const RenderOptions& options) {
  if (options.frames == 0) fail("--frames 0: render at least one frame");
  HybridSettings settings = settingsFrom(options);
  Scene scene = options.common.loadScene();
  std::unique_ptr<vk::Context> context = options.common.createContext();
  GpuScene gpuScene(*context, scene);
  HybridFrame frame(*context, gpuScene, scene, settings);
  frame.requestDebugView(options.view);
  Camera camera = effectiveCamera(scene);
  bool everyFrame = outIsDirectory(options.out);
  if (everyFrame) std::filesystem::create_directories(options.out);

  std::vector<TimingRow> timings;
  for (uint32_t i = 0; i < options.frames; ++i) {
    for (vk::PassTiming& t : frame.render(camera)) timings.push_back({i, std::move(t)});
    if (everyFrame) writeImage(frameImagePath(options.out, i), frame.debugViewImage(options.view));
  }
  if (!everyFrame) {
    createParentDirectory(options.out);
    writeImage(options.out, frame.debugViewImage(options.view));
  }
  if (!options.timings.empty())
    writeTimingsJson(options.timings, timings, scene.name, settings, context->info().name);
  std::printf("%s: %s %ux%u, %u frame(s) on %s -> %s\n", scene.name.c_str(), options.view.c_str(),
              settings.width, settings.height, options.frames, context->info().name.c_str(),
              options.out.c_str());
  for (const TimingRow& t : timings)
    if (t.frame + 1 == options.frames)
      std::printf("  %-24s %8.3f ms\n", t.pass.name.c_str(), t.pass.milliseconds);
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
  cmd->add_option("--gi", options->gi, std::string("Diffuse GI mode: ") + giModeNames())
      ->capture_default_str();
  cmd->add_option("--view", options->view,
                  std::string("What to write: a pass of the frame (scene-update, vbuffer, gbuffer, "
                              "shadows-trace, shadows-denoise, sky, composite, tonemap) or a "
                              "resource (gbuffer.normals, ...), or a ray-cast view: ") +
                      primaryViewNames())
      ->capture_default_str();
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
  cmd->add_flag("--lambert", options->lambert, "Shade every material as pure Lambert");
  cmd->callback([&action, options] { action = [options] { return runRender(*options); }; });
}

}  // namespace bounce::app
