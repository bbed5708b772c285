#include "viewer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <vector>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_vulkan.h>
#include <imgui.h>
#include <imgui_stdlib.h>

#include "camera_recorder.h"
#include "core/error.h"
#include "fly_camera.h"
#include "frame/animation_player.h"
#include "frame/hybrid_frame.h"
#include "frame/presets.h"
#include "pass_time_history.h"
#include "presenter.h"
#include "rt/gpu_scene.h"
#include "scene/load.h"
#include "scene/scene_options.h"
#include "scene/time_of_day.h"
#include "suggest.h"
#include "swapchain.h"
#include "tools/image_io.h"
#include "tools/output_file.h"
#include "vk/check.h"
#include "vk/resources.h"
#include "window_device.h"

namespace bounce::view {

namespace {

constexpr float kScriptFrameSeconds = 1.0f / 60.0f;  // animation time per scripted frame
constexpr int kResizeWaitFrames = 120;               // --resize-test: frames to wait for X

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void checkImGuiResult(VkResult r) {
  if (r < 0) fail("Dear ImGui's Vulkan back end: {}", vk::resultName(r));
}

// What the panel edits; applied to the frame by Viewer::applyUi.
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
  std::optional<VkExtent2D> resizeTarget_;  // --resize-test
  int resizeWaitFrames_ = 0;
};

Viewer::Viewer(const ViewerOptions& options, Scene scene)
    : options_(options),
      window_([&] {
        WindowOptions w;
        Resolution res =
            options.common.res.empty() ? parseResolution("640x360") : options.common.resolution();
        w.width = res.width;
        w.height = res.height;
        // --device and --validate, else BOUNCE_DEVICE and BOUNCE_VALIDATE, as in `bounce`.
        vk::ContextOptions c;
        c.deviceIndex = options.common.device;
        c.validation = options.common.validate;
        c = vk::contextOptionsFromEnvironment(c);
        w.deviceIndex = c.deviceIndex;
        w.validation = c.validation;
        return w;
      }()),
      context_(window_.context()),
      swapchain_(window_.physicalDevice(), window_.device(), window_.surface()),
      presenter_(context_, swapchain_) {
  try {
    giNames_ = app::splitNames(giModeNames());
    presetNames_ = app::splitNames(presetNames());
    ui_.giMode = int(std::find(giNames_.begin(), giNames_.end(), options.gi) - giNames_.begin());
    if (!options.preset.empty())
      ui_.preset = 1 + int(std::find(presetNames_.begin(), presetNames_.end(), options.preset) -
                           presetNames_.begin());
    if (options.exposureStops) {
      ui_.autoExposure = false;
      ui_.exposureStops = *options.exposureStops;
    }
    if (options.timeOfDay) {
      ui_.timeOfDayEnabled = true;
      ui_.timeOfDay = *options.timeOfDay;
    }
    ui_.view = options.view;
    ui_.animate = options.animate;
    panelHidden_ = options.hideUi;
    ui_.renderScale = options.renderScale;
    ui_.cameraPathOut = options.cameraPathOut;
    if (!options.screenshot.empty()) ui_.screenshotPath = options.screenshot;

    recreateSwapchain();
    auto owned = std::make_unique<Scene>(std::move(scene));
    auto gpuScene = std::make_unique<GpuScene>(context_, *owned);
    useScene(std::move(owned), std::move(gpuScene), options.common.scene);
    initImGui();
    glfwSetWindowUserPointer(window_.window(), this);
    glfwSetDropCallback(window_.window(), &Viewer::onDrop);
    glfwGetCursorPos(window_.window(), &lastCursorX_, &lastCursorY_);
  } catch (...) {
    release();
    throw;
  }
}

Viewer::~Viewer() {
  release();
}

void Viewer::release() {
  VkDevice device = context_.device();
  vkDeviceWaitIdle(device);
  if (imguiReady_) {
    ImGui_ImplVulkan_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
    imguiReady_ = false;
  }
  frame_.reset();
  gpuScene_.reset();
  vkDestroyDescriptorPool(device, imguiPool_, nullptr);
  imguiPool_ = VK_NULL_HANDLE;
}

// ---- scene and frame --------------------------------------------------------------------------

HybridSettings Viewer::settingsFromUi() const {
  HybridSettings s;
  if (ui_.preset > 0) s = presetSettings(*presetFromName(presetNames_[size_t(ui_.preset - 1)]));
  int w = 0, h = 0;
  glfwGetFramebufferSize(window_.window(), &w, &h);
  s.width = std::max(1u, uint32_t(std::lround(float(std::max(w, 1)) * ui_.renderScale)));
  s.height = std::max(1u, uint32_t(std::lround(float(std::max(h, 1)) * ui_.renderScale)));
  s.gi = *giModeFromName(giNames_[size_t(ui_.giMode)]);
  s.autoExposure = ui_.autoExposure;
  s.exposureStops = ui_.exposureStops;
  if (!ui_.giDenoise) s.restirGi.temporalDenoise = s.restirGi.spatialDenoise = false;
  s.reflectionDenoise.enabled = ui_.reflectionDenoise;
  validate(s);
  return s;
}

// A scene that cannot be loaded or uploaded (a bad dropped file, one too large for the device)
// leaves the current one showing, with the message in the panel. (The command line's scene is
// loaded by runViewer, before any window.)
void Viewer::loadScene(const std::string& nameOrPath) {
  app::CommonOptions source = options_.common;
  source.camera = source.sun = source.sky = "";  // the command line's were for its scene
  source.scene = nameOrPath;
  std::unique_ptr<Scene> scene;
  std::unique_ptr<GpuScene> gpuScene;
  try {
    source.checkArguments();
    scene = std::make_unique<Scene>(source.loadScene());
    gpuScene = std::make_unique<GpuScene>(context_, *scene);
  } catch (const Error& e) {
    ui_.status = e.what();
    std::fprintf(stderr, "bounce view: %s\n", e.what());
    return;
  }
  useScene(std::move(scene), std::move(gpuScene), nameOrPath);
}

// A frame that cannot be made for the new scene ends the viewer (runViewer reports it).
void Viewer::useScene(std::unique_ptr<Scene> scene, std::unique_ptr<GpuScene> gpuScene,
                      const std::string& nameOrPath) {
  context_.waitIdle();
  player_.reset();
  frame_.reset();
  gpuScene_ = std::move(gpuScene);
  scene_ = std::move(scene);
  camera_ = FlyCamera(effectiveCamera(*scene_));
  ui_.scenePath = nameOrPath;
  ui_.status = "loaded " + scene_->name;
  createFrame();
}

void Viewer::createFrame() {
  context_.waitIdle();
  player_.reset();
  frame_.reset();
  settings_ = settingsFromUi();
  frame_ = std::make_unique<HybridFrame>(context_, *gpuScene_, *scene_, settings_);
  viewNames_ = frame_->passNames();
  for (const std::string& name : frame_->resourceNames()) viewNames_.push_back(name);
  if (std::find(viewNames_.begin(), viewNames_.end(), ui_.view) == viewNames_.end()) {
    // The command line's --view is checked as `render --view` checks it; later frames (another
    // GI mode) may lack the panel's choice, which then falls back.
    if (!frameCreated_)
      fail(
          "--view '{}': not a pass or resource of this frame{}; `bounce render --list-views` "
          "prints them",
          ui_.view, app::didYouMean(ui_.view, viewNames_));
    ui_.status = fmt::format("view '{}' is not in this frame; showing tonemap", ui_.view);
    ui_.view = "tonemap";
  }
  frameCreated_ = true;
  SceneAnimation animation = scene_->animation;
  animation.camera.reset();
  animation.timeOfDay.reset();
  player_.emplace(*scene_, std::move(animation));
  animationTime_ = 0.0;
  setView(ui_.view);
  applySun();
  history_.clear();
  rebuildPending_ = false;
}

void Viewer::applySun() {
  Sun sun = scene_->sun;
  Sky sky = scene_->sky;
  if (ui_.timeOfDayEnabled) applyTimeOfDay(ui_.timeOfDay, scene_->sun, scene_->sky, sun, sky);
  const float a = glm::radians(ui_.sunAzimuthDegrees);
  const glm::vec3 d = sun.direction;
  sun.direction = {std::cos(a) * d.x + std::sin(a) * d.z, d.y,
                   -std::sin(a) * d.x + std::cos(a) * d.z};
  frame_->setSunAndSky(sun, sky);
}

// Moves the scene's objects and lights, and the sun through the day, by dt seconds.
void Viewer::advanceAnimation(double dt) {
  if (ui_.animate) {
    animationTime_ += dt;
    player_->apply(*frame_, float(animationTime_));
  }
  if (ui_.dayCycle && ui_.timeOfDayEnabled) {
    ui_.timeOfDay = std::fmod(ui_.timeOfDay + float(dt) * ui_.hoursPerSecond, 24.0f);
    applySun();
  }
}

void Viewer::setView(const std::string& name) {
  frame_->clearDebugViews();
  frame_->requestDebugView(name);
  ui_.view = name;
}

// The chosen view as the last frame captured it; "tonemap" (always captured) where it could not
// be (a view requested after the frame was recorded).
ImageRGBA32F Viewer::shownImage() {
  if (ui_.view != "tonemap") {
    try {
      return frame_->debugViewImage(ui_.view);
    } catch (const Error&) {
    }
  }
  return frame_->debugViewImage("tonemap");
}

// ---- window and presentation ------------------------------------------------------------------

void Viewer::initImGui() {
  VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 8};
  VkDescriptorPoolCreateInfo pi{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  pi.flags = VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT;
  pi.maxSets = 8;
  pi.poolSizeCount = 1;
  pi.pPoolSizes = &size;
  VK_CHECK(vkCreateDescriptorPool(context_.device(), &pi, nullptr, &imguiPool_));

  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini in the working directory
  ImGui::StyleColorsDark();
  ImGui_ImplGlfw_InitForVulkan(window_.window(), true);
  ImGui_ImplVulkan_InitInfo info{};
  info.Instance = window_.instance();
  info.PhysicalDevice = window_.physicalDevice();
  info.Device = context_.device();
  info.QueueFamily = context_.queueFamily();
  info.Queue = context_.queue();
  info.DescriptorPool = imguiPool_;
  info.MinImageCount = swapchain_.minImageCount();
  info.ImageCount = std::max(swapchain_.imageCount(), swapchain_.minImageCount());
  info.MSAASamples = VK_SAMPLE_COUNT_1_BIT;
  info.CheckVkResultFn = &checkImGuiResult;
  ImGui_ImplVulkan_Init(&info, swapchain_.renderPass());
  imguiReady_ = true;
  context_.submitAndWait([](VkCommandBuffer cmd) { ImGui_ImplVulkan_CreateFontsTexture(cmd); });
  ImGui_ImplVulkan_DestroyFontUploadObjects();
}

// The swapchain follows the framebuffer; the render resolution follows it too (times the
// render scale), which rebuilds the frame's resolution-dependent images (HybridFrame::resize).
void Viewer::recreateSwapchain() {
  int w = 0, h = 0;
  glfwGetFramebufferSize(window_.window(), &w, &h);
  context_.waitIdle();
  if (!swapchain_.recreate(uint32_t(std::max(w, 0)), uint32_t(std::max(h, 0)))) return;
  swapchainDirty_ = false;
  ++swapchainRecreations_;
  if (imguiReady_) ImGui_ImplVulkan_SetMinImageCount(swapchain_.minImageCount());
  if (frame_) {
    HybridSettings wanted = settingsFromUi();
    if (wanted.width != settings_.width || wanted.height != settings_.height) {
      frame_->resize(wanted.width, wanted.height);
      settings_.width = wanted.width;
      settings_.height = wanted.height;
      history_.clear();
    }
  }
  std::printf("bounce view: swapchain %ux%u (%u images)", swapchain_.extent().width,
              swapchain_.extent().height, swapchain_.imageCount());
  if (frame_) std::printf(", render %ux%u", settings_.width, settings_.height);
  std::printf("\n");
}

// ---- input and UI -----------------------------------------------------------------------------

void Viewer::onDrop(GLFWwindow* window, int count, const char** paths) {
  auto* self = static_cast<Viewer*>(glfwGetWindowUserPointer(window));
  for (int i = 0; i < count; ++i)
    if (isGltfPath(paths[i])) {
      self->sceneToLoad_ = paths[i];
      return;
    }
  if (count > 0) self->ui_.status = fmt::format("'{}': not a .gltf or .glb file", paths[0]);
}

// Fly: WASD (Q/E down/up, Shift x4) and the right mouse button to look around. Orbit: the left
// button turns the camera around its pivot. The wheel zooms. Nothing reaches the camera while
// the panel has the mouse or keyboard.
void Viewer::handleInput(double dt) {
  GLFWwindow* w = window_.window();
  double x = 0.0, y = 0.0;
  glfwGetCursorPos(w, &x, &y);
  const float dx = float(x - lastCursorX_), dy = float(y - lastCursorY_);
  lastCursorX_ = x;
  lastCursorY_ = y;
  const ImGuiIO& io = ImGui::GetIO();
  if (!io.WantCaptureMouse) {
    const int button =
        camera_.mode() == CameraMode::Fly ? GLFW_MOUSE_BUTTON_RIGHT : GLFW_MOUSE_BUTTON_LEFT;
    constexpr float kRadiansPerPixel = 0.004f;
    if (glfwGetMouseButton(w, button) == GLFW_PRESS)
      camera_.turn(dx * kRadiansPerPixel, -dy * kRadiansPerPixel);
    if (io.MouseWheel != 0.0f) camera_.zoom(std::pow(0.9f, io.MouseWheel));
  }
  if (io.WantCaptureKeyboard) return;
  auto down = [&](int key) { return glfwGetKey(w, key) == GLFW_PRESS; };
  glm::vec3 move{float(down(GLFW_KEY_D)) - float(down(GLFW_KEY_A)),
                 float(down(GLFW_KEY_E)) - float(down(GLFW_KEY_Q)),
                 float(down(GLFW_KEY_W)) - float(down(GLFW_KEY_S))};
  const float speed = ui_.moveSpeed * (down(GLFW_KEY_LEFT_SHIFT) ? 4.0f : 1.0f);
  if (move != glm::vec3(0.0f)) camera_.move(move * speed * float(dt));
  if (down(GLFW_KEY_ESCAPE) && options_.frames == 0) glfwSetWindowShouldClose(w, GLFW_TRUE);
  // F1 shows or hides the panels, F12 takes a screenshot: on the key's press, not while held.
  auto pressed = [&](int key, bool& was) {
    const bool now = down(key);
    const bool edge = now && !was;
    was = now;
    return edge;
  };
  if (pressed(GLFW_KEY_F1, f1Down_)) panelHidden_ = !panelHidden_;
  if (pressed(GLFW_KEY_F12, f12Down_)) takeScreenshot(ui_.screenshotPath);
}

// Each pass a band of its own colour, stacked bottom to top in recording order, one column per
// frame (newest on the right); the legend gives the 9-frame rolling mean.
void Viewer::drawTimingGraph() {
  const size_t frames = history_.frameCount();
  const std::vector<std::string>& names = history_.passNames();
  if (frames == 0) return;
  const double top = std::max(history_.maxFrameMilliseconds(), 1e-3);
  const ImVec2 size(ImGui::GetContentRegionAvail().x, 120.0f);
  const ImVec2 origin = ImGui::GetCursorScreenPos();
  ImDrawList* draw = ImGui::GetWindowDrawList();
  draw->AddRectFilled(origin, ImVec2(origin.x + size.x, origin.y + size.y),
                      IM_COL32(20, 20, 20, 255));
  auto color = [&](size_t pass) {
    return ImU32(ImColor::HSV(std::fmod(0.61803f * float(pass), 1.0f), 0.6f, 0.9f));
  };
  const float column = size.x / float(std::max<size_t>(frames, 60));
  for (size_t f = 0; f < frames; ++f) {
    const float x0 = origin.x + size.x - float(frames - f) * column;
    float y = origin.y + size.y;
    for (size_t p = 0; p < names.size(); ++p) {
      const float h = float(history_.milliseconds(f, p) / top) * size.y;
      if (h <= 0.0f) continue;
      draw->AddRectFilled(ImVec2(x0, y - h), ImVec2(x0 + column, y), color(p));
      y -= h;
    }
  }
  ImGui::Dummy(size);
  ImGui::Text("frame %.2f ms (9-frame mean), graph top %.2f ms", history_.rollingFrameMean(), top);
  ImGui::BeginChild("legend", ImVec2(0, 12 * ImGui::GetTextLineHeightWithSpacing()));
  draw = ImGui::GetWindowDrawList();  // the child's
  for (size_t p = 0; p < names.size(); ++p) {
    const ImVec2 at = ImGui::GetCursorScreenPos();
    const float s = ImGui::GetTextLineHeight();
    draw->AddRectFilled(at, ImVec2(at.x + s, at.y + s), color(p));
    ImGui::Dummy(ImVec2(s, s));
    ImGui::SameLine();
    ImGui::Text("%-28s %7.3f ms", names[p].c_str(), history_.rollingMean(p));
  }
  ImGui::EndChild();
}

void Viewer::drawPanel() {
  ImGui::SetNextWindowPos(ImVec2(8, 8), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(380, 0), ImGuiCond_FirstUseEver);
  ImGui::Begin("bounce");
  ImGui::Text("%s on %s", scene_->name.c_str(), context_.info().name.c_str());
  ImGui::Text("render %ux%u, window %ux%u", settings_.width, settings_.height,
              swapchain_.extent().width, swapchain_.extent().height);
  if (!ui_.status.empty()) ImGui::TextWrapped("%s", ui_.status.c_str());

  if (ImGui::CollapsingHeader("Scene", ImGuiTreeNodeFlags_DefaultOpen)) {
    ImGui::InputText("##scene", &ui_.scenePath);
    ImGui::SameLine();
    if (ImGui::Button("Load")) sceneToLoad_ = ui_.scenePath;
    ImGui::TextDisabled("a built-in name or .gltf/.glb path; or drop a file on the window");
  }
  if (ImGui::CollapsingHeader("Frame", ImGuiTreeNodeFlags_DefaultOpen)) {
    auto combo = [](const char* label, int* index, const std::vector<std::string>& names) {
      bool changed = false;
      if (ImGui::BeginCombo(label, names[size_t(*index)].c_str())) {
        for (size_t i = 0; i < names.size(); ++i)
          if (ImGui::Selectable(names[i].c_str(), int(i) == *index)) {
            changed = int(i) != *index;
            *index = int(i);
          }
        ImGui::EndCombo();
      }
      return changed;
    };
    if (combo("GI mode", &ui_.giMode, giNames_)) rebuildPending_ = true;
    std::vector<std::string> presets = {"(none)"};
    presets.insert(presets.end(), presetNames_.begin(), presetNames_.end());
    if (combo("preset", &ui_.preset, presets)) rebuildPending_ = true;
    if (ImGui::Checkbox("GI denoisers", &ui_.giDenoise)) rebuildPending_ = true;
    ImGui::SameLine();
    if (ImGui::Checkbox("reflection denoiser", &ui_.reflectionDenoise)) rebuildPending_ = true;
    ImGui::SliderFloat("render scale", &ui_.renderScale, 0.25f, 1.0f, "%.2f");
    if (ImGui::IsItemDeactivatedAfterEdit()) rebuildPending_ = true;
    if (ImGui::BeginCombo("view", ui_.view.c_str())) {
      for (const std::string& name : viewNames_)
        if (ImGui::Selectable(name.c_str(), name == ui_.view)) setView(name);
      ImGui::EndCombo();
    }
  }
  ImGui::Checkbox("play the scene's animation (objects, lights)", &ui_.animate);
  if (ImGui::CollapsingHeader("Light and exposure")) {
    bool sun = ImGui::Checkbox("time of day", &ui_.timeOfDayEnabled);
    sun |= ImGui::SliderFloat("hours", &ui_.timeOfDay, 0.0f, 24.0f, "%.2f");
    ImGui::Checkbox("day cycle", &ui_.dayCycle);
    ImGui::SameLine();
    ImGui::SliderFloat("h/s", &ui_.hoursPerSecond, 0.01f, 4.0f, "%.2f",
                       ImGuiSliderFlags_Logarithmic);
    sun |= ImGui::SliderFloat("sun azimuth", &ui_.sunAzimuthDegrees, -180.0f, 180.0f, "%.0f deg");
    if (sun) applySun();
    if (ImGui::Checkbox("auto exposure", &ui_.autoExposure)) rebuildPending_ = true;
    ImGui::SliderFloat(ui_.autoExposure ? "compensation" : "exposure", &ui_.exposureStops, -12.0f,
                       12.0f, "%.1f stops");
    if (ImGui::IsItemDeactivatedAfterEdit()) rebuildPending_ = true;
  }
  if (ImGui::CollapsingHeader("Camera")) {
    int mode = int(camera_.mode());
    ImGui::RadioButton("fly (WASD, QE, right drag)", &mode, int(CameraMode::Fly));
    ImGui::RadioButton("orbit (left drag, wheel)", &mode, int(CameraMode::Orbit));
    camera_.setMode(CameraMode(mode));
    ImGui::SliderFloat("speed", &ui_.moveSpeed, 0.05f, 20.0f, "%.2f m/s",
                       ImGuiSliderFlags_Logarithmic);
    ImGui::SliderFloat("vertical fov", &camera_.verticalFovDegrees, 10.0f, 120.0f, "%.0f deg");
    ImGui::InputText("path file", &ui_.cameraPathOut);
    if (!recorder_.recording()) {
      if (ImGui::Button("Record camera path")) recorder_.start();
    } else if (ImGui::Button("Stop and save")) {
      CameraPath path = recorder_.stop();
      try {
        if (path.keys.size() < 2) fail("a camera path needs two keys at least; record longer");
        writeTextFile(ui_.cameraPathOut, cameraPathJson(path));
        ui_.status = fmt::format("{} keys -> {}", path.keys.size(), ui_.cameraPathOut);
      } catch (const Error& e) {
        ui_.status = e.what();
      }
    }
    if (recorder_.recording()) {
      ImGui::SameLine();
      ImGui::Text("%zu keys", recorder_.keyCount());
    }
  }
  ImGui::InputText("##shot", &ui_.screenshotPath);
  ImGui::SameLine();
  if (ImGui::Button("Screenshot")) takeScreenshot(ui_.screenshotPath);
  ImGui::End();

  // The timings in a window of their own, at the right edge.
  const float width = 360.0f;
  ImGui::SetNextWindowPos(
      ImVec2(std::max(8.0f, float(swapchain_.extent().width) - width - 8.0f), 8),
      ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(width, 0), ImGuiCond_FirstUseEver);
  // In a small window it would hide the frame: it starts folded there.
  ImGui::SetNextWindowCollapsed(swapchain_.extent().width < 2 * width + 24, ImGuiCond_FirstUseEver);
  ImGui::Begin("GPU time per pass");
  if (context_.info().type == "cpu")
    ImGui::TextDisabled("a CPU device: these times measure its emulation of a GPU");
  drawTimingGraph();
  ImGui::End();
}

// The shown view's values: .png as sRGB (clamped), .exr as linear floats.
void Viewer::takeScreenshot(const std::string& path) {
  try {
    requireExtension("screenshot", path, {"png", "exr"});
    writeImage(path, shown_);
    ui_.status = fmt::format("{} {}x{} -> {}", ui_.view, shown_.width, shown_.height, path);
    std::printf("bounce view: %s\n", ui_.status.c_str());
  } catch (const Error& e) {
    ui_.status = e.what();
    if (options_.frames > 0) throw;
  }
}

// --ui-test: the functions the panel's controls call, one per frame, so that CI runs them under
// validation without a mouse.
void Viewer::uiTestStep(int64_t frame, bool last) {
  auto say = [](const char* what) { std::printf("bounce view: --ui-test: %s\n", what); };
  switch (frame) {
    case 1:
      say("view shadows-trace, turn the camera");
      setView("shadows-trace");
      camera_.turn(0.1f, -0.05f);
      break;
    case 2:
      say("GI mode cache, time of day 9 h");
      ui_.giMode = int(std::find(giNames_.begin(), giNames_.end(), "cache") - giNames_.begin());
      rebuildPending_ = true;
      ui_.timeOfDayEnabled = true;
      ui_.timeOfDay = 9.0f;
      break;
    case 3: {
      say("drop a file that is not glTF (refused), record a camera path, fly forward");
      const char* paths[] = {"notes.txt"};
      onDrop(window_.window(), 1, paths);
      recorder_.start();
      camera_.move({0.0f, 0.0f, 0.2f});
      break;
    }
    case 4:
      say("load the scene sunroom, orbit");
      sceneToLoad_ = "sunroom";
      break;
    case 5:
      say("orbit, view tonemap, the scene's animation and the day cycle on");
      setView("tonemap");
      ui_.animate = true;
      ui_.dayCycle = true;
      camera_.setMode(CameraMode::Orbit);
      camera_.zoom(0.8f);  // nearer the pivot, and a small turn: still inside sunroom
      camera_.turn(0.03f, 0.0f);
      break;
    default:
      break;
  }
  if (frame >= 5) recorder_.update(float(frame), camera_.camera());  // a key per frame
  if (last && recorder_.recording()) {
    CameraPath path = recorder_.stop();
    writeTextFile(ui_.cameraPathOut, cameraPathJson(path));
    std::printf("bounce view: --ui-test: camera path of %zu keys -> %s\n", path.keys.size(),
                ui_.cameraPathOut.c_str());
  }
}

// --resize-test: after half the frames, the window grows by half; the run goes on until the
// swapchain has that size, and fails if it never comes.
void Viewer::resizeTestStep(int64_t presented, int64_t scripted) {
  if (!resizeTarget_ && presented >= std::max<int64_t>(1, scripted / 2)) {
    resizeTarget_ =
        VkExtent2D{swapchain_.extent().width * 3 / 2, swapchain_.extent().height * 3 / 2};
    std::printf("bounce view: --resize-test: resizing the window to %ux%u\n", resizeTarget_->width,
                resizeTarget_->height);
    glfwSetWindowSize(window_.window(), int(resizeTarget_->width), int(resizeTarget_->height));
  }
  if (presented >= scripted && !resizeTestDone() && ++resizeWaitFrames_ > kResizeWaitFrames)
    fail("--resize-test: the window did not reach {}x{} within {} frames (it is {}x{})",
         resizeTarget_->width, resizeTarget_->height, kResizeWaitFrames, swapchain_.extent().width,
         swapchain_.extent().height);
}

bool Viewer::resizeTestDone() const {
  return !options_.resizeTest ||
         (resizeTarget_ && swapchain_.extent().width == resizeTarget_->width &&
          swapchain_.extent().height == resizeTarget_->height);
}

int Viewer::run() {
  const auto start = std::chrono::steady_clock::now();
  auto previous = start;
  const int64_t scripted = options_.frames;
  int64_t presented = 0, rendered = 0;
  // Wall time after the first frame (pipelines, first resources): the frame's render() (with
  // its readback of the view), and the viewer's own work (conversion, upload, UI, present).
  double renderSeconds = 0.0, presentSeconds = 0.0;
  while (!glfwWindowShouldClose(window_.window())) {
    glfwPollEvents();
    int fbw = 0, fbh = 0;
    glfwGetFramebufferSize(window_.window(), &fbw, &fbh);
    if (fbw == 0 || fbh == 0) {  // minimised: nothing to present to; wait for the window
      glfwWaitEventsTimeout(0.1);
      continue;
    }
    if (swapchainDirty_ || !swapchain_.valid() || uint32_t(fbw) != swapchain_.extent().width ||
        uint32_t(fbh) != swapchain_.extent().height)
      recreateSwapchain();
    if (!swapchain_.valid()) {  // the surface has no area yet (minimising, mapping): wait
      glfwWaitEventsTimeout(0.05);
      continue;
    }
    if (options_.uiTest) uiTestStep(rendered, scripted > 0 && presented + 1 >= scripted);
    if (!sceneToLoad_.empty()) {
      std::string path = std::move(sceneToLoad_);
      sceneToLoad_.clear();
      loadScene(path);
    }
    if (rebuildPending_) createFrame();

    const double now = secondsSince(start);
    const double dt = std::min(0.1, secondsSince(previous));
    previous = std::chrono::steady_clock::now();
    handleInput(dt);
    const Camera camera = camera_.camera();
    if (!options_.uiTest) recorder_.update(float(now), camera);
    advanceAnimation(scripted > 0 ? kScriptFrameSeconds : dt);
    frame_->setTime(scripted > 0 ? double(rendered) * kScriptFrameSeconds : now);
    const auto renderStart = std::chrono::steady_clock::now();
    history_.add(frame_->render(camera));
    if (rendered > 0) renderSeconds += secondsSince(renderStart);
    ++rendered;
    shown_ = shownImage();
    const auto presentStart = std::chrono::steady_clock::now();
    presenter_.upload(shown_);

    ImGui_ImplVulkan_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    if (!panelHidden_) drawPanel();
    ImGui::Render();

    const bool last = scripted > 0 && presented + 1 >= scripted && resizeTestDone();
    const Presenter::Outcome outcome =
        presenter_.present(ImGui::GetDrawData(), last && !options_.windowScreenshot.empty());
    swapchainDirty_ = swapchainDirty_ || outcome.recreate;
    if (!outcome.presented) continue;
    if (rendered > 1) presentSeconds += secondsSince(presentStart);
    ++presented;
    if (options_.resizeTest) resizeTestStep(presented, scripted);
    if (last) {
      if (!options_.screenshot.empty()) takeScreenshot(options_.screenshot);
      if (!options_.windowScreenshot.empty())
        presenter_.writeWindowCapture(options_.windowScreenshot);
      break;
    }
  }
  const double seconds = secondsSince(start);
  std::printf(
      "bounce view: %lld frame(s) presented (%lld rendered) in %.2f s, %u swapchain "
      "creation(s)\n",
      (long long)presented, (long long)rendered, seconds, swapchainRecreations_);
  if (rendered > 1)
    std::printf(
        "bounce view: after the first frame, per frame: render %.1f ms, view upload + UI + "
        "present %.1f ms\n",
        1e3 * renderSeconds / double(rendered - 1), 1e3 * presentSeconds / double(rendered - 1));
  context_.waitIdle();
  if (window_.validationErrorCount() > 0) {
    std::fprintf(stderr, "bounce view: error: %u Vulkan validation error(s)\n",
                 window_.validationErrorCount());
    return app::kValidationFailedExit;
  }
  return 0;
}

}  // namespace

int runViewer(const ViewerOptions& options) {
  options.common.checkArguments();
  app::requireOneOf("--gi", options.gi, app::splitNames(giModeNames()));
  if (!options.preset.empty())
    app::requireOneOf("--preset", options.preset, app::splitNames(presetNames()));
  if (!(options.renderScale >= 0.25f && options.renderScale <= 1.0f))
    fail("--render-scale {}: expected 0.25 to 1", options.renderScale);
  if (options.frames < 0) fail("--frames {}: expected 0 (until closed) or more", options.frames);
  if (options.uiTest && options.frames < 8)
    fail("--ui-test needs --frames 8 or more (one panel action per frame)");
  if (options.resizeTest && options.frames < 2)
    fail("--resize-test needs --frames 2 or more (it resizes half-way)");
  if (!options.screenshot.empty()) {
    requireExtension("--screenshot", options.screenshot, {"png", "exr"});
    requireWritableFile("--screenshot", options.screenshot);
  }
  if (!options.windowScreenshot.empty()) {
    requireExtension("--window-screenshot", options.windowScreenshot, {"png"});
    requireWritableFile("--window-screenshot", options.windowScreenshot);
  }
  Scene scene = options.common.loadScene();  // a bad scene fails before any window opens
  try {
    Viewer viewer(options, std::move(scene));
    return viewer.run();
  } catch (const Error& e) {
    if (std::strstr(e.what(), "VK_ERROR_DEVICE_LOST"))
      fail(
          "the Vulkan device was lost (a driver reset, a GPU hang or a removed GPU): {}; the "
          "viewer cannot go on",
          e.what());
    if (std::strstr(e.what(), "VK_ERROR_SURFACE_LOST_KHR"))
      fail("the window's surface was lost: {}", e.what());
    throw;
  }
}

}  // namespace bounce::view
