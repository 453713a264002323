// SIGINT / SIGTERM: stop between bands of rows instead of being killed mid-write.
//
// The default action of both signals ends the process without unwinding the stack, so the atomic
// writers' temporary files ("<name>.tmp-...") would be left behind. install_interrupt_handlers()
// replaces it by a handler that only records the signal; the long loops poll it through
// throw_if_interrupted() (ProgressBar::update calls it after every band), which throws
// Interrupted, and main() maps that to the shell's convention, 128 + signal number (130, 143).
// Unwinding runs the writers' destructors, which remove their temporary files. A second signal
// gets the default action (the handler is installed with SA_RESETHAND), so it still kills at once.
#pragma once

#include "skyspec/error.hpp"

namespace skyspec::cli {

class Interrupted : public Error {
 public:
  explicit Interrupted(int signal_number);
  int signal_number() const { return signal_; }
  /// 128 + the signal number.
  int exit_code() const { return 128 + signal_; }

 private:
  int signal_;
};

/// Installs the SIGINT and SIGTERM handlers (once, before running a command).
void install_interrupt_handlers();
/// The signal received since install_interrupt_handlers(), or 0.
int pending_interrupt();
/// Throws Interrupted if a signal was received.
void throw_if_interrupted();

}  // namespace skyspec::cli
