#include <algorithm>
#include <cmath>
#include <cstdio>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_stdlib.h>

#include "core/error.h"
#include "scene/load.h"
#include "tools/image_io.h"
#include "tools/output_file.h"
#include "viewer_app.h"

namespace bounce::view {

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

}  // namespace bounce::view
