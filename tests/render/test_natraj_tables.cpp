// skyspec's vector transport (single scattering marched along the ray, higher orders from the
// polarised scattering-order tables: SkyRenderer::stokes) against the published plane-parallel
// Rayleigh tables of Natraj, Li & Yung (2009, ApJ 691, 1909), the corrected Coulson, Dave &
// Sekera (1960) tables: I, Q and U leaving the top and reaching the bottom of a conservative,
// non-depolarising Rayleigh layer over a Lambertian ground, for 7 sun and 16 view zenith cosines
// and 7 relative azimuths.
//
// The plane-parallel limit, as skyspec is configured for it (docs/validation.md): a planet of
// radius 1e9 m (the largest allowed) under a homogeneous layer 100 m thick (atmosphere.rayleigh.profile
// = "constant"), so that a ray 1.15 degrees from the horizontal (mu = 0.02) crosses it along a
// path within 0.013 % of the plane-parallel one (a 1 km layer's curvature showed at such grazing
// views under a low sun: docs/validation.md, "The published Rayleigh tables"); typed-in Rayleigh
// coefficients (no depolarisation: gamma = 0) giving the optical thickness; no aerosol, no ozone; a flat solar spectrum
// of 1 W m^-2 nm^-1, so that pi I / F0 is pi times the radiance. Tables finer than the default: here 128 sun angles, 32
// altitudes and 10 orders, in the bench 192, 64 and 20; the limits are the issue's: I within 0.5 % (or 1e-4 where it is
// small), Q and U within 0.002.
//
// The case here (optical thickness 0.25, ground albedo 0.25, every geometry; tests/data/natraj2009)
// runs in the release stage; bench/natraj_tables.sh runs all 18 (six thicknesses, three albedos)
// from ../shared/reference/natraj2009 with the case all_published_tables.

#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "natraj_tables.hpp"
#include "release_stage.hpp"
#include "scene_fixtures.hpp"
#include "skyspec/geometry.hpp"
#include "skyspec/render.hpp"
#include "skyspec/units.hpp"

BOOST_AUTO_TEST_SUITE(test_natraj_tables)

using namespace skyspec;

namespace {

using test::kNatrajAlbedos;
using test::kNatrajAzimuthsDeg;
using test::kNatrajSunCosines;
using test::kNatrajViewCosines;

// The limits.
constexpr double kRelativeI = 0.005, kAbsoluteI = 1e-4, kAbsoluteQU = 0.002;

// The scattering-order tables' settings.
struct TableSettings {
  int orders, sun_samples, altitude_samples;
};
constexpr TableSettings kTestTables{10, 128, 32}, kBenchTables{20, 192, 64};

// The plane-parallel limit (above): the camera at the bottom (looking up) or the top (looking down).
Scene plane_parallel_scene(double tau, double albedo, double mu0, bool at_top, const TableSettings& tables) {
  const double thickness_m = 100.0, beta = tau / thickness_m;
  char toml[1200];
  std::snprintf(toml, sizeof toml,
                "[planet]\nradius_m = 1e9\n[atmosphere]\ntop_altitude_m = %g\n"
                "[atmosphere.rayleigh]\nsource = \"fixed\"\nwavelengths_nm = [550, 560]\n"
                "beta_per_m = [%.15g, %.15g]\nprofile = \"constant\"\n"
                "[atmosphere.mie]\nenabled = false\n[atmosphere.ozone]\nenabled = false\n"
                "[ground]\nalbedo = %g\n[spectrum]\nwavelengths_nm = [550, 560]\n"
                "[sun]\nspectrum = \"flat\"\nspectral_irradiance = 1\nelevation_deg = %.15g\nazimuth_deg = 0\n"
                "[camera]\nwidth = 1\nheight = 1\nposition_m = [0, 0, %g]\n[output]\npolarisation = true\n"
                "[render]\ncache_tables = false\nsky_view_table = false\nscattering_orders = %d\n"
                "ms_angular_degree = 2\nms_sun_samples = %d\nms_altitude_samples = %d\n",
                thickness_m, beta, beta, albedo, radians_to_degrees(std::asin(mu0)), at_top ? thickness_m : 0.0,
                tables.orders, tables.sun_samples, tables.altitude_samples);
  return test::scene_with(toml, "default");
}

struct Worst {
  double i = 0.0, q = 0.0,
         u = 0.0;           // I: the largest excess over the limit's scale (relative, or absolute / 1e-4 * 0.5 %)
  double i_relative = 0.0;  // the largest relative difference of I
  std::string where_i, where_q, where_u;
  int failures = 0, values = 0;
};

// Compares one optical thickness and albedo, UP or DN, at every geometry.
Worst compare(const std::string& folder, const std::string& tau_text, int albedo, bool up,
              const TableSettings& tables) {
  const char* kinds = "IQU";
  std::array<test::NatrajTable, 3> published;
  for (int c = 0; c < 3; ++c)
    published[static_cast<size_t>(c)] =
        test::read_natraj_table(folder + "/" + kinds[c] + (up ? "_UP_TAU_" : "_DN_TAU_") + tau_text);
  const double tau = std::stod(tau_text);
  Worst w;
  for (size_t s = 0; s < kNatrajSunCosines.size(); ++s) {
    const SkyRenderer renderer(
        plane_parallel_scene(tau, kNatrajAlbedos[static_cast<size_t>(albedo)], kNatrajSunCosines[s], up, tables));
    for (int v = 0; v < kNatrajViewCosines; ++v) {
      const int sun = static_cast<int>(s);
      const double mu = published[0].row(albedo, sun, v)[1];
      for (size_t p = 0; p < kNatrajAzimuthsDeg.size(); ++p) {
        // The line of sight at azimuth phi from the sun's (north), up or down at arcsin(mu); the
        // Stokes frame's first axis horizontal (r), so that Q = I_r - I_l as the tables have it.
        const double azimuth = kNatrajAzimuthsDeg[p], a = degrees_to_radians(azimuth);
        const Vec3 dir = direction_from_angles(azimuth, (up ? -1.0 : 1.0) * radians_to_degrees(std::asin(mu)));
        Spectrum i, q, u;
        renderer.stokes(dir, Vec3(std::cos(a), -std::sin(a), 0.0), i, q, u);
        const double I = kPi * i[0], Q = kPi * q[0], U = kPi * u[0];
        const double I0 = published[0].row(albedo, sun, v)[2 + p];
        const double Q0 = published[1].row(albedo, sun, v)[2 + p];
        const double U0 = published[2].row(albedo, sun, v)[2 + p];
        char where[96];
        std::snprintf(where, sizeof where, "mu0 %.2f, mu %.2f, phi %.0f", kNatrajSunCosines[s], mu, azimuth);
        const double di = std::abs(I - I0), excess_i = std::min(di / (kRelativeI * I0), di / kAbsoluteI);
        if (excess_i > w.i) w.i = excess_i, w.where_i = where;
        if (I0 > 0.0 && di / I0 > w.i_relative) w.i_relative = di / I0;
        if (std::abs(Q - Q0) > w.q) w.q = std::abs(Q - Q0), w.where_q = where;
        if (std::abs(U - U0) > w.u) w.u = std::abs(U - U0), w.where_u = where;
        w.failures += (excess_i > 1.0) + (std::abs(Q - Q0) > kAbsoluteQU) + (std::abs(U - U0) > kAbsoluteQU);
        w.values += 3;
      }
    }
  }
  return w;
}

void report(const std::string& tau, int albedo, bool up, const Worst& w) {
  std::printf("| %s | %g | %s | %.3f %% | %.2f (%s) | %.5f (%s) | %.5f (%s) | %d of %d |\n", tau.c_str(),
              kNatrajAlbedos[static_cast<size_t>(albedo)], up ? "top (UP)" : "bottom (DN)", 100.0 * w.i_relative, w.i,
              w.where_i.c_str(), w.q, w.where_q.c_str(), w.u, w.where_u.c_str(), w.failures, w.values);
}

boost::test_tools::assertion_result with_published_folder(boost::unit_test::test_unit_id) {
  boost::test_tools::assertion_result result(std::getenv("SKYSPEC_NATRAJ_DIR") != nullptr);
  result.message() << "set SKYSPEC_NATRAJ_DIR to the folder of all the tables (bench/natraj_tables.sh)";
  return result;
}

}  // namespace

// The columns of the printed rows (docs/validation.md): I's largest relative difference, I's
// largest difference as a fraction of the limit (1 = at the limit), Q's and U's largest absolute
// differences, and the values outside the limits.
BOOST_AUTO_TEST_CASE(rayleigh_layer_of_optical_thickness_0_25,
                     *boost::unit_test::precondition(test::not_in_sanitizer_stage)) {
  const std::string folder = std::string(SKYSPEC_TEST_DATA_DIR) + "/natraj2009";
  for (const bool up : {false, true}) {
    const Worst w = compare(folder, "0.25", 1, up, kTestTables);
    report("0.25", 1, up, w);
    BOOST_TEST(w.values == 3 * 7 * 16 * 7);
    BOOST_TEST(w.i <= 1.0, "I: " << w.i << " of the limit at " << w.where_i);
    BOOST_TEST(w.q <= kAbsoluteQU, "Q: " << w.q << " at " << w.where_q);
    BOOST_TEST(w.u <= kAbsoluteQU, "U: " << w.u << " at " << w.where_u);
  }
}

BOOST_AUTO_TEST_CASE(all_published_tables,
                     *boost::unit_test::disabled() * boost::unit_test::precondition(with_published_folder)) {
  const std::string folder = std::getenv("SKYSPEC_NATRAJ_DIR");
  // SKYSPEC_NATRAJ_TAUS (bench/natraj_tables.sh --taus): a comma-separated subset of the thicknesses.
  const char* only = std::getenv("SKYSPEC_NATRAJ_TAUS");
  const std::string subset = only ? "," + std::string(only) + "," : "";
  int compared = 0;
  for (const char* tau : {"0.02", "0.05", "0.1", "0.25", "0.5", "1"}) {
    if (only && subset.find("," + std::string(tau) + ",") == std::string::npos) continue;
    ++compared;
    for (int albedo = 0; albedo < 3; ++albedo)
      for (const bool up : {false, true}) {
        const Worst w = compare(folder, tau, albedo, up, kBenchTables);
        report(tau, albedo, up, w);
        std::fflush(stdout);
        BOOST_TEST(w.failures == 0);
      }
  }
  BOOST_TEST(compared > 0,
             "SKYSPEC_NATRAJ_TAUS = \"" << (only ? only : "") << "\" names none of 0.02, 0.05, 0.1, 0.25, 0.5, 1");
}

BOOST_AUTO_TEST_SUITE_END()
