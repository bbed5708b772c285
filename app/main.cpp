// bounce: the command-line program. One verb per task (DESIGN.md §7). Conventions
// (docs/cli.md): usage errors are one line "bounce: error: ..." naming the option or verb at
// fault, with the closest valid name suggested, and exit code 1; bad input (files, scenes)
// exits 1 too; internal errors exit 3; Vulkan validation errors 4; Ctrl-C 130.
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <exception>
#include <string>
#include <vector>

#include "core/error.h"
#include "suggest.h"
#include "verbs.h"

namespace {

constexpr int kUsageExit = 1;
constexpr int kInternalErrorExit = 3;

std::vector<CLI::App*> verbs(CLI::App& app) {
  return app.get_subcommands([](CLI::App*) { return true; });
}

std::vector<std::string> verbNames(CLI::App& app) {
  std::vector<std::string> names;
  for (CLI::App* verb : verbs(app)) names.push_back(verb->get_name());
  return names;
}

// `bounce` alone: the verbs, one line each. Like git, this is a usage error (exit 1): the
// program was asked to do nothing.
int printVerbs(CLI::App& app) {
  std::printf("usage: bounce <verb> [options]\n\nverbs:\n");
  for (CLI::App* verb : verbs(app)) {
    std::string description = verb->get_description();
    description = description.substr(0, description.find(": "));  // the first clause
    std::printf("  %-12s %s\n", verb->get_name().c_str(), description.c_str());
  }
  std::printf(
      "\n'bounce <verb> --help' lists a verb's options; 'bounce --version' prints the version.\n");
  return kUsageExit;
}

// argv[1] must be a verb or one of the program's own options; CLI11 alone would answer a typo
// with "A subcommand is required".
void checkVerb(CLI::App& app, const std::string& first) {
  const std::vector<std::string> names = verbNames(app);
  if (first.empty() || first[0] != '-') {
    for (const std::string& name : names)
      if (name == first) return;
    bounce::fail("unknown verb '{}'{}; the verbs are {}", first,
                 bounce::app::didYouMean(first, names), bounce::app::joinNames(names));
  }
  const std::vector<std::string> own = {"--help", "-h", "--help-all", "--version"};
  for (const std::string& option : own)
    if (option == first) return;
  bounce::fail("unknown option {}{}; usage: bounce <verb> [options]", first,
               bounce::app::didYouMean(first, own));
}

std::vector<std::string> longOptionNames(const CLI::App& verb) {
  std::vector<std::string> names;
  for (const CLI::Option* option : verb.get_options())
    for (const std::string& name : option->get_lnames()) names.push_back("--" + name);
  return names;
}

// The verbs allow extras so that an unknown option reaches us whole ("--scen" rather than
// "arguments were not expected: sunroom --scen") and gets a suggestion.
void refuseExtras(const CLI::App& verb) {
  const std::vector<std::string> extras = verb.remaining();
  for (const std::string& extra : extras) {
    if (extra.size() < 2 || extra[0] != '-') continue;
    const std::string name = extra.substr(0, extra.find('='));
    bounce::fail("{}: unknown option {}{}", verb.get_name(), name,
                 bounce::app::didYouMean(name, longOptionNames(verb)));
  }
  if (!extras.empty())
    bounce::fail("{}: unexpected argument '{}' (see 'bounce {} --help')", verb.get_name(),
                 extras[0], verb.get_name());
}

int usageError(const std::string& message) {
  std::fprintf(stderr, "bounce: error: %s\n", message.c_str());
  return kUsageExit;
}

// A verb's output that could not reach stdout (a full disk, a closed pipe) is a failure too.
int checkedStdout(int exitCode) {
  if (std::fflush(stdout) == 0 && !std::ferror(stdout)) return exitCode;
  std::fprintf(stderr, "bounce: error: cannot write to standard output: %s\n",
               std::strerror(errno));
  return exitCode == 0 ? kUsageExit : exitCode;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Bounce: real-time dynamic global illumination on Vulkan", "bounce"};
  app.set_version_flag("--version", std::string("bounce ") + BOUNCE_VERSION);
  app.require_subcommand(1);
  bounce::app::VerbAction action;
  bounce::app::addInfoVerb(app, action);
  bounce::app::addRenderVerb(app, action);
  bounce::app::addBenchVerb(app, action);
  bounce::app::addBenchRaysVerb(app, action);
  bounce::app::addReferenceVerb(app, action);
  bounce::app::addCompareVerb(app, action);
  bounce::app::addViewVerb(app, action);
  for (CLI::App* verb : verbs(app)) verb->allow_extras();
  if (argc < 2) return printVerbs(app);
  if (std::string(argv[1]) == "view") {
    try {
      bounce::app::forwardToViewer(argc, argv);
    } catch (const bounce::Error& e) {
      return usageError(e.what());
    }
  }
  try {
    checkVerb(app, argv[1]);
    app.parse(argc, argv);
    for (CLI::App* verb : app.get_subcommands()) refuseExtras(*verb);
  } catch (const CLI::Success& e) {  // --help, --version
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    const std::vector<CLI::App*> chosen = app.get_subcommands();
    return usageError((chosen.empty() ? "" : chosen[0]->get_name() + ": ") + e.what());
  } catch (const bounce::Error& e) {
    return usageError(e.what());
  }
  try {
    return checkedStdout(action ? action() : 0);
  } catch (const bounce::Error& e) {
    checkedStdout(0);
    return usageError(e.what());
  } catch (const std::exception& e) {
    checkedStdout(0);
    std::fprintf(stderr, "bounce: internal error: %s\n", e.what());
    return kInternalErrorExit;
  }
}
