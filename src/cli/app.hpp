// The skyspec command-line application: the CLI11 app with every subcommand, and the function that
// parses a command line, runs (or only validates) the chosen subcommand and maps exceptions to
// exit codes. main.cpp calls it to run; the fuzzer (tests/fuzz/fuzz_cli.cpp) calls it to validate.
#pragma once

#include <CLI/CLI.hpp>

#include <iosfwd>
#include <memory>
#include <vector>

#include "commands.hpp"

namespace skyspec::cli {

/// The parser and its subcommands. Built anew for every command line: the options write into
/// state owned by the commands, so one instance parses once.
struct CliApp {
  CLI::App app;
  std::vector<Command> commands;
  CliApp();
  CliApp(const CliApp&) = delete;
  CliApp& operator=(const CliApp&) = delete;
};

enum class CliMode {
  Run,           ///< what `skyspec` does: run the parsed subcommand
  ValidateOnly,  ///< parse and run the subcommand's checks (Command::validate): no rendering, no files
};

/// Parses argv (argv[0] is the program name), then runs or validates the parsed subcommand.
/// Help, version and error messages go to `out` / `err`; returns the exit code (commands.hpp).
/// In Run mode the SIGINT/SIGTERM handlers are installed before the command runs.
int run_cli(int argc, const char* const* argv, CliMode mode, std::ostream& out, std::ostream& err);

}  // namespace skyspec::cli
