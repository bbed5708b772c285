// bounce view: the interactive viewer. It lives in its own program, bounce-view (app/view/),
// which links GLFW and Dear ImGui; `bounce` itself stays headless (the GPU machine has no
// window-system libraries). The verb replaces this process with bounce-view from the same
// directory, passing every argument after "view" on.
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <vector>

#include "core/error.h"
#include "verbs.h"

namespace bounce::app {

namespace {

std::filesystem::path viewerPath() {
  std::error_code error;
  std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", error);
  if (error) fail("view: cannot find the bounce program's own directory: {}", error.message());
  return self.parent_path() / "bounce-view";
}

}  // namespace

void forwardToViewer(int argc, char** argv) {
  const std::filesystem::path viewer = viewerPath();
  if (!std::filesystem::exists(viewer))
    fail(
        "view: the viewer is not built: {} is missing (it needs GLFW and Dear ImGui: "
        "apt-get install libglfw3-dev libimgui-dev, then rebuild; or configure with "
        "-DBOUNCE_BUILD_VIEWER=ON to see why it was skipped)",
        viewer.string());
  std::vector<char*> args;
  std::string program = viewer.string();
  args.push_back(program.data());
  for (int i = 2; i < argc; ++i) args.push_back(argv[i]);
  args.push_back(nullptr);
  execv(program.c_str(), args.data());
  fail("view: cannot run {}: {}", program, std::strerror(errno));
}

void addViewVerb(CLI::App& app, VerbAction&) {
  // Registered for the verb list and suggestions only: main() forwards `bounce view ...`
  // before parsing, so that the viewer parses (and documents, --help) its own options.
  app.add_subcommand("view",
                     "Open a window on the real-time frame: fly camera, GI and debug-view "
                     "pickers, pass timings (bounce-view)");
}

}  // namespace bounce::app
