// bounce: the command-line program. One verb per task (DESIGN.md §7); errors go to stderr with
// a non-zero exit code.
#include <cstdio>
#include <exception>

#include "core/error.h"
#include "verbs.h"

int main(int argc, char** argv) {
  CLI::App app{"Bounce: real-time dynamic global illumination on Vulkan", "bounce"};
  app.require_subcommand(1);
  bounce::app::VerbAction action;
  bounce::app::addInfoVerb(app, action);
  bounce::app::addRenderVerb(app, action);
  bounce::app::addBenchRaysVerb(app, action);
  bounce::app::addReferenceVerb(app, action);
  bounce::app::addCompareVerb(app, action);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  try {
    return action ? action() : 0;
  } catch (const bounce::Error& e) {
    std::fprintf(stderr, "bounce: error: %s\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bounce: internal error: %s\n", e.what());
    return 3;
  }
}
