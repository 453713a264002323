// How far the preparation of a render has come: the scattering-order tables being built, the
// longest step before the first pixel (once per atmosphere: they are cached). Process-wide, like
// skyspec/cancellation.hpp: the builders count the work they plan and the work they finish, in
// units of equal cost (rays traced), and a host reads it from a thread of its own to draw a
// progress bar (the CLI, the Python module).
#pragma once

namespace skyspec {

struct PreparationProgress {
  long long done = 0;     ///< units finished
  long long planned = 0;  ///< units planned (0: nothing being built since the last reset)
  /// done / planned, 0 when nothing is planned.
  double fraction() const { return planned > 0 ? static_cast<double>(done) / static_cast<double>(planned) : 0.0; }
};

/// The work planned and finished since the last reset, by every build in the process.
PreparationProgress preparation_progress() noexcept;
/// Forgets the counts (a host, before a call whose preparation it shows).
void reset_preparation_progress() noexcept;

}  // namespace skyspec
