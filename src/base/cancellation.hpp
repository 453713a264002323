// The polling side of cancellation (the public side, skyspec/cancellation.hpp: the flag, the
// request, the exception).
//
// Every loop that can run for more than a fraction of a second calls throw_if_cancelled() once
// per unit of work that takes well under a second, so a request stops any stage within a second.
// The exception unwinds through TBB's parallel loops (which cancel their other tasks) and through
// the atomic writers, whose destructors remove their temporary files.
#pragma once

#include "skyspec/cancellation.hpp"

namespace skyspec {

/// Throws Cancelled if a cancellation was requested.
void throw_if_cancelled();

}  // namespace skyspec
