// The verbs of the `bounce` program. Each add*Verb registers its subcommand and options on
// `app` and, when the subcommand is chosen, stores in `action` the function that runs it and
// returns the exit code. Errors are thrown as bounce::Error and reported by main().
#pragma once
#include <functional>

#include <CLI/CLI.hpp>

namespace bounce::app {

using VerbAction = std::function<int()>;

void addInfoVerb(CLI::App& app, VerbAction& action);
void addRenderVerb(CLI::App& app, VerbAction& action);
void addBenchVerb(CLI::App& app, VerbAction& action);
void addBenchRaysVerb(CLI::App& app, VerbAction& action);
void addCompareVerb(CLI::App& app, VerbAction& action);
void addReferenceVerb(CLI::App& app, VerbAction& action);
void addViewVerb(CLI::App& app, VerbAction& action);

// `bounce view ARGS`: replaces the process with bounce-view ARGS (the sibling program); throws
// bounce::Error when it is not built or cannot run.
[[noreturn]] void forwardToViewer(int argc, char** argv);

}  // namespace bounce::app
