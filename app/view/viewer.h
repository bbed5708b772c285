// bounce view: the real-time frame in a window (GLFW), with a Dear ImGui panel to change it
// while it runs. Each loop: input -> camera, HybridFrame::render, the chosen view read back and
// uploaded, blitted into the acquired swapchain image (letterboxed), the UI drawn over it,
// presented. --frames N makes it a script: N presented frames, the screenshots, exit.
#pragma once
#include <cstdint>
#include <optional>
#include <string>

#include "common_options.h"

namespace bounce::view {

struct ViewerOptions {
  app::CommonOptions common;  // --scene, --camera, --sun, --sky, --res, --device, --validate
  std::string preset;         // empty: the --res size with the frame's defaults
  std::string gi = "evolve";
  std::string view = "tonemap";  // any pass or resource of the frame (bounce render --view)
  int64_t frames = 0;            // 0: run until the window is closed
  std::string screenshot;        // the shown image at the end (.png sRGB, .exr linear)
  std::string windowScreenshot;  // the window as presented, UI included (.png)
  std::string cameraPathOut = "camera_path.json";  // where "record camera path" writes
  bool resizeTest = false;  // script: grow the window by half mid-run, check the swapchain follows
  // script: the panel's actions in turn, one per frame (a view, GI mode, the sun, a refused
  // drop, a scene load, camera moves, a recorded camera path written to cameraPathOut)
  bool uiTest = false;
  bool hideUi = false;
  bool animate = false;                // play the scene's object and light animation from the start
  float renderScale = 1.0f;            // render resolution / window size, in [0.25, 1]
  std::optional<float> exposureStops;  // fixed exposure; else automatic
  std::optional<float> timeOfDay;      // hours; else the scene's sun
};

// Checks the options (usage errors before any window opens), then runs. Returns the exit code.
int runViewer(const ViewerOptions& options);

}  // namespace bounce::view
