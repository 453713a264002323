// Stopping long work on request (SIGINT, SIGTERM): a flag that a signal handler may set and that
// every long loop polls.
//
// The library never installs a handler; the program does (cli/interrupt.hpp) and calls
// request_cancellation() from it. Every loop that can run for more than a fraction of a second
// (the scattering-order tables, the sky-view table, the image's bands, time-lapse frames) calls
// throw_if_cancelled() once per unit of work that takes well under a second, so a request stops
// any stage within a second. The exception unwinds through TBB's parallel loops (which cancel
// their other tasks) and through the atomic writers, whose destructors remove their temporary
// files.
#pragma once

#include "skyspec/error.hpp"

namespace skyspec {

/// Thrown by throw_if_cancelled() once a cancellation was requested.
class Cancelled : public Error {
 public:
  explicit Cancelled(int signal_number);
  /// The signal that asked for it (SIGINT, SIGTERM), or 0 for a request without a signal.
  int signal_number() const { return signal_; }
  /// The shell's convention for a process ended by that signal: 128 + its number (130, 143).
  int exit_code() const { return 128 + signal_; }

 private:
  int signal_;
};

/// Asks every long loop to stop. Async-signal-safe (one store to a lock-free flag).
void request_cancellation(int signal_number) noexcept;
/// The signal number of the request, or 0 if there was none (and -1 for a request without one).
int cancellation_requested() noexcept;
/// Throws Cancelled if a cancellation was requested.
void throw_if_cancelled();
/// Forgets the request (a host that goes on after a cancelled call; tests).
void clear_cancellation_request() noexcept;

}  // namespace skyspec
