// The `bounce` program as a user meets it: devices listed, images written, and bad input
// answered with a clear message and a non-zero exit (never a crash or a hang).
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "harness.h"
#include "tools/image_io.h"

namespace bounce {
namespace {

using test::bounceExe;
using test::runCommand;

TEST(Cli, InfoListsTheChosenDevice) {
  test::CommandResult r = runCommand(bounceExe() + " info --json");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  nlohmann::json j = nlohmann::json::parse(r.output.substr(r.output.find('{')));
  ASSERT_FALSE(j["devices"].empty());
  bool anyChosen = false;
  for (const auto& d : j["devices"])
    anyChosen |= d["chosen"].get<bool>() && d["suitable"].get<bool>();
  EXPECT_TRUE(anyChosen);
}

// Each bad invocation must fail with exit code 1..4 and a message that names the problem.
struct BadInvocation {
  std::string args;
  std::string expectedText;
};

TEST(Cli, BadInputGetsAClearError) {
  std::string dir = test::tempDir("cli");
  std::ofstream(dir + "/broken.gltf") << "{ \"asset\": {\"version\": \"2.0\"}, \"meshes\": [ ";
  const std::vector<BadInvocation> cases = {
      {"render --scene nosuchscene", "not a built-in scene"},
      {"render --scene " + dir + "/missing.gltf", "missing.gltf"},
      {"render --scene " + dir + "/broken.gltf", "broken.gltf"},
      {"render --scene cornell --res 10by10", "--res"},
      {"render --scene cornell --res 0x10", "--res"},
      {"render --scene cornell --camera 1,2,3:4,5", "--camera"},
      {"render --scene cornell --camera 0,0,0:0,0,0:45", "--camera"},
      {"render --scene cornell --sun 0,-1,0", "--sun"},
      {"render --scene cornell --sky 1,nan,1", "--sky"},
      {"render --scene cornell --view nosuchview --res 8x8", "nosuchview"},
      {"render --scene cornell --device 99 --res 8x8", "--device 99"},
      {"render --scene cornell --gi foo --res 8x8", "--gi 'foo'"},
      {"render --scene cornell --gi-divisor 17 --res 8x8", "resolution divisor 17"},
      {"render --scene cornell --shadow-divisor 17 --res 8x8", "shadow divisor 17"},
      {"render --scene cornell --exposure 100 --res 8x8", "--exposure 100"},
      {"render --scene cornell --restir-second-vertex foo --res 8x8", "--restir-second-vertex"},
      {"render --scene cornell --gi-texture-side 5000 --res 8x8", "material texture side 5000"},
      {"render --scene cornell --restir-max-sample-age -3 --res 8x8", "--restir-max-sample-age -3"},
      {"compare " + dir + "/a.png " + dir + "/b.png", "a.png"},
  };
  for (const BadInvocation& c : cases) {
    test::CommandResult r = runCommand(bounceExe() + " " + c.args, 60);
    EXPECT_GE(r.exitCode, 1) << c.args << "\n" << r.output;
    EXPECT_LE(r.exitCode, 4) << c.args << " (crash or hang?)\n" << r.output;
    EXPECT_NE(r.output.find(c.expectedText), std::string::npos)
        << c.args << ": message should mention '" << c.expectedText << "'\n"
        << r.output;
  }
}

// A frame that does not fit the device's memory: exit code 1 and a message with the size that
// failed, what Bounce already held, what it needed at least and the heap's size (issue 24). The
// limit makes any device run out, as a GPU with 8 MiB would.
TEST(Cli, OutOfDeviceMemoryGetsAClearMessage) {
  const std::string dir = test::tempDir("cli-oom");
  test::CommandResult r =
      runCommand(bounceExe() + " render --scene cornell --res 256x256 --frames 1 " +
                     "--device-memory-limit 8 --out " + dir + "/frame.png",
                 60);
  EXPECT_EQ(r.exitCode, 1) << r.output;
  const std::regex message(
      "out of GPU memory on .*: an allocation of [0-9.]+ MiB failed \\(the "
      "--device-memory-limit of 8.0 MiB\\)\\. Bounce already held [0-9.]+ MiB in [0-9]+ "
      "allocations, so it needed at least [0-9.]+ MiB; memory heap [0-9]+ of the device has "
      "[0-9.]+ MiB");
  EXPECT_TRUE(std::regex_search(r.output, message)) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir + "/frame.png"));
  // The same frame renders with room to spare, so the limit, not the frame, made it fail.
  r = runCommand(bounceExe() + " render --scene cornell --res 256x256 --frames 1 " +
                     "--device-memory-limit 4096 --out " + dir + "/frame.png",
                 120);
  EXPECT_EQ(r.exitCode, 0) << r.output;
}

// Counts the lines of a command's output.
size_t lineCount(const std::string& output) {
  return size_t(std::count(output.begin(), output.end(), '\n'));
}

struct UsageError {
  std::string args;
  std::vector<std::string> expected;  // each must appear in the message
};

// Every usage error: exit code 1 and one line "bounce: error: ..." naming the verb or option at
// fault, with the closest valid name where one is close. These fail before any Vulkan device is
// opened, so nothing else may be printed.
TEST(Cli, UsageErrorsAreOneLineWithExitCodeOneAndASuggestion) {
  const std::vector<UsageError> cases = {
      {"rendr", {"unknown verb 'rendr'", "did you mean render?"}},
      {"bench-ray", {"unknown verb 'bench-ray'", "did you mean bench-rays?"}},
      {"--verison", {"unknown option --verison", "did you mean --version?"}},
      {"render --scen sunroom", {"render: unknown option --scen", "did you mean --scene?"}},
      {"render --gi evolv", {"--gi 'evolv'", "none, evolve, cache", "did you mean evolve?"}},
      {"render --preset desktpo", {"--preset 'desktpo'", "did you mean desktop?"}},
      {"render --vbuffer rastr", {"--vbuffer 'rastr'", "did you mean raster?"}},
      {"bench-rays --bvh wid", {"--bvh 'wid'", "binary, wide", "did you mean wide?"}},
      {"render --restir-second-vertex pth", {"--restir-second-vertex 'pth'", "did you mean path?"}},
      {"reference --scene cornel", {"--scene 'cornel'", "did you mean cornell?"}},
      {"render --frames abc", {"--frames"}},
      {"render --scene", {"--scene"}},
      {"render stray", {"unexpected argument 'stray'"}},
      {"compare only-one.png", {"reference"}},
      {"bench-rays --iterations 0", {"--iterations"}},
  };
  for (const UsageError& c : cases) {
    test::CommandResult r = runCommand(bounceExe() + " " + c.args, 30);
    EXPECT_EQ(r.exitCode, 1) << c.args << "\n" << r.output;
    EXPECT_EQ(r.output.rfind("bounce: error: ", 0), 0u) << c.args << "\n" << r.output;
    EXPECT_EQ(lineCount(r.output), 1u) << c.args << "\n" << r.output;
    for (const std::string& text : c.expected)
      EXPECT_NE(r.output.find(text), std::string::npos)
          << c.args << ": message should contain '" << text << "'\n"
          << r.output;
  }
  // Nothing close: no suggestion rather than a wild guess.
  test::CommandResult r = runCommand(bounceExe() + " render --gi xyzzyq", 30);
  EXPECT_EQ(r.exitCode, 1) << r.output;
  EXPECT_EQ(r.output.find("did you mean"), std::string::npos) << r.output;
}

// An unknown --view is only known once the frame is declared (after the scene loads).
TEST(Cli, UnknownViewGetsASuggestion) {
  const std::string dir = test::tempDir("cli-view");
  test::CommandResult r = runCommand(bounceExe() +
                                     " render --scene cornell --res 8x8 --frames 1 --gi none "
                                     "--view tonemapp --out " +
                                     dir + "/x.png");
  EXPECT_EQ(r.exitCode, 1) << r.output;
  EXPECT_NE(r.output.find("bounce: error: --view 'tonemapp'"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("did you mean tonemap?"), std::string::npos) << r.output;
}

TEST(Cli, VersionHelpAndBareProgram) {
  test::CommandResult version = runCommand(bounceExe() + " --version");
  EXPECT_EQ(version.exitCode, 0) << version.output;
  EXPECT_EQ(version.output, std::string("bounce ") + BOUNCE_VERSION + "\n");

  // `bounce` alone lists the verbs, one line each, and (like git) exits 1: nothing was done.
  test::CommandResult bare = runCommand(bounceExe());
  EXPECT_EQ(bare.exitCode, 1) << bare.output;
  for (const std::string verb : {"info", "render", "bench-rays", "reference", "compare"})
    EXPECT_TRUE(std::regex_search(bare.output, std::regex("\n  " + verb + " +[A-Z]")))
        << verb << "\n"
        << bare.output;

  test::CommandResult help = runCommand(bounceExe() + " render --help");
  EXPECT_EQ(help.exitCode, 0) << help.output;
  EXPECT_NE(help.output.find("--exposure"), std::string::npos) << help.output;
}

// Options that cannot both be honoured are refused, naming both, before any work.
TEST(Cli, ConflictingOptionsAreRefusedNamingBoth) {
  const std::string dir = test::tempDir("cli-conflicts");
  std::ofstream(dir + "/path.json")
      << R"({"keyframes": [{"time": 0, "position": [0, 1, 5], "target": [0, 1, 0]}]})";
  const std::vector<std::pair<std::string, std::vector<std::string>>> cases = {
      {"render --camera 0,1,5:0,1,0:40 --camera-path " + dir + "/path.json",
       {"--camera", "--camera-path"}},
      {"render --gi none --restir-unbiased", {"--gi none", "--restir-unbiased"}},
      {"render --gi cache --restir-validation-period 3",
       {"--gi cache", "--restir-validation-period"}},
      {"render --gi none --gi-divisor 2", {"--gi none", "--gi-divisor"}},
      {"render --gi none --gi-texture-side 8", {"--gi none", "--gi-texture-side"}},
      {"render --time-of-day 9 --sun 0,-1,0:3", {"--time-of-day", "--sun"}},
      {"render --day-cycle 10 --sun 0,-1,0:3", {"--day-cycle", "--sun"}},
      {"render --restir-unbiased --restir-second-vertex cache",
       {"--restir-unbiased", "--restir-second-vertex"}},
      {"render --list-views --out " + dir + "/x.png", {"--list-views", "--out"}},
      {"render --view primary-albedo --timings " + dir + "/t.json",
       {"--view primary-albedo", "--timings"}},
      {"reference --exposure 1 --out " + dir + "/x.exr", {"--exposure", "--out"}},
      {"compare a.png b.png --zoom 2", {"--zoom", "--side-by-side"}},
      {"bench-rays --build-only --tracer both", {"--build-only", "--tracer both"}},
      {"render --di-unbiased --di-candidate-visibility auto",
       {"--di-unbiased", "--di-candidate-visibility auto"}},
  };
  for (const auto& [args, names] : cases) {
    test::CommandResult r = runCommand(bounceExe() + " " + args, 30);
    EXPECT_EQ(r.exitCode, 1) << args << "\n" << r.output;
    EXPECT_EQ(r.output.rfind("bounce: error: ", 0), 0u) << args << "\n" << r.output;
    for (const std::string& name : names)
      EXPECT_NE(r.output.find(name), std::string::npos) << args << "\n" << r.output;
  }
}

// bench-rays --build-only times the CPU BVH build alone, with no device: one time per
// iteration, their median as triangles/s, and the trees' SAH costs.
TEST(Cli, BenchRaysBuildOnlyTimesTheBvhBuild) {
  const std::string dir = test::tempDir("cli-build-only");
  test::CommandResult r = runCommand(bounceExe() +
                                         " bench-rays --build-only --scene sunroom --iterations 3 "
                                         "--build-threads 2 --json " +
                                         dir + "/b.json",
                                     60);
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("M triangles/s"), std::string::npos) << r.output;
  const nlohmann::json j = nlohmann::json::parse(std::ifstream(dir + "/b.json"));
  EXPECT_EQ(j["bvh_build_seconds"].size(), 3u);
  EXPECT_GT(j["unique_triangles"].get<double>(), 0.0);
  EXPECT_GT(j["bvh_build_mtriangles_per_second"].get<double>(), 0.0);
  EXPECT_GT(j["blas_sah_cost"].get<double>(), 1.0);
  EXPECT_EQ(j["build_threads"], 2);
}

// Values out of range are refused naming the flag (not the library's field alone), never
// replaced by a default: --shadow-divisor 0 used to mean "the preset's".
TEST(Cli, OutOfRangeValuesAreRefusedNamingTheFlag) {
  const std::vector<std::string> cases = {
      "--shadow-divisor 0",
      "--shadow-divisor 17",
      "--gi-divisor 0",
      "--gi-divisor 17",
      "--exposure 65",
      "--exposure nan",
      "--sky-ambient -1",
      "--frames 0",
      "--frames -2",
      "--fps 0",
      "--time-of-day 25",
      "--day-cycle -1",
      "--restir-history-brightening 0.5",
      "--restir-max-sample-age -3",
      "--restir-validation-period -1",
      "--gi-texture-side 5000",
      "--gi-denoise-history 0",
      "--gi-denoise-history 2000",
  };
  for (const std::string& c : cases) {
    test::CommandResult r = runCommand(bounceExe() + " render --res 8x8 " + c, 30);
    EXPECT_EQ(r.exitCode, 1) << c << "\n" << r.output;
    EXPECT_EQ(r.output.rfind("bounce: error: " + c, 0), 0u) << c << "\n" << r.output;
    EXPECT_EQ(lineCount(r.output), 1u) << c << "\n" << r.output;
  }
}

// --denoiser names one of the denoisers of docs/denoise.md; another name is refused with the list.
TEST(Cli, UnknownDenoiserIsRefusedWithTheList) {
  test::CommandResult r = runCommand(bounceExe() + " render --res 8x8 --denoiser nlm", 30);
  EXPECT_EQ(r.exitCode, 1) << r.output;
  EXPECT_NE(r.output.find("--denoiser: nlm not in {evolve,svgf,reblur,hybrid,none}"),
            std::string::npos)
      << r.output;
  EXPECT_EQ(lineCount(r.output), 1u) << r.output;
}

// --exposure is in stops, as in `reference` and `compare`: the radiance is scaled by 2^STOPS
// before the tone curve, so -30 stops leaves about a billionth of the light (black), -1 less
// than 0; a linear factor could not be negative at all.
TEST(Cli, RenderExposureIsInStops) {
  const std::string dir = test::tempDir("cli-exposure");
  std::map<std::string, double> luminance;
  for (const std::string stops : {"-30", "-1", "0"}) {
    const std::string out = dir + "/e" + stops + ".exr";
    test::CommandResult r =
        runCommand(bounceExe() + " render --scene cornell --res 16x12 --frames 1 --gi none " +
                   "--exposure " + stops + " --out " + out);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    luminance[stops] = test::meanLuminance(readImage(out));
  }
  EXPECT_GT(luminance["0"], 0.0);
  EXPECT_LT(luminance["-1"], luminance["0"]);
  EXPECT_LT(luminance["-30"], 1e-3 * luminance["0"]);
}

// The first image of each built-in scene: the primary views cover the frame with surfaces
// (the cameras look at geometry), with validation on and silent.
TEST(Cli, PrimaryViewsOfBuiltinScenes) {
  std::string dir = test::tempDir("views");
  for (std::string scene : {"cornell", "sunroom", "foliage", "manylights", "furnace", "city"}) {
    for (std::string view : {"primary-albedo", "primary-normal", "primary-depth"}) {
      std::string out = dir + "/" + scene + "-" + view + ".png";
      test::CommandResult r = runCommand(bounceExe() + " render --validate --scene " + scene +
                                             " --view " + view + " --res 64x48 --out " + out,
                                         300);
      ASSERT_EQ(r.exitCode, 0) << scene << " " << view << "\n" << r.output;
      EXPECT_EQ(r.output.find("validation"), std::string::npos) << r.output;
      ImageRGBA32F image = readImage(out);
      ASSERT_EQ(image.width, 64);
      ASSERT_EQ(image.height, 48);
      int lit = 0;
      for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
          glm::vec4 p = image.at(x, y);
          lit += (p.x + p.y + p.z) > 0.0f;
        }
      // Enclosed scenes fill the frame; open ones show sky (black here) in part of it.
      EXPECT_GT(lit, image.width * image.height / 3) << scene << " " << view;
    }
  }
}

}  // namespace
}  // namespace bounce
