// The `bounce` program as a user meets it: devices listed, images written, and bad input
// answered with a clear message and a non-zero exit (never a crash or a hang).
#include <filesystem>
#include <fstream>

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
      {"render --scene cornell --exposure -1 --res 8x8", "exposure -1"},
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
