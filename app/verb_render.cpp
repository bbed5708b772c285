// bounce render: renders a scene headless to an image. For now the ray-cast primary views
// (--view primary-albedo|primary-normal|primary-depth|primary-instance|primary-geometry).
#include <cstdio>
#include <filesystem>
#include <memory>

#include "common_options.h"
#include "core/error.h"
#include "passes/primary_view.h"
#include "render/gpu_scene.h"
#include "tools/image_io.h"
#include "verbs.h"

namespace bounce::app {

namespace {

struct RenderOptions {
  CommonOptions common;
  std::string view = "primary-albedo";
  std::string out = "out/render.png";
};

int runRender(const RenderOptions& options) {
  std::optional<PrimaryViewKind> view = primaryViewFromName(options.view);
  if (!view) fail("--view '{}': expected one of {}", options.view, primaryViewNames());
  Resolution res = options.common.resolution();
  Scene scene = options.common.loadScene();
  std::unique_ptr<vk::Context> context = options.common.createContext();
  GpuScene gpuScene(*context, scene);
  PrimaryViewPass pass(*context, gpuScene);
  vk::GpuTimer timer(*context);
  ImageRGBA32F image = pass.render(effectiveCamera(scene), res.width, res.height, *view, &timer);
  std::filesystem::path outPath(options.out);
  if (outPath.has_parent_path()) std::filesystem::create_directories(outPath.parent_path());
  writeImage(options.out, image);
  double ms = timer.available() ? timer.read().at(0).milliseconds : 0.0;
  std::printf("%s: %s %ux%u on %s: primary-view %.3f ms -> %s\n", scene.name.c_str(),
              options.view.c_str(), res.width, res.height, context->info().name.c_str(), ms,
              options.out.c_str());
  return exitCodeFor(*context);
}

}  // namespace

void addRenderVerb(CLI::App& app, VerbAction& action) {
  auto options = std::make_shared<RenderOptions>();
  CLI::App* cmd = app.add_subcommand("render", "Render a scene headless to an image");
  options->common.addSceneOptions(*cmd, "sunroom");
  options->common.addResolution(*cmd, "640x360");
  options->common.addDeviceOptions(*cmd);
  cmd->add_option("--view", options->view, std::string("Debug view: ") + primaryViewNames())
      ->capture_default_str();
  cmd->add_option("--out", options->out, "Output image (.png sRGB, .exr linear)")->capture_default_str();
  cmd->callback([&action, options] { action = [options] { return runRender(*options); }; });
}

}  // namespace bounce::app
