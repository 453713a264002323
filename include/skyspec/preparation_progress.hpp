// How far the preparation of a render has come: the longest steps before the first pixel, each
// once per atmosphere (their results are cached): a microphysical aerosol's optics, then the
// scattering-order tables. Process-wide, like skyspec/cancellation.hpp: each builder names its
// phase and counts the work it plans and finishes in units of its own (rays traced; component
// and wavelength pairs), and a host reads it from a thread of its own to draw a progress bar
// (the CLI, the Python module). A new phase starts its counts from zero.
#pragma once

namespace skyspec {

struct PreparationProgress {
  long long done = 0;     ///< units finished in this phase
  long long planned = 0;  ///< units planned in this phase (0: nothing being built since the last reset)
  /// What is being prepared, e.g. "building the scattering tables" ("" when nothing is).
  const char* what = "";
  /// Counts the phases since the last reset: a host restarts its time estimate when it changes.
  long long phase = 0;
  /// done / planned, 0 when nothing is planned.
  double fraction() const { return planned > 0 ? static_cast<double>(done) / static_cast<double>(planned) : 0.0; }
};

/// The work planned and finished since the last reset, by every build in the process.
PreparationProgress preparation_progress() noexcept;
/// Forgets the counts (a host, before a call whose preparation it shows).
void reset_preparation_progress() noexcept;

}  // namespace skyspec
