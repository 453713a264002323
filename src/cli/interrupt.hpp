// SIGINT / SIGTERM / SIGHUP: stop the long loops instead of being killed mid-write.
//
// The default action of both signals ends the process without unwinding the stack, so the atomic
// writers' temporary files ("<name>.tmp-...") would be left behind. install_interrupt_handlers()
// replaces it by a handler that only records the request (base/cancellation.hpp); every long loop
// of the library polls it (throw_if_cancelled: the scattering tables per table entry, the image
// per band, ...) and throws Cancelled, and main() maps that to the shell's convention, 128 +
// signal number (130, 143). Unwinding runs the writers' destructors, which remove their temporary
// files. A second signal gets the default action (the handler is installed with SA_RESETHAND), so
// it still kills at once.
#pragma once

#include "base/cancellation.hpp"

namespace skyspec::cli {

using Interrupted = skyspec::Cancelled;

/// Installs the SIGINT, SIGTERM and SIGHUP handlers (once, before running a command).
void install_interrupt_handlers();
/// Throws Interrupted if a signal was received.
inline void throw_if_interrupted() { skyspec::throw_if_cancelled(); }

}  // namespace skyspec::cli
