// The subcommands of the skyspec CLI. Each lives in its own file (command_<name>.cpp) and
// registers itself on the application; run_cli() (app.hpp) parses, finds the parsed one, runs it
// and maps exceptions to exit codes.
#pragma once

#include <CLI/CLI.hpp>

#include <functional>

namespace skyspec::cli {

/// Exit codes shared by every subcommand.
constexpr int kExitOk = 0;
constexpr int kExitInternal = 1;
constexpr int kExitBadInput = 2;
constexpr int kExitIo = 3;
/// `skyspec job`: the job ran, but tasks failed or did not run (the summary and manifest say which).
constexpr int kExitTasksFailed = 4;

struct Command {
  CLI::App* app;             ///< the subcommand, to ask whether it was parsed
  std::function<int()> run;  ///< runs it after parsing; returns the exit code
  /// The checks run() makes before any real work (scene, display names, value syntax), without
  /// rendering, reading images or writing files; throws what run() would. Used by the fuzzer
  /// (tests/fuzz/fuzz_cli.cpp, through run_cli with CliMode::ValidateOnly).
  std::function<void()> validate;
};

Command add_render_command(CLI::App& app);
Command add_convert_command(CLI::App& app);
Command add_compare_command(CLI::App& app);
Command add_irradiance_command(CLI::App& app);
Command add_timelapse_command(CLI::App& app);
Command add_aerial_command(CLI::App& app);
Command add_coefficients_command(CLI::App& app);
Command add_job_command(CLI::App& app);
Command add_merge_command(CLI::App& app);
Command add_reference_command(CLI::App& app);
Command add_lee_command(CLI::App& app);
Command add_view_command(CLI::App& app);

}  // namespace skyspec::cli
