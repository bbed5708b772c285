// bounce-view: the viewer's own program, run as `bounce view ...` (app/verb_view.cpp forwards
// there) or directly. It is a program of its own so that `bounce`, which runs headless on
// machines without X or GLFW, links no window-system library. Exit codes as `bounce`'s
// (docs/cli.md): usage errors and bad input 1, internal errors 3, validation errors 4.
#include <cstdio>
#include <exception>

#include <CLI/CLI.hpp>

#include "core/error.h"
#include "frame/frame_settings.h"
#include "frame/presets.h"
#include "viewer.h"

namespace {

constexpr int kUsageExit = 1;
constexpr int kInternalErrorExit = 3;

void addOptions(CLI::App& app, bounce::view::ViewerOptions& o) {
  o.common.addSceneOptions(app, "sunroom");
  o.common.addResolution(app, "640x360");
  app.get_option("--res")->description(
      "Window size WxH; the render resolution follows the window (times the panel's render "
      "scale)");
  o.common.addDeviceOptions(app);
  app.add_option("--preset", o.preset,
                 std::string("Settings preset: ") + bounce::presetNames() +
                     " (its choices, not its size: the window sets the size)");
  app.add_option("--gi", o.gi, std::string("Diffuse GI mode: ") + bounce::giModeNames())
      ->capture_default_str();
  app.add_option("--view", o.view,
                 "The pass or resource shown (as `bounce render --view`; the panel lists them)")
      ->capture_default_str();
  app.add_option("--frames", o.frames,
                 "Present N frames, write the screenshots and exit 0 (0: run until the window "
                 "is closed or Esc)")
      ->capture_default_str();
  app.add_option("--screenshot", o.screenshot,
                 "With --frames: write the shown view of the last frame (.png sRGB, .exr linear "
                 "floats); also the panel's screenshot file");
  app.add_option("--window-screenshot", o.windowScreenshot,
                 "With --frames: write the last presented window, panel included (.png)");
  app.add_option("--camera-path-out", o.cameraPathOut,
                 "Where the panel's camera recording is written (the JSON --camera-path reads)")
      ->capture_default_str();
  app.add_option("--exposure", o.exposureStops, "Fixed exposure in stops (default: automatic)");
  app.add_option("--time-of-day", o.timeOfDay, "Solar time in hours [0, 24] for the sun");
  app.add_flag("--resize-test", o.resizeTest,
               "With --frames: grow the window by half after half the frames and check that "
               "the swapchain and the render resolution follow (for CI)");
  app.add_flag("--ui-test", o.uiTest,
               "With --frames 8 or more: do what the panel does, one action per frame (for CI; "
               "docs/cli.md lists them)");
  app.add_flag("--animate", o.animate,
               "Play the scene's moving objects and lights (the panel's checkbox); the camera "
               "stays yours");
  app.add_flag("--hide-ui", o.hideUi, "No panel over the image");
  app.add_option("--render-scale", o.renderScale,
                 "Render resolution / window size, 0.25 to 1 (the panel's render scale)")
      ->capture_default_str();
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"bounce view: the real-time frame in a window, with a panel to change it",
               "bounce view"};
  bounce::view::ViewerOptions options;
  addOptions(app, options);
  try {
    app.parse(argc, argv);
    for (const CLI::Option* option : app.get_options())
      if (option->count() > 0) options.common.given.names.insert(option->get_name());
  } catch (const CLI::Success& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "bounce: error: view: %s\n", e.what());
    return kUsageExit;
  }
  try {
    return bounce::view::runViewer(options);
  } catch (const bounce::Error& e) {
    std::fprintf(stderr, "bounce: error: view: %s\n", e.what());
    return kUsageExit;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bounce: internal error: view: %s\n", e.what());
    return kInternalErrorExit;
  }
}
