// A medium: one scatterer or absorber of the atmosphere (air, an aerosol, ozone, ...), evaluated
// on the wavelength grid. What light transport needs of it, and all it needs:
//
//   beta_sca(lambda, z) = scattering_per_m(lambda) rho(z),  beta_ext(lambda, z) = extinction_per_m(lambda) rho(z),
//
// with rho(z) its density relative to altitude 0 (`profile`), and how it scatters: its phase
// function (or its whole scattering matrix) per wavelength. Optical depth, single scattering, the
// scattering-order tables, their cache key and the Monte Carlo reference all iterate the
// atmosphere's media (AtmosphereModel::media()); none of them names a medium.
//
// A new medium is one file in src/physics/ with a function that builds it from the scene's
// AtmosphereSpec, plus one entry in the list of media (src/physics/media.cpp); docs/architecture.md
// ("the files you touch") has the recipe.
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "skyspec/density_profile.hpp"
#include "skyspec/phase_function.hpp"
#include "skyspec/spectrum.hpp"
#include "skyspec/tabulated_scattering.hpp"
#include "skyspec/vertical_cylinder.hpp"

namespace skyspec {

/// At most this many media in one atmosphere (light transport keeps a column per medium in fixed
/// arrays); the list (medium_registry(), src/physics/media/) has seven, so one of a user's own fits.
constexpr int kMaxMedia = 8;

/// How a medium scatters, per wavelength: one of four forms.
struct MediumPhase {
  enum class Kind {
    /// Absorbs only (ozone).
    None,
    /// Scattering by molecules (Chandrasekhar's anisotropic Rayleigh scattering): the phase
    /// function A + B mu^2 and its polarisation from gamma(lambda) (phase_function.hpp,
    /// scattering_matrix.hpp). Light transport resolves its polarisation exactly in every order.
    Rayleigh,
    /// An analytic phase function (Henyey-Greenstein or Cornette-Shanks) with an asymmetry
    /// parameter per wavelength; it does not polarise.
    Analytic,
    /// A scattering matrix tabulated per wavelength (from Lorenz-Mie theory or any other source):
    /// phase function a1, and b1 (P12), which polarises its singly scattered light.
    Tabulated
  };
  Kind kind = Kind::None;
  SpectrumD rayleigh_gamma;  ///< Rayleigh: gamma per wavelength (0 = no depolarisation)
  AerosolPhase::Model analytic_model = AerosolPhase::Model::CornetteShanks;  ///< Analytic
  SpectrumD g;  ///< Analytic: the asymmetry per wavelength; Tabulated: the table's (for reports)
  std::shared_ptr<const TabulatedScatteringMatrix> matrix;  ///< Tabulated

  /// The phase function of wavelength i at mu = cosine of the scattering angle (sr^-1).
  double at(int i, double mu) const;
  /// True when the phase function's shape differs between wavelengths (beyond Rayleigh's gamma):
  /// a table, or an analytic function whose asymmetry differs.
  bool varies_with_wavelength() const;
  /// The analytic function of wavelength i.
  AerosolPhase analytic(int i) const { return AerosolPhase{analytic_model, g[i]}; }
};

struct Medium {
  /// Its name in reports, in the tables' cache key and in the Monte Carlo's components:
  /// "air", "aerosol", "ozone".
  std::string name;
  DensityProfile profile;
  SpectrumD scattering_per_m;  ///< at relative density 1, per wavelength
  SpectrumD extinction_per_m;  ///< at relative density 1, per wavelength (>= scattering)
  MediumPhase phase;
  /// Where it is: everywhere (empty: a spherical shell, rho(z) at every point of altitude z), or
  /// only inside a vertical cylinder (a rain shower: rho(z) inside, 0 outside). The integrator cuts
  /// its rays at the walls and takes the sun's light through the cylinder by its chord; the Monte
  /// Carlo tracks it in three dimensions; the scattering-order tables hold the light field of the
  /// atmosphere without it, which it scatters (AtmosphereModel::with_regional_media_as_probes).
  std::optional<VerticalCylinder> region;

  /// Extinguishes light at some wavelength.
  bool enabled() const { return extinction_per_m.size() > 0 && extinction_per_m.maxCoeff() > 0.0; }
  /// Scatters light (a phase function and a scattering coefficient > 0 somewhere). A scattering
  /// medium's profile must be positive everywhere (DensityProfile::positive_everywhere): the
  /// integrator's log-mean rule needs it; an absorber's may be a layer.
  bool scatters() const {
    return phase.kind != MediumPhase::Kind::None && scattering_per_m.size() > 0 && scattering_per_m.maxCoeff() > 0.0;
  }
};

}  // namespace skyspec
