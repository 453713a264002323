// skyspec command-line front end: parses and validates, then calls the library.
//
// Exit codes: 0 success; 2 bad input (unknown option or key, value out of range, ...);
// 3 an input or output file could not be read or written; 1 an internal error; 4 a job's tasks
// failed or did not run (skyspec job);
// 130 / 143 stopped by SIGINT / SIGTERM (interrupt.hpp), leaving no partial file.
// The application (subcommands, error mapping) is in app.cpp, shared with the fuzzer.

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <iostream>

#include "app.hpp"
#include "commands.hpp"

int main(int argc, char** argv) {
  using namespace skyspec::cli;
  const int status = run_cli(argc, argv, CliMode::Run, std::cout, std::cerr);
  // What a command printed must have arrived: `skyspec coefficients > /dev/full` is a failure.
  errno = 0;
  std::cout.flush();
  if (!std::cout || std::fflush(stdout) != 0) {
    const int error_number = errno;
    std::cerr << "skyspec: error: cannot write to standard output"
              << (error_number ? std::string(": ") + std::strerror(error_number) : std::string()) << "\n";
    return status == kExitOk ? kExitIo : status;
  }
  return status;
}
