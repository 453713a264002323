// Fuzz target: the command line, through the real CLI11 application with every subcommand
// (src/cli/app.cpp), in validation-only mode: each subcommand runs its checks (scene loading from
// --preset, --scene, flags and --set; display names; its own values) but renders, reads images
// and writes files never (Command::validate).
//
// The input is the argument list, one argument per line (argv[0] "skyspec" is added). Exit codes
// 0, 2 (bad input) and 3 (unreadable file) are expected; 1 (an internal error: an exception that
// is not skyspec's), another exception, a crash, a sanitizer report or a hang is a finding.
//
// Built with libFuzzer (-DSKYSPEC_FUZZ=ON, clang) or with replay_main.cpp, which runs the corpus
// and the regressions once (CTest fuzz_replay_cli, any compiler).

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <sstream>
#include <string>
#include <vector>

#include "app.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size > 4096) return -1;  // command lines are short
  const std::string text(reinterpret_cast<const char*>(data), size);
  std::vector<std::string> args{"skyspec"};
  size_t start = 0;
  while (start < text.size()) {
    const size_t end = text.find('\n', start);
    args.push_back(text.substr(start, end == std::string::npos ? std::string::npos : end - start));
    if (end == std::string::npos) break;
    start = end + 1;
  }
  if (args.size() > 128) return -1;
  std::vector<const char*> argv;
  for (const auto& a : args) argv.push_back(a.c_str());
  argv.push_back(nullptr);

  std::ostringstream out, err;
  int code = 0;
  try {
    code = skyspec::cli::run_cli(static_cast<int>(args.size()), argv.data(), skyspec::cli::CliMode::ValidateOnly, out,
                                 err);
  } catch (const std::exception& e) {
    err << "exception escaped run_cli: " << e.what() << "\n";
    code = skyspec::cli::kExitInternal;
  }
  if (code == skyspec::cli::kExitInternal) {
    std::fprintf(stderr, "fuzz_cli: internal error (exit code %d) for:\n", code);
    for (const auto& a : args) std::fprintf(stderr, "  [%s]\n", a.c_str());
    std::fprintf(stderr, "%s", err.str().c_str());
    std::abort();
  }
  return 0;
}
