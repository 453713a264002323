// Stopping long work on request: a process-wide flag that every long loop of the library polls.
//
// The library never installs a signal handler. A program does (the CLI's SIGINT/SIGTERM/SIGHUP
// handler calls request_cancellation), or a host that waits for a call on another thread asks
// (the Python module, on Ctrl-C). Every loop that can run for more than a fraction of a second
// (the scattering-order tables, the optical-depth and sky-view tables, the image's rows, the Monte
// Carlo's estimates, time-lapse frames) polls it once per unit of work that takes well under a
// second, and a request makes the call under way throw Cancelled: its unfinished output files are
// removed on the way out. The flag is process-wide: a request stops every call under way.
#pragma once

#include "skyspec/error.hpp"

namespace skyspec {

/// Thrown by a long call once a cancellation was requested.
class Cancelled : public Error {
 public:
  explicit Cancelled(int signal_number);
  /// The signal that asked for it (SIGINT, SIGTERM, SIGHUP), or 0 for a request without a signal.
  int signal_number() const { return signal_; }
  /// The shell's convention for a process ended by that signal: 128 + its number (130, 143).
  int exit_code() const { return 128 + signal_; }

 private:
  int signal_;
};

/// Asks every long call under way to stop. Async-signal-safe (one store to a lock-free flag).
/// signal_number: the signal that asked (0: a request without one).
void request_cancellation(int signal_number) noexcept;
/// The signal number of the request, -1 for a request without one, 0 if there was none.
int cancellation_requested() noexcept;
/// Forgets the request, so that later calls run (a host that goes on after a cancelled call).
void clear_cancellation_request() noexcept;

}  // namespace skyspec
