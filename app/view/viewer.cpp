#include "viewer_app.h"

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

}  // namespace

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
    auto gpuScene = std::make_unique<GpuScene>(context_, *owned, options.common.gpuSceneOptions());
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
  markChange();
  app::CommonOptions source = options_.common;
  source.camera = source.sun = source.sky = "";  // the command line's were for its scene
  source.scene = nameOrPath;
  std::unique_ptr<Scene> scene;
  std::unique_ptr<GpuScene> gpuScene;
  try {
    source.checkArguments();
    scene = std::make_unique<Scene>(source.loadScene());
    gpuScene = std::make_unique<GpuScene>(context_, *scene, source.gpuSceneOptions());
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
  markChange();
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
  markChange();
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
  markChange();
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
  int64_t steadyFrames = 0;
  uint64_t steadyAllocations = 0;
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
    frameIndex_ = rendered;
    const uint64_t allocationsBefore = context_.allocationCount();
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
    if (presenter_.upload(shown_)) markChange();

    ImGui_ImplVulkan_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    if (!panelHidden_) drawPanel();
    ImGui::Render();

    const bool last = scripted > 0 && presented + 1 >= scripted && resizeTestDone();
    if (last && !options_.windowScreenshot.empty()) markChange();  // its readback buffer
    const Presenter::Outcome outcome =
        presenter_.present(ImGui::GetDrawData(), last && !options_.windowScreenshot.empty());
    swapchainDirty_ = swapchainDirty_ || outcome.recreate;
    if (frameIndex_ >= lastChange_ + 2) {
      ++steadyFrames;
      steadyAllocations += context_.allocationCount() - allocationsBefore;
    }
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
  std::printf("bounce view: %llu GPU allocation(s) in %lld steady frame(s)\n",
              (unsigned long long)steadyAllocations, (long long)steadyFrames);
  context_.waitIdle();
  if (window_.validationErrorCount() > 0) {
    std::fprintf(stderr, "bounce view: error: %u Vulkan validation error(s)\n",
                 window_.validationErrorCount());
    return app::kValidationFailedExit;
  }
  return 0;
}

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
