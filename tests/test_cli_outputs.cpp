// The `bounce` program's outputs: checked writable before any work, every write checked, JSON
// that stays valid whatever the paths hold, Ctrl-C that keeps a reference render, and the
// progress line on terminals only.
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "harness.h"
#include "tools/image_io.h"

namespace bounce {
namespace {

namespace fs = std::filesystem;
using test::bounceExe;
using test::runCommand;

std::string quoted(const std::string& s) {
  return "'" + s + "'";
}

std::string readText(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  std::stringstream text;
  text << file.rdbuf();
  return text.str();
}

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// A path whose parent is a regular file: unwritable for every user, root included.
std::string unwritablePath(const std::string& dir, const std::string& name) {
  std::ofstream(dir + "/plain-file") << "x";
  return dir + "/plain-file/" + name;
}

// A reference render of hours on lavapipe (640x360, 100000 spp) with an unwritable --out must
// fail at once, naming --out; so must every other verb's outputs. 20 s is far below the
// render's time and far above the program's start-up, even on a loaded machine.
TEST(CliOutputs, UnwritableOutputsFailBeforeAnyWork) {
  const std::string dir = test::tempDir("cli-unwritable");
  const std::string image = test::sharedDir() + "/references/cornell_box/cycles_16spp.png";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"reference --res 640x360 --spp 100000 --out " + unwritablePath(dir, "r.exr"), "--out"},
      {"render --frames 1000 --out " + unwritablePath(dir, "r.png"), "--out"},
      {"render --frames 1000 --out " + unwritablePath(dir, "frames/"), "--out"},
      {"render --frames 1000 --out " + dir + "/ok.png --timings " + unwritablePath(dir, "t.json"),
       "--timings"},
      {"bench-rays --json " + unwritablePath(dir, "b.json"), "--json"},
      {"compare " + image + " " + image + " --json " + unwritablePath(dir, "c.json"), "--json"},
      {"compare " + image + " " + image + " --heatmap " + unwritablePath(dir, "h.png"),
       "--heatmap"},
      {"compare " + image + " " + image + " --side-by-side " + unwritablePath(dir, "s.png"),
       "--side-by-side"},
      {"render --out " + dir, "is a directory"},
  };
  for (const auto& [args, option] : cases) {
    const auto start = std::chrono::steady_clock::now();
    test::CommandResult r = runCommand(bounceExe() + " " + args, 60);
    EXPECT_LT(secondsSince(start), 20.0) << args;
    EXPECT_EQ(r.exitCode, 1) << args << "\n" << r.output;
    EXPECT_EQ(r.output.rfind("bounce: error: ", 0), 0u) << args << "\n" << r.output;
    EXPECT_NE(r.output.find(option), std::string::npos) << args << "\n" << r.output;
    EXPECT_EQ(r.output.find("internal error"), std::string::npos) << r.output;
  }
  EXPECT_FALSE(fs::exists(dir + "/ok.png")) << "the --out probe must not leave a file behind";
}

// A missing parent directory is created; a failed run leaves no output file behind.
TEST(CliOutputs, MissingDirectoriesAreCreatedAndFailedRunsLeaveNoFile) {
  const std::string dir = test::tempDir("cli-dirs");
  const std::string out = dir + "/new/deeper/view.png";
  test::CommandResult r = runCommand(bounceExe() +
                                     " render --scene cornell --view primary-albedo --res 8x8 "
                                     "--out " +
                                     out);
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_EQ(readImage(out).width, 8);
  r = runCommand(bounceExe() + " render --scene " + dir + "/missing.gltf --out " + dir +
                 "/never.png");
  EXPECT_EQ(r.exitCode, 1) << r.output;
  EXPECT_FALSE(fs::exists(dir + "/never.png"));
}

// --out needs an image extension; every frame goes to a directory written with a trailing '/'.
TEST(CliOutputs, UnknownImageExtensionsAreRefused) {
  const std::string dir = test::tempDir("cli-extension");
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"render --out " + dir + "/name", "no extension"},
      {"render --out " + dir + "/name.bmp", ".bmp"},
      {"reference --out " + dir + "/name.tif", ".tif"},
      {"render --view primary-depth --out " + dir + "/frames/", "ray-cast view is one image"},
  };
  for (const auto& [args, reason] : cases) {
    test::CommandResult r = runCommand(bounceExe() + " " + args, 30);
    EXPECT_EQ(r.exitCode, 1) << args << "\n" << r.output;
    EXPECT_NE(r.output.find(reason), std::string::npos) << args << "\n" << r.output;
    if (reason != "ray-cast view is one image")
      EXPECT_NE(r.output.find("expected .png or .exr"), std::string::npos) << r.output;
  }
  EXPECT_FALSE(fs::exists(dir + "/name")) << "no directory made for a name without extension";
}

// A scene path holding a quote, a backslash, a space and non-ASCII characters: every JSON file
// the program writes parses back and holds the path unchanged.
TEST(CliOutputs, JsonWithOddCharactersInPathsParsesBack) {
  const std::string odd = test::tempDir("cli-json") + "/odd \"quoted\" back\\slash é";
  fs::create_directories(odd);
  const std::string box = test::sharedDir() + "/scenes/cornell_box/";
  fs::copy_file(box + "cornell_box.gltf", odd + "/cornell_box.gltf");
  fs::copy_file(box + "cornell_box.bin", odd + "/cornell_box.bin");
  const std::string scene = odd + "/cornell_box.gltf";

  test::CommandResult r = runCommand(bounceExe() + " render --scene " + quoted(scene) +
                                     " --res 16x12 --frames 2 --gi none --timings " +
                                     quoted(odd + "/t.json") + " --out " + quoted(odd + "/x.png"));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  nlohmann::json timings = nlohmann::json::parse(readText(odd + "/t.json"));
  EXPECT_EQ(timings["scene_source"], scene);
  EXPECT_FALSE(timings["timings"].empty());
  EXPECT_EQ(timings["frame_wall_ms"].size(), 2u);

  r = runCommand(bounceExe() + " bench-rays --scene " + quoted(scene) +
                 " --res 16x12 --iterations 1 --json " + quoted(odd + "/b.json"));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_EQ(nlohmann::json::parse(readText(odd + "/b.json"))["scene_source"], scene);

  const std::string image = odd + "/ref \"1\".png";
  fs::copy_file(test::sharedDir() + "/references/cornell_box/cycles_16spp.png", image);
  r = runCommand(bounceExe() + " compare " + quoted(image) + " " + quoted(image) + " --json " +
                 quoted(odd + "/c.json"));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_EQ(nlohmann::json::parse(readText(odd + "/c.json"))["test"], image);
}

// A write that fails is an error, stdout included.
TEST(CliOutputs, FailedWriteToStdoutIsAnError) {
  if (!fs::exists("/dev/full")) GTEST_SKIP() << "no /dev/full";
  test::CommandResult r = runCommand("sh -c '" + bounceExe() + " info --json > /dev/full'");
  EXPECT_EQ(r.exitCode, 1) << r.output;
  EXPECT_NE(r.output.find("bounce: error: cannot write to standard output"), std::string::npos)
      << r.output;
}

// Starts `bounce` with stdout and stderr into `log`; returns its process id.
pid_t spawnBounce(const std::vector<std::string>& args, const std::string& log) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    FILE* out = std::freopen(log.c_str(), "w", stdout);
    if (!out || ::dup2(STDOUT_FILENO, STDERR_FILENO) < 0) ::_exit(127);
    std::vector<char*> argv;
    std::string exe = bounceExe();
    argv.push_back(exe.data());
    std::vector<std::string> copies = args;
    for (std::string& a : copies) argv.push_back(a.data());
    argv.push_back(nullptr);
    ::execv(exe.c_str(), argv.data());
    ::_exit(127);
  }
  return pid;
}

// Waits up to `seconds` for the process to end; its exit code, 1000 + signal when a signal
// ended it (so a missing SIGINT handler does not pass for exit code 130), or -1 (still
// running: killed).
int waitForExit(pid_t pid, double seconds) {
  const auto start = std::chrono::steady_clock::now();
  int status = 0;
  while (secondsSince(start) < seconds) {
    if (::waitpid(pid, &status, WNOHANG) == pid)
      return WIFEXITED(status) ? WEXITSTATUS(status) : 1000 + WTERMSIG(status);
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  ::kill(pid, SIGKILL);
  ::waitpid(pid, &status, 0);
  return -1;
}

// Ctrl-C during a long reference render: the image traced so far is written, its samples per
// pixel said on stderr and in the EXR's attributes, and the exit code is 130.
TEST(CliOutputs, CtrlCDuringReferenceWritesTheImageSoFar) {
  const std::string dir = test::tempDir("cli-sigint");
  const std::string out = dir + "/partial.exr";
  const std::string log = dir + "/log.txt";
  const pid_t pid = spawnBounce(
      {"reference", "--scene", "cornell", "--res", "32x24", "--spp", "1000000", "--out", out}, log);
  ASSERT_GT(pid, 0);
  // The verb says when tracing starts (its Ctrl-C handler is in place from then on).
  const auto start = std::chrono::steady_clock::now();
  while (readText(log).find("Ctrl-C") == std::string::npos && secondsSince(start) < 240.0)
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  ASSERT_NE(readText(log).find("Ctrl-C"), std::string::npos) << readText(log);
  std::this_thread::sleep_for(std::chrono::milliseconds(500));  // a batch or two
  ::kill(pid, SIGINT);
  EXPECT_EQ(waitForExit(pid, 120.0), 130) << readText(log);

  const ImageRGBA32F image = readImage(out);
  EXPECT_EQ(image.width, 32);
  EXPECT_EQ(image.height, 24);
  EXPECT_GT(test::meanLuminance(image), 0.0);
  std::string spp, interrupted;
  for (const auto& [name, value] : readExrMetadata(out)) {
    if (name == "bounce.spp") spp = value;
    if (name == "bounce.interrupted") interrupted = value;
  }
  ASSERT_FALSE(spp.empty());
  EXPECT_GE(std::stoll(spp), 1);
  EXPECT_LT(std::stoll(spp), 1000000);
  EXPECT_EQ(interrupted, "true");
  EXPECT_NE(readText(log).find("interrupted after " + spp + " of 1000000 spp"), std::string::npos)
      << readText(log);
}

// The render progress line is drawn on terminals only (here a pseudo-terminal made by
// script(1)); the wall time is always printed; on a CPU device the per-pass GPU times are
// called what they are, and --timings marks them.
TEST(CliOutputs, RenderProgressOnTerminalsOnlyAndWallTimeAlways) {
  const std::string dir = test::tempDir("cli-progress");
  const std::string command = bounceExe() +
                              " render --scene cornell --res 16x12 --frames 3 --gi none --out " +
                              dir + "/x.png --timings " + dir + "/t.json";
  test::CommandResult piped = runCommand(command);
  ASSERT_EQ(piped.exitCode, 0) << piped.output;
  EXPECT_EQ(piped.output.find('\r'), std::string::npos) << piped.output;
  EXPECT_NE(piped.output.find("wall time"), std::string::npos) << piped.output;

  test::CommandResult terminal = runCommand("script -qfec '" + command + "' /dev/null");
  ASSERT_EQ(terminal.exitCode, 0) << terminal.output;
  EXPECT_NE(terminal.output.find("\r["), std::string::npos) << terminal.output;
  EXPECT_NE(terminal.output.find("3/3 frames"), std::string::npos) << terminal.output;
  EXPECT_NE(terminal.output.find("ETA"), std::string::npos) << terminal.output;
  EXPECT_NE(terminal.output.find("wall time"), std::string::npos) << terminal.output;

  const nlohmann::json timings = nlohmann::json::parse(readText(dir + "/t.json"));
  const bool cpu = timings["device_type"] == "cpu";
  EXPECT_EQ(timings["gpu_times_meaningful"].get<bool>(), !cpu);
  EXPECT_EQ(piped.output.find("not meaningful on a CPU device") != std::string::npos, cpu)
      << piped.output;
  EXPECT_EQ(piped.output.find("GPU time per pass, median") != std::string::npos, !cpu)
      << piped.output;
}

}  // namespace
}  // namespace bounce
