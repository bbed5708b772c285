// `bounce bench` (issue 24): a short scripted run of sunroom on lavapipe writes the JSON report
// with every pass's series, the stacked plot (PNG and SVG) and the contact sheet, and passes the
// soak's checks; several runs make a comparison plot.
#include <filesystem>
#include <fstream>
#include <iterator>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "harness.h"
#include "tools/image_io.h"
#include "tools/metrics.h"
#include "tools/soak_check.h"

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
                           std::to_string(kFrames) + " --soak --soak-warmup 4 --out " + dir,
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
  // Rays (counted by default): a series per pass; the frame's rays are the passes' sum; the
  // sun's shadow rays are at most one per shadow pixel (a quarter of the pixels, desktop); the
  // passes that trace nothing count none (HybridFrame.CountedRaysMatchWhatEachPassTraces checks
  // the counts exactly).
  ASSERT_EQ(run["frame_rays"].size(), size_t(kFrames));
  for (int f = 0; f < kFrames; ++f) {
    double sum = 0.0;
    for (const nlohmann::json& pass : run["passes"]) sum += pass["rays"][f].get<double>();
    EXPECT_EQ(sum, run["frame_rays"][f].get<double>()) << "frame " << f;
  }
  auto rowOf = [&](const std::string& pass) {
    for (const nlohmann::json& row : run["table"])
      if (row["pass"] == pass) return row;
    ADD_FAILURE() << "no table row " << pass;
    return nlohmann::json();
  };
  EXPECT_GT(rowOf("shadows-trace")["rays_per_pixel"].get<double>(), 0.0);
  EXPECT_LE(rowOf("shadows-trace")["rays_per_pixel"].get<double>(), 0.25);
  EXPECT_EQ(rowOf("composite")["rays_per_pixel"].get<double>(), 0.0);
  EXPECT_GT(rowOf("frame (GPU)")["median_rays"].get<double>(), 0.0);

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

  // The soak's checks on this short run (`make soak` runs long ones): every frame finite, and
  // after the warm-up no device allocation (DESIGN.md: frames allocate nothing).
  const nlohmann::json& soak = run["soak"];
  EXPECT_TRUE(soak["passed"].get<bool>()) << soak.dump(2);
  EXPECT_EQ(soak["frames"], kFrames);
  EXPECT_EQ(soak["non_finite_frames"], 0);
  EXPECT_EQ(soak["after_warmup"]["device_bytes"], soak["last"]["device_bytes"]);
  EXPECT_EQ(soak["after_warmup"]["device_bytes"], run["device_bytes"]);
  EXPECT_GT(soak["last"]["resident_bytes"].get<uint64_t>(), 0u);
}

// Several runs make a comparison plot, one stacked bar per run; `--compare` draws the runs of
// several reports (other scenes, other GPUs) the same way, rendering nothing.
TEST(Bench, RunsSideBySideMakeComparisonPlots) {
  const std::string dir = test::tempDir("bench-compare");
  test::CommandResult r = test::runCommand(
      test::bounceExe() + " bench --scene cornell --res 64x36 --frames 3 --contact-frames 1 " +
          "--gi cache,none --out " + dir + "/a",
      180);
  ASSERT_EQ(r.exitCode, 0) << r.output;
  std::ifstream file(fs::path(dir) / "a" / "bench.json");
  const nlohmann::json report = nlohmann::json::parse(file);
  ASSERT_EQ(report["runs"].size(), 2u);
  const ImageRGBA32F bars = readImage((fs::path(dir) / "a" / "comparison.png").string());
  EXPECT_GT(pixelsUnlikeTheFirst(bars), bars.pixelCount() / 50);
  // The SVG has one rectangle per pass of each run that has it: the cache run has more passes.
  std::ifstream svgFile(fs::path(dir) / "a" / "comparison.svg");
  const std::string svg((std::istreambuf_iterator<char>(svgFile)), {});
  size_t rectangles = 0;
  for (size_t at = svg.find("<title>"); at != std::string::npos; at = svg.find("<title>", at + 1))
    ++rectangles;
  const size_t passes = report["runs"][0]["passes"].size() + report["runs"][1]["passes"].size();
  EXPECT_GE(rectangles, passes);

  r = test::runCommand(test::bounceExe() + " bench --compare " + dir + "/a/bench.json," + dir +
                           "/a/bench.json --out " + dir + "/b",
                       30);
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_TRUE(fs::exists(fs::path(dir) / "b" / "comparison.png"));
  // A file that is not a report is refused by name.
  r = test::runCommand(
      test::bounceExe() + " bench --compare " + dir + "/a/comparison.svg --out " + dir + "/c", 30);
  EXPECT_EQ(r.exitCode, 1) << r.output;
  EXPECT_NE(r.output.find("comparison.svg"), std::string::npos) << r.output;
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
      {"--soak --frames 10 --soak-warmup 10", "--soak-warmup 10"},
      {"--soak --soak-rss-growth -1", "--soak-rss-growth -1"},
  };
  for (const auto& [args, message] : cases) {
    const test::CommandResult r =
        test::runCommand(test::bounceExe() + " bench " + args + " --out " + dir, 30);
    EXPECT_EQ(r.exitCode, 1) << args << "\n" << r.output;
    EXPECT_NE(r.output.find(message), std::string::npos) << args << "\n" << r.output;
  }
  EXPECT_FALSE(fs::exists(fs::path(dir) / "bench.json"));
}

// The soak's rules on made-up runs: each broken rule is found and named with its frame, and a
// clean run passes.
TEST(SoakCheck, FindsNonFiniteFramesAndMemoryGrowthAfterTheWarmup) {
  constexpr uint64_t kMiB = 1 << 20;
  ImageRGBA32F clean(4, 4);
  ImageRGBA32F withNaN(4, 4);
  withNaN.set(1, 2, glm::vec4(std::nanf(""), 0.0f, 0.0f, 1.0f));
  withNaN.set(3, 3, glm::vec4(0.0f, INFINITY, 0.0f, 1.0f));
  EXPECT_EQ(countNonFinitePixels(clean), 0u);
  EXPECT_EQ(countNonFinitePixels(withNaN), 2u);

  // Memory may change during the warm-up (frames 0-9), not after.
  auto run = [&](auto sampleAt) {
    SoakCheck check(10, 8 * kMiB);
    for (uint32_t i = 0; i < 40; ++i) check.add(sampleAt(i));
    return check;
  };
  const SoakCheck good = run([&](uint32_t i) {
    return SoakSample{i, 0, (i < 10 ? 100 + i : 110) * kMiB, (i < 5 ? 1 : 2) * kMiB, 7};
  });
  EXPECT_TRUE(good.passed()) << good.failures()[0];
  EXPECT_NEAR(good.residentSlopeBytesPerFrame(), 0.0, 1e-6);

  const SoakCheck nan = run([&](uint32_t i) {
    return SoakSample{i, countNonFinitePixels(i == 17 || i == 30 ? withNaN : clean), 100 * kMiB,
                      kMiB, 7};
  });
  ASSERT_EQ(nan.failures().size(), 1u);
  EXPECT_NE(nan.failures()[0].find("2 of 40 frames"), std::string::npos) << nan.failures()[0];
  EXPECT_NE(nan.failures()[0].find("frame 17"), std::string::npos) << nan.failures()[0];

  const SoakCheck device = run([&](uint32_t i) {
    return SoakSample{i, 0, 100 * kMiB, kMiB, i < 25 ? 7u : 8u};
  });
  ASSERT_EQ(device.failures().size(), 1u);
  EXPECT_NE(device.failures()[0].find("at frame 25"), std::string::npos) << device.failures()[0];

  // A leak of 300 KiB a frame: 9 MiB over the 30 frames after the warm-up, above the 8 allowed.
  const SoakCheck host = run([&](uint32_t i) {
    return SoakSample{i, 0, 100 * kMiB + i * 300 * 1024, kMiB, 7};
  });
  ASSERT_EQ(host.failures().size(), 1u);
  EXPECT_NE(host.failures()[0].find("host memory grew"), std::string::npos);
  EXPECT_NEAR(host.residentSlopeBytesPerFrame(), 300.0 * 1024, 1.0);
}

}  // namespace
}  // namespace bounce
