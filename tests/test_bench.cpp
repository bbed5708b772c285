// `bounce bench` (issue 24): a short scripted run of sunroom on lavapipe writes the JSON report
// with every pass's series, the stacked plot (PNG and SVG) and the contact sheet.
#include <filesystem>
#include <fstream>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "harness.h"
#include "tools/image_io.h"

namespace bounce {
namespace {

namespace fs = std::filesystem;

// Few frames: a 160x90 frame of the desktop preset takes seconds on lavapipe. Eight frames are
// three hours apart, from 4 h: night, sunrise, day, sunset, night.
constexpr int kFrames = 8;

// Pixels whose RGB differs from the image's first pixel: 0 for a blank image.
size_t pixelsUnlikeTheFirst(const ImageRGBA32F& image) {
  size_t count = 0;
  const glm::vec4 first = image.at(0, 0);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      if (glm::any(glm::greaterThan(glm::abs(glm::vec3(image.at(x, y) - first)), glm::vec3(0.01f))))
        ++count;
  return count;
}

TEST(Bench, SunroomWritesReportPlotAndContactSheet) {
  const std::string dir = test::tempDir("bench");
  const test::CommandResult r =
      test::runCommand(test::bounceExe() + " bench --scene sunroom --res 160x90 --frames " +
                           std::to_string(kFrames) + " --out " + dir,
                       120);
  ASSERT_EQ(r.exitCode, 0) << r.output;

  std::ifstream file(fs::path(dir) / "bench.json");
  const nlohmann::json report = nlohmann::json::parse(file);  // throws if it does not parse
  ASSERT_EQ(report["runs"].size(), 1u);
  const nlohmann::json& run = report["runs"][0];
  EXPECT_EQ(run["preset"], "desktop");
  EXPECT_EQ(run["gi"], "evolve");
  // Every pass has a series of raw and averaged times, one value per frame.
  ASSERT_GE(run["passes"].size(), 5u);
  for (const nlohmann::json& pass : run["passes"]) {
    EXPECT_EQ(pass["ms"].size(), size_t(kFrames)) << pass["name"];
    EXPECT_EQ(pass["rolling_ms"].size(), size_t(kFrames)) << pass["name"];
  }
  EXPECT_EQ(run["frame_gpu_ms"].size(), size_t(kFrames));
  EXPECT_EQ(run["frame_wall_ms"].size(), size_t(kFrames));
  // The default day runs night to night: the sun rises and sets during the run.
  const nlohmann::json& hours = run["hours"];
  EXPECT_LT(hours[0].get<double>(), 6.0);
  bool day = false;
  for (const nlohmann::json& h : hours)
    day = day || (h.get<double>() > 6.0 && h.get<double>() < 18.0);
  EXPECT_TRUE(day);
  // The table: every pass plus the frame's GPU and wall times.
  EXPECT_EQ(run["table"].size(), run["passes"].size() + 2);

  const ImageRGBA32F plot =
      readImage((fs::path(dir) / run["plot_png"].get<std::string>()).string());
  EXPECT_GT(plot.width, 0);
  // Not blank: the stacked areas cover a good part of the plot area.
  EXPECT_GT(pixelsUnlikeTheFirst(plot), plot.pixelCount() / 10);
  EXPECT_TRUE(fs::exists(fs::path(dir) / run["plot_svg"].get<std::string>()));

  // Eight 160x90 frames, four to a row.
  const ImageRGBA32F sheet =
      readImage((fs::path(dir) / run["contact_sheet"].get<std::string>()).string());
  EXPECT_EQ(sheet.width, 4 * 160);
  EXPECT_EQ(sheet.height, 2 * 90);
  EXPECT_GT(test::meanLuminance(sheet), 0.01);
}

// Usage errors name the option and exit 1 before any scene is loaded or frame rendered.
TEST(Bench, UsageErrorsAreRefusedBeforeAnyWork) {
  const std::string dir = test::tempDir("bench-usage");
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"--preset mobile,desk", "did you mean desktop?"},
      {"--gi evolve,cach", "did you mean cache?"},
      {"--frames 0", "--frames 0"},
      {"--sun 0,-1,0:3", "--sun cannot be used"},
      {"--contact-frames 0", "--contact-frames"},
      {"--runs " + dir + "/missing.json", "missing.json"},
      {"--runs " + dir + "/runs.json --gi cache", "--runs and --gi cannot be used together"},
  };
  for (const auto& [args, message] : cases) {
    const test::CommandResult r =
        test::runCommand(test::bounceExe() + " bench " + args + " --out " + dir, 30);
    EXPECT_EQ(r.exitCode, 1) << args << "\n" << r.output;
    EXPECT_NE(r.output.find(message), std::string::npos) << args << "\n" << r.output;
  }
  EXPECT_FALSE(fs::exists(fs::path(dir) / "bench.json"));
}

}  // namespace
}  // namespace bounce
