// skyspec command-line front end: parses and validates, then calls the library.
//
// Exit codes: 0 success; 2 bad input (unknown option or key, value out of range, ...);
// 3 an input or output file could not be read or written; 1 an internal error; 4 a job's tasks
// failed or did not run (skyspec job);
// 130 / 143 stopped by SIGINT / SIGTERM (interrupt.hpp), leaving no partial file.
// The application (subcommands, error mapping) is in app.cpp, shared with the fuzzer.

#include <iostream>

#include "app.hpp"

int main(int argc, char** argv) {
  using namespace skyspec::cli;
  return run_cli(argc, argv, CliMode::Run, std::cout, std::cerr);
}
