// The viewer's state between its files: viewer.cpp (scene, frame, window, the loop) and
// viewer_panel.cpp (input, the panels, the scripted --ui-test). Internal to bounce-view.
#pragma once
#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "camera_recorder.h"
#include "fly_camera.h"
#include "frame/animation_player.h"
#include "frame/hybrid_frame.h"
#include "pass_time_history.h"
#include "presenter.h"
#include "rt/gpu_scene.h"
#include "swapchain.h"
#include "viewer.h"
#include "window_device.h"

struct GLFWwindow;

namespace bounce::view {

// What the panel edits; the viewer applies it to the frame.
struct UiState {
  std::string scenePath;
  int giMode = 1;  // index into giNames
  int preset = 0;  // 0: none (the frame's defaults), else 1 + index into presetNames
  bool giDenoise = true;
  bool reflectionDenoise = true;
  float renderScale = 1.0f;
  bool autoExposure = true;
  float exposureStops = 0.0f;
  bool timeOfDayEnabled = false;
  float timeOfDay = 12.0f;
  bool dayCycle = false;        // the hours advance while the viewer runs
  float hoursPerSecond = 0.5f;  // of wall time (a day in 48 s)
  bool animate = false;         // the scene's moving objects and lights
  float sunAzimuthDegrees = 0.0f;
  float moveSpeed = 1.0f;  // metres per second
  std::string view = "tonemap";
  std::string screenshotPath = "screenshot.png";
  std::string cameraPathOut;
  std::string status;
};

// One window on one scene's frame. run() loops (events, camera, frame, view, panels, present)
// until the window closes or a script's --frames are done; see viewer.h.
class Viewer {
 public:
  Viewer(const ViewerOptions& options, Scene scene);
  ~Viewer();
  int run();

 private:
  // Scene and frame.
  HybridSettings settingsFromUi() const;
  void loadScene(const std::string& nameOrPath);
  void useScene(std::unique_ptr<Scene> scene, std::unique_ptr<GpuScene> gpuScene,
                const std::string& nameOrPath);
  void release();  // everything the constructor made, in reverse order
  void createFrame();
  void applySun();
  void setView(const std::string& name);
  void advanceAnimation(double dt);
  ImageRGBA32F shownImage();
  // Window and presentation.
  void initImGui();
  void recreateSwapchain();
  // Input and UI.
  void handleInput(double dt);
  void drawPanel();
  void drawTimingGraph();
  void takeScreenshot(const std::string& path);
  void uiTestStep(int64_t frame, bool last);
  void resizeTestStep(int64_t presented, int64_t scripted);
  bool resizeTestDone() const;
  static void onDrop(GLFWwindow* window, int count, const char** paths);

  ViewerOptions options_;
  WindowDevice window_;
  vk::Context& context_;
  Swapchain swapchain_;
  bool swapchainDirty_ = true;

  // On the heap: the frame and the GPU scene hold on to its address while a new one loads.
  std::unique_ptr<Scene> scene_;
  std::unique_ptr<GpuScene> gpuScene_;
  std::unique_ptr<HybridFrame> frame_;
  // The scene's object and light animation (its camera path and time of day left out: the
  // camera and the sun are the panel's), played while ui_.animate is on.
  std::optional<AnimationPlayer> player_;
  double animationTime_ = 0.0;
  HybridSettings settings_;
  std::vector<std::string> viewNames_;
  bool rebuildPending_ = false;
  bool frameCreated_ = false;  // after the first createFrame()
  std::string sceneToLoad_;

  FlyCamera camera_;
  CameraRecorder recorder_;
  PassTimeHistory history_;
  UiState ui_;
  std::vector<std::string> giNames_, presetNames_;
  ImageRGBA32F shown_;  // the last view image shown

  Presenter presenter_;
  VkDescriptorPool imguiPool_ = VK_NULL_HANDLE;
  bool imguiReady_ = false;

  double lastCursorX_ = 0.0, lastCursorY_ = 0.0;
  bool f1Down_ = false, f12Down_ = false;
  bool panelHidden_ = false;  // --hide-ui, or F1
  uint32_t swapchainRecreations_ = 0;
  // DESIGN.md §1, no GPU allocation per frame: frames at least two after the last change
  // (a new frame, view, swapchain, display size, a window capture: each may allocate, and a
  // frame's first render makes its resources) are steady, and their allocations are counted.
  void markChange() { lastChange_ = frameIndex_; }
  int64_t frameIndex_ = 0;
  int64_t lastChange_ = 0;
  std::optional<VkExtent2D> resizeTarget_;  // --resize-test
  int resizeWaitFrames_ = 0;
};

}  // namespace bounce::view
