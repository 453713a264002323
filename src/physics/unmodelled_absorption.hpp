// Absorption skyspec does not model, and where it matters: the gas bands that fall on a wavelength
// grid. The atmosphere absorbs through ozone only (ozone.hpp) and the aerosols' extinction/scattering
// ratio; molecular oxygen and water vapour are absent. In the visible their bands are narrow (the
// oxygen A and B bands) or weak; towards the near infrared water vapour removes a large part of
// the sunlight (the 940 nm band). A render whose grid reaches a band says so in its files
// (skyspec:notModelled) instead of being silently wrong there.
#pragma once

#include <string>
#include <vector>

#include "skyspec/spectrum.hpp"

namespace skyspec {

/// One absorption band that is not modelled, nm (approximate edges of the band's strong part).
struct UnmodelledBand {
  const char* absorber;  ///< e.g. "oxygen A band"
  double min_nm, max_nm;
};

/// Every band listed (physics.md, "What is not modelled").
const std::vector<UnmodelledBand>& unmodelled_bands();

/// The bands the grid's samples (with their bandwidth) fall in or span, as one sentence for file
/// headers; names the grid's range, and says so when no band lies within it.
std::string unmodelled_absorption_note(const WavelengthGrid& grid);

}  // namespace skyspec
