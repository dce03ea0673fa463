#pragma once
// Each subcommand lives in its own cmd_<name>.cpp and registers itself here.
// Conventions (docs/cli.md): exit 0 = ok, 1 = the run failed (e.g. the plant
// faulted), 2 = bad input (flags, files, values) with a one-line message on
// stderr that starts with "cvtplant <subcommand>: error: ".
#include <CLI/CLI.hpp>

#include <functional>
#include <string>

namespace cvtcli {

// Thrown by subcommand bodies for bad input discovered after flag parsing
// (unreadable file, NaN in a CSV, ...). main() maps it to exit code 2.
struct UsageError {
  std::string message;
};
// Thrown when the input was fine but the run could not complete (exit 1).
struct RunError {
  std::string message;
};
// Thrown when SIGINT or SIGTERM stopped a run (docs/cli.md#interruption):
// main() says `interrupted at <at>` on stderr and exits 128 + the signal.
// `summary_written`: the command printed its own summary with
// "status": "interrupted"; otherwise main() prints a short one for --json.
struct Interrupted {
  std::string at;  // "t = 1.25 s", "120/400 plant runs"
  bool summary_written = false;
};

// A subcommand body; returns the process exit code.
using Action = std::function<int()>;

// Registers a subcommand on `app` and returns the action to run if it was
// selected. Each cmd_*.cpp defines one of these and registers it itself at
// static initialisation (registry.hpp): no central list to edit.
using Registrar = Action (*)(CLI::App& app);

}  // namespace cvtcli
