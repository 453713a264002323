// Lorenz-Mie averaged over size distributions: the small-particle (dipole) limit of a lognormal
// haze, the extinction paradox of large drops, the normalised scattering matrix (it integrates to
// 1 and its first moment is g), the quadrature's convergence when both steps are halved, and
// distributions the solver cannot reach.

#include <boost/test/unit_test.hpp>

#include <cmath>
#include <complex>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "base/quadrature.hpp"
#include "release_stage.hpp"
#include "skyspec/sphere_ensemble.hpp"
#include "skyspec/units.hpp"

BOOST_AUTO_TEST_SUITE(test_sphere_ensemble)

using namespace skyspec;
using complex = std::complex<double>;

namespace {
double relative(double ours, double theirs) { return std::abs(ours / theirs - 1.0); }
}  // namespace

// Spheres much smaller than the wavelength: <C_sca> = 8 pi / 3 k^4 <r^6> |K|^2 and
// <C_abs> = 4 pi k <r^3> Im K, K = (m^2 - 1) / (m^2 + 2), <r^k> = r_m^k exp(k^2 s^2 / 2).
BOOST_AUTO_TEST_CASE(small_particles_scatter_as_dipoles) {
  const double r_m = 2e-9, sigma = 1.3, s = std::log(sigma), lambda = 550e-9;
  const complex m(1.53, 0.006);
  const SphereEnsembleOptics o =
      sphere_ensemble_optics(SizeDistribution::lognormal(r_m, sigma), m, lambda, 1.0, {1.0, 0.0, -1.0});
  const double k = 2.0 * kPi / lambda;
  const complex kk = (m * m - 1.0) / (m * m + 2.0);
  const double r6 = std::pow(r_m, 6) * std::exp(18.0 * s * s), r3 = std::pow(r_m, 3) * std::exp(4.5 * s * s);
  BOOST_TEST(relative(o.scattering_cross_section_m2, 8.0 * kPi / 3.0 * std::pow(k, 4) * r6 * std::norm(kk)) < 1e-3);
  BOOST_TEST(relative(o.extinction_cross_section_m2 - o.scattering_cross_section_m2, 4.0 * kPi * k * r3 * kk.imag()) <
             1e-3);
  // The dipole's phase function, 3 / (16 pi) (1 + mu^2), and full polarisation at 90 degrees.
  BOOST_TEST(relative(o.phase_matrix[0].s11, 3.0 / (8.0 * kPi)) < 1e-3);
  BOOST_TEST(relative(o.phase_matrix[1].s11, 3.0 / (16.0 * kPi)) < 1e-3);
  BOOST_TEST(o.phase_matrix[1].degree_of_polarisation() > 0.999);
}

// Drops much larger than the wavelength remove twice their geometric cross-section (the
// extinction paradox), approached as Q_ext = 2 + 1.99239 x^(-2/3) + O(x^(-4/3)) (Nussenzveig &
// Wiscombe 1980, Phys. Rev. Lett. 45, 1490, eq. 2); averaged over the lognormal's area,
// <r^(4/3)> / <r^2> = r_m^(-2/3) exp(-10 s^2 / 9).
BOOST_AUTO_TEST_CASE(large_drops_extinguish_twice_their_area) {
  const double r_m = 20e-6, s = std::log(1.2), lambda = 550e-9;
  const SizeDistribution drops = SizeDistribution::lognormal(r_m, 1.2);
  const SphereEnsembleOptics o = sphere_ensemble_optics(drops, complex(1.333, 1e-8), lambda, 1.0, {1.0});
  BOOST_TEST(relative(o.geometric_cross_section_m2, kPi * drops.moment(2)) < 1e-6);
  const double q = o.extinction_cross_section_m2 / o.geometric_cross_section_m2;
  const double x_m = 2.0 * kPi * r_m / lambda;
  const double expected = 2.0 + 1.99239 * std::pow(x_m, -2.0 / 3.0) * std::exp(-10.0 * s * s / 9.0);
  BOOST_TEST_MESSAGE("lognormal 20 um drops at 550 nm: <C_ext> / (pi <r^2>) = " << q << ", asymptotic " << expected);
  BOOST_TEST(std::abs(q - expected) < 1e-3);
}

// P_11 integrates to 1 over the sphere, its first moment is g, and |P_12|, |P_33|, |P_34| <= P_11,
// for an accumulation-mode aerosol and small cloud droplets (Gauss-Legendre in mu, 2000 nodes, for
// the droplets' forward peak).
BOOST_AUTO_TEST_CASE(phase_matrix_is_normalised, *boost::unit_test::precondition(test::not_in_sanitizer_stage)) {
  std::vector<double> mu, w;
  gauss_legendre(2000, -1.0, 1.0, mu, w);
  const struct {
    SizeDistribution sizes;
    complex m;
  } cases[] = {{SizeDistribution::lognormal(0.1e-6, 1.6), complex(1.45, 0.003)},
               {SizeDistribution::modified_gamma(2e-6, 6.0, 1.0), complex(1.333, 1e-8)}};
  for (const auto& c : cases) {
    const SphereEnsembleOptics o = sphere_ensemble_optics(c.sizes, c.m, 550e-9, 1.0, mu);
    double norm = 0.0, first = 0.0;
    for (size_t j = 0; j < mu.size(); ++j) {
      norm += 2.0 * kPi * w[j] * o.phase_matrix[j].s11;
      first += 2.0 * kPi * w[j] * mu[j] * o.phase_matrix[j].s11;
      const SphereScatteringMatrix& p = o.phase_matrix[j];
      BOOST_TEST((std::abs(p.s12) <= p.s11 && std::abs(p.s33) <= p.s11 && std::abs(p.s34) <= p.s11));
    }
    BOOST_TEST_CONTEXT(c.sizes.description()) {
      BOOST_TEST(std::abs(norm - 1.0) < 1e-4);
      BOOST_TEST(std::abs(first - o.asymmetry) < 1e-4);
      BOOST_TEST(o.single_scattering_albedo() <= 1.0);
      BOOST_TEST_MESSAGE(c.sizes.description() << ": g " << o.asymmetry << ", albedo " << o.single_scattering_albedo()
                                               << ", " << o.radius_nodes << " nodes");
    }
  }
}

// Halving both quadrature steps changes <C_ext>, <C_sca> and g by less than 2e-4, P_11 at 0 and
// 138 degrees (the rainbow) by less than 2e-3, at 90 degrees by less than 1e-2; at 180 degrees,
// where narrow resonances that the rule samples rather than resolves dominate (the glory), by
// less than 5e-2. An aerosol, a fog and drizzle (Marshall-Palmer cut to 50-150 um).
BOOST_AUTO_TEST_CASE(quadrature_converges, *boost::unit_test::precondition(test::not_in_sanitizer_stage)) {
  const std::vector<double> mu = {1.0, std::cos(138.0 * kPi / 180.0), 0.0, -1.0};
  const double limits[] = {2e-3, 2e-3, 1e-2, 5e-2};
  const struct {
    SizeDistribution sizes;
    complex m;
    double wavelength_m;
  } cases[] = {{SizeDistribution::lognormal(0.1e-6, 2.0), complex(1.45, 0.003), 450e-9},
               {SizeDistribution::modified_gamma(8e-6, 3.0, 1.0), complex(1.333, 1e-8), 550e-9},
               {SizeDistribution::marshall_palmer(2.0).truncated(0.05e-3, 0.15e-3), complex(1.331, 1e-8), 650e-9}};
  for (const auto& c : cases) {
    const SphereEnsembleOptics a = sphere_ensemble_optics(c.sizes, c.m, c.wavelength_m, 1.0, mu);
    SphereEnsembleSettings fine;
    fine.panel_ln_radius /= 2.0;
    fine.panel_size_parameter /= 2.0;
    const SphereEnsembleOptics b = sphere_ensemble_optics(c.sizes, c.m, c.wavelength_m, 1.0, mu, fine);
    BOOST_TEST_CONTEXT(c.sizes.description() << " at " << c.wavelength_m * 1e9 << " nm") {
      const double integrals = std::max({relative(a.extinction_cross_section_m2, b.extinction_cross_section_m2),
                                         relative(a.scattering_cross_section_m2, b.scattering_cross_section_m2),
                                         std::abs(a.asymmetry - b.asymmetry)});
      BOOST_TEST(integrals < 2e-4);
      std::ostringstream angles;
      for (size_t j = 0; j < mu.size(); ++j) {
        const double change = relative(a.phase_matrix[j].s11, b.phase_matrix[j].s11);
        BOOST_TEST(change < limits[j], "P_11 at " << std::acos(mu[j]) * 180.0 / kPi << " deg");
        angles << ", P_11(" << std::round(std::acos(mu[j]) * 180.0 / kPi) << " deg) " << change;
      }
      BOOST_TEST_MESSAGE(c.sizes.description()
                         << " at " << c.wavelength_m * 1e9 << " nm, " << a.radius_nodes
                         << " nodes: halving the steps changes C_ext, C_sca, g by " << integrals << angles.str());
    }
  }
}

// OPAC's sulfate droplets at 99 % humidity (lognormal) and fog (modified gamma) at 550 nm, from the
// size distributions and refractive indices OPAC states: the asymmetry parameter and the single
// scattering albedo within 0.005 of OPAC's, the extinction per particle within 1 % (OPAC prints
// four digits; tests/data/mie/opac_components.csv says where the values come from).
BOOST_AUTO_TEST_CASE(opac_components_at_550nm) {
  std::ifstream in(std::string(SKYSPEC_TEST_DATA_DIR) + "/mie/opac_components.csv");
  BOOST_REQUIRE(in);
  std::string line;
  int checked = 0;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#' || line.rfind("component,", 0) == 0) continue;
    std::vector<std::string> f;
    std::stringstream fields(line);
    for (std::string v; std::getline(fields, v, ',');) f.push_back(v);
    BOOST_REQUIRE(f.size() == 12u);
    const auto num = [&f](size_t i) { return std::stod(f[i]); };
    const SizeDistribution shape =
        f[1] == "lognormal" ? SizeDistribution::lognormal(num(2) * 1e-6, num(3))
                            // n = A r^alpha exp(-B r^gamma), r in um: mode radius (alpha / (gamma B))^(1/gamma) um
                            : SizeDistribution::modified_gamma(
                                  std::pow(num(2) / (num(4) * num(3)), 1.0 / num(4)) * 1e-6, num(2), num(4));
    const SizeDistribution sizes = shape.truncated(num(5) * 1e-6, num(6) * 1e-6);
    const SphereEnsembleOptics o = sphere_ensemble_optics(sizes, complex(num(7), num(8)), 550e-9, 1.0, {});
    // 1 particle per cm^3 = 1e6 m^-3; 1 / km = 1e-3 / m.
    const double ext_per_km = o.extinction_cross_section_m2 * 1e6 * 1e3;
    BOOST_TEST_MESSAGE(f[0] << ": g " << o.asymmetry << " (OPAC " << f[11] << "), albedo "
                            << o.single_scattering_albedo() << " (" << f[10] << "), extinction " << ext_per_km
                            << " / km per particle / cm^3 (" << f[9] << ")");
    BOOST_TEST_CONTEXT(f[0]) {
      BOOST_TEST(std::abs(o.asymmetry - num(11)) < 0.005);
      BOOST_TEST(std::abs(o.single_scattering_albedo() - num(10)) < 0.005);
      BOOST_TEST(std::abs(ext_per_km / num(9) - 1.0) < 0.01);
    }
    ++checked;
  }
  BOOST_TEST(checked == 2);
}

BOOST_AUTO_TEST_CASE(out_of_reach_is_refused) {
  // Rain drops of several millimetres: size parameters far above 2e4 at visible wavelengths.
  try {
    sphere_ensemble_optics(SizeDistribution::marshall_palmer(5.0), complex(1.333, 0.0), 500e-9, 1.0, {1.0});
    BOOST_FAIL("no error");
  } catch (const std::invalid_argument& e) {
    BOOST_TEST(std::string(e.what()).find("truncate the distribution") != std::string::npos);
  }
  const SizeDistribution haze = SizeDistribution::lognormal(0.1e-6, 2.0);
  BOOST_CHECK_THROW(sphere_ensemble_optics(haze, complex(1.5, 0.0), 0.0, 1.0, {1.0}), std::invalid_argument);
  BOOST_CHECK_THROW(sphere_ensemble_optics(haze, complex(1.5, 0.0), 500e-9, 0.5, {1.0}), std::invalid_argument);
  BOOST_CHECK_THROW(sphere_ensemble_optics(haze, complex(1.5, 0.0), 500e-9, 1.0, {1.5}), std::invalid_argument);
  BOOST_CHECK_THROW(sphere_ensemble_optics(haze, complex(1.5, -0.1), 500e-9, 1.0, {1.0}), std::invalid_argument);
}

BOOST_AUTO_TEST_SUITE_END()
