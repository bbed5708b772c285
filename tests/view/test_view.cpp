// The viewer (app/view/, `bounce view`): its camera, camera-path recording and timing history
// as units, and the program itself in a window under a virtual X server (xvfb-run): frames
// presented through a swapchain, a resize that the swapchain and the render resolution follow,
// screenshots that are not blank, validation silent, exit code 0.
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <regex>

#include <gtest/gtest.h>

#include "camera_recorder.h"
#include "fly_camera.h"
#include "harness.h"
#include "pass_time_history.h"
#include "scene/animation.h"
#include "tools/image_io.h"

namespace bounce::view {
namespace {

Camera cameraAt(glm::vec3 position, glm::vec3 target) {
  Camera c;
  c.position = position;
  c.target = target;
  c.verticalFovDegrees = 40.0f;
  return c;
}

void expectNear(glm::vec3 a, glm::vec3 b, float tolerance = 1e-4f) {
  EXPECT_NEAR(a.x, b.x, tolerance);
  EXPECT_NEAR(a.y, b.y, tolerance);
  EXPECT_NEAR(a.z, b.z, tolerance);
}

TEST(FlyCamera, StartsWhereTheSceneCameraIs) {
  const Camera start = cameraAt({1, 2, 3}, {0, 1, -2});
  const Camera c = FlyCamera(start).camera();
  expectNear(c.position, start.position);
  expectNear(c.target, start.target);
  EXPECT_FLOAT_EQ(c.verticalFovDegrees, 40.0f);
}

TEST(FlyCamera, MovesAlongTheViewAndTurnsAboutItself) {
  FlyCamera fly(cameraAt({0, 0, 0}, {0, 0, -4}));
  fly.move({0, 0, 2});  // forward 2 m
  expectNear(fly.camera().position, {0, 0, -2});
  fly.move({1, 0, 0});  // right: +X when looking down -Z
  expectNear(fly.camera().position, {1, 0, -2});
  fly.turn(glm::radians(90.0f), 0.0f);  // now looking towards +X, from the same place
  expectNear(fly.camera().position, {1, 0, -2});
  expectNear(fly.forward(), {1, 0, 0});
  fly.turn(0.0f, glm::radians(120.0f));  // pitch stops short of the pole
  EXPECT_LT(fly.forward().y, 1.0f);
  EXPECT_GT(fly.forward().y, 0.999f);
}

TEST(FlyCamera, OrbitKeepsThePivotAndItsDistance) {
  FlyCamera orbit(cameraAt({0, 0, 5}, {0, 0, 0}));
  orbit.setMode(CameraMode::Orbit);
  orbit.turn(glm::radians(90.0f), glm::radians(30.0f));
  const Camera c = orbit.camera();
  expectNear(c.target, {0, 0, 0});
  EXPECT_NEAR(glm::length(c.position), 5.0f, 1e-4f);
  // The view tilts up by 30 degrees: the camera sinks below the pivot, looking up at it.
  EXPECT_NEAR(c.position.y, -5.0f * std::sin(glm::radians(30.0f)), 1e-4f);
  orbit.zoom(0.5f);
  EXPECT_NEAR(glm::length(orbit.camera().position), 2.5f, 1e-4f);
  expectNear(orbit.camera().target, {0, 0, 0});
}

// The recording is read back by the same parser `bounce render --camera-path` uses.
TEST(CameraRecorder, WritesThePathTheRendererReads) {
  CameraRecorder recorder(0.5f);
  recorder.start();
  recorder.update(0.0f, cameraAt({0, 1, 5}, {0, 1, 0}));
  recorder.update(0.2f, cameraAt({9, 9, 9}, {0, 0, 0}));  // within the interval: skipped
  recorder.update(0.6f, cameraAt({1, 1, 5}, {0, 1, 0}));
  recorder.update(1.2f, cameraAt({2, 1, 4}, {0, 1, 0}));
  const CameraPath recorded = recorder.stop();
  ASSERT_EQ(recorded.keys.size(), 3u);
  const CameraPath read = parseCameraPathJson(cameraPathJson(recorded), "recorded.json");
  ASSERT_EQ(read.keys.size(), 3u);
  EXPECT_FALSE(read.loop);
  EXPECT_TRUE(read.catmullRom);
  for (size_t i = 0; i < 3; ++i) {
    EXPECT_FLOAT_EQ(read.keys[i].time, recorded.keys[i].time);
    expectNear(read.keys[i].position, recorded.keys[i].position);
    expectNear(read.keys[i].target, recorded.keys[i].target);
    EXPECT_FLOAT_EQ(read.keys[i].verticalFovDegrees, 40.0f);
  }
}

TEST(PassTimeHistory, RollingMeanOverNineFramesWithoutImageCopies) {
  PassTimeHistory history(240);
  for (int f = 0; f < 20; ++f)
    history.add({{"vbuffer", double(f)}, {"tonemap", 1.0}, {"debug-view:tonemap", 5.0}});
  ASSERT_EQ(history.passNames().size(), 2u);
  EXPECT_EQ(history.passNames()[0], "vbuffer");
  EXPECT_DOUBLE_EQ(history.rollingMean(0), (11 + 19) / 2.0);  // frames 11..19
  EXPECT_DOUBLE_EQ(history.rollingMean(1), 1.0);
  EXPECT_DOUBLE_EQ(history.frameMilliseconds(19), 20.0);
  EXPECT_DOUBLE_EQ(history.maxFrameMilliseconds(), 20.0);
  history.add({{"composite", 2.0}});  // a new pass; older frames read 0 for it
  EXPECT_DOUBLE_EQ(history.milliseconds(0, 2), 0.0);
  EXPECT_DOUBLE_EQ(history.milliseconds(20, 2), 2.0);
}

// Standard deviation of Rec. 709 luminance over the pixels: 0 for a blank (uniform) image.
double luminanceSpread(const ImageRGBA32F& image) {
  const double mean = test::meanLuminance(image);
  double sum = 0.0;
  for (size_t i = 0; i < image.pixelCount(); ++i) {
    const float* p = &image.pixels[4 * i];
    const double l = 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
    sum += (l - mean) * (l - mean);
  }
  return std::sqrt(sum / double(image.pixelCount()));
}

// xvfb-run needs xauth for its server's cookie.
bool haveXvfb() {
  return std::system("command -v xvfb-run >/dev/null 2>&1 && command -v xauth >/dev/null 2>&1") ==
         0;
}

TEST(ViewerProgram, HelpListsTheScriptOptions) {
  const test::CommandResult r = test::runCommand(test::bounceExe() + " view --help");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("--screenshot"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("--resize-test"), std::string::npos) << r.output;
}

// `bounce` without bounce-view beside it (a build without GLFW or ImGui): one clear line, exit 1.
TEST(ViewerProgram, MissingViewerIsAClearError) {
  const std::string dir = test::tempDir("viewer-missing");
  std::filesystem::copy_file(test::bounceExe(), dir + "/bounce");
  std::filesystem::permissions(dir + "/bounce", std::filesystem::perms::owner_exec,
                               std::filesystem::perm_options::add);
  const test::CommandResult r = test::runCommand(dir + "/bounce view --scene cornell");
  EXPECT_EQ(r.exitCode, 1) << r.output;
  EXPECT_NE(r.output.find("bounce: error: view: the viewer is not built"), std::string::npos)
      << r.output;
}

// CI's check (issue 24): the viewer opens on a virtual X server, presents frames, follows a
// resize, writes its screenshots and exits 0 with validation on; steady frames allocate nothing.
TEST(ViewerProgram, NoDisplayIsAClearError) {
  const test::CommandResult r = test::runCommand("env -u DISPLAY -u WAYLAND_DISPLAY " +
                                                 test::bounceExe() + " view --scene cornell");
  EXPECT_EQ(r.exitCode, 1) << r.output;
  EXPECT_NE(r.output.find("bounce: error: view: cannot open a window"), std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("xvfb-run"), std::string::npos) << r.output;
}

// Each xvfb test starts its search for a free display at its own number (-a -n): two started at
// once by `ctest -j` would otherwise both try :99.
TEST(ViewerProgram, PresentsResizesAndScreenshotsUnderXvfb) {
  if (!haveXvfb())
    GTEST_SKIP() << "xvfb-run or xauth is not installed (apt-get install xvfb xauth)";
  const std::string dir = test::tempDir("viewer");
  const std::string shot = dir + "/shot.png", window = dir + "/window.png";
  const test::CommandResult r = test::runCommand(
      "xvfb-run -a -n 101 -s '-screen 0 1024x768x24' " + test::bounceExe() +
          " view --scene cornell --res 96x64 --frames 8 --resize-test --validate --screenshot " +
          shot + " --window-screenshot " + window,
      120);
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_EQ(r.output.find("validation"), std::string::npos) << r.output;
  // No GPU memory allocated in the frames without a change (DESIGN.md §1): frames 2 and 3
  // before the resize, and 6 when X has resized the window by frame 4 (the last, with the
  // window capture, is a change).
  std::smatch steady;
  ASSERT_TRUE(std::regex_search(r.output, steady,
                                std::regex(R"((\d+) GPU allocation\(s\) in (\d+) steady frame)")))
      << r.output;
  EXPECT_EQ(std::stoi(steady[1]), 0) << r.output;
  EXPECT_GE(std::stoi(steady[2]), 2) << r.output;
  // The window grew by half: the swapchain was recreated and the frame rendered at its size.
  EXPECT_NE(r.output.find("swapchain 144x96"), std::string::npos) << r.output;
  const ImageRGBA32F image = readImage(shot);
  EXPECT_EQ(image.width, 144);
  EXPECT_EQ(image.height, 96);
  const double mean = test::meanLuminance(image);
  EXPECT_GT(mean, 0.02) << "the frame is black";
  EXPECT_LT(mean, 0.98) << "the frame is white";
  EXPECT_GT(luminanceSpread(image), 0.02) << "the frame is blank";
  const ImageRGBA32F presented = readImage(window);
  EXPECT_EQ(presented.width, 144);
  EXPECT_EQ(presented.height, 96);
  EXPECT_GT(luminanceSpread(presented), 0.02) << "the window is blank";
}

// The panel's actions (a debug view, a GI mode change that rebuilds the frame, the sun, a refused
// drop, a scene load, fly and orbit moves, a recorded camera path) under validation: exit 0,
// and the path file is one `bounce render --camera-path` accepts.
TEST(ViewerProgram, PanelActionsRunCleanUnderXvfb) {
  if (!haveXvfb())
    GTEST_SKIP() << "xvfb-run or xauth is not installed (apt-get install xvfb xauth)";
  const std::string dir = test::tempDir("viewer-ui");
  const std::string path = dir + "/path.json", shot = dir + "/shot.png";
  const test::CommandResult r = test::runCommand(
      "xvfb-run -a -n 121 -s '-screen 0 1024x768x24' " + test::bounceExe() +
          " view --scene cornell --res 64x48 --frames 8 --ui-test --validate --camera-path-out " +
          path + " --screenshot " + shot,
      120);
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_EQ(r.output.find("validation"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("camera path of 3 keys"), std::string::npos) << r.output;
  const CameraPath read = loadCameraPath(path);
  ASSERT_EQ(read.keys.size(), 3u);
  validateCameraPath(read, path);
  // The last frames show sunroom's tone-mapped frame in the cache GI mode: not blank.
  EXPECT_GT(luminanceSpread(readImage(shot)), 0.02) << r.output;
}

}  // namespace
}  // namespace bounce::view
