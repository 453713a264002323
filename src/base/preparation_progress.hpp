// The counting side of skyspec/preparation_progress.hpp: a builder plans its work before it starts
// and adds what it finishes as it goes (from any thread; lock-free).
#pragma once

#include "skyspec/preparation_progress.hpp"

namespace skyspec {

/// Plans `units` more of the phase `what` (a string literal that outlives the process's builds);
/// a `what` other than the current phase's starts a new phase with its counts at zero.
void plan_preparation(long long units, const char* what) noexcept;
void finish_preparation(long long units) noexcept;

}  // namespace skyspec
