#include <boost/test/unit_test.hpp>

#include <Eigen/Geometry>
#include <cmath>
#include <limits>

#include "atmosphere_fixtures.hpp"
#include "skyspec/camera.hpp"
#include "skyspec/phase_function.hpp"
#include "transport/single_scattering.hpp"

BOOST_AUTO_TEST_SUITE(test_single_scattering)

using namespace skyspec;

namespace {
constexpr double R = 6360e3;
const std::vector<double> kNm = {440, 550, 680};
const std::vector<double> kBetaR = {33.1e-6, 13.5e-6, 5.8e-6};

struct ZeroSunColumns : SunColumns {
  Columns at(double, double) const override { return {0.0, 0.0}; }
};

Spectrum radiance(const SingleScattering& ss, const Vec3& o, const Vec3& d, const Vec3& s, float e_sun = 1.0f) {
  const int n = ss.atmosphere().grid().size();
  ScatteringWorkspace ws(n);
  Spectrum out(n);
  ss.radiance(o, d, s, Spectrum::Constant(n, e_sun), ws, out);
  return out;
}
}  // namespace

// The seed talk's closed form for a homogeneous medium lit without attenuation:
// L = E beta_sca p / beta_ext (1 - exp(-beta_ext s)).
BOOST_AUTO_TEST_CASE(constant_density_unattenuated_sun_matches_closed_form) {
  const double top = 10e3, h = 1.0;
  const AtmosphereModel atm(test::simple_atmosphere(ProfileKind::Constant, top, kNm, kBetaR, 21e-6),
                            WavelengthGrid::from_list(kNm));
  const ZeroSunColumns zero;
  const SingleScattering ss(atm, zero, {16});
  const Vec3 o(0, 0, R + h), up(0, 0, 1);
  const Vec3 sun = direction_from_angles(0, 40);
  const Spectrum L = radiance(ss, o, up, sun, 2.0f);
  const double mu = up.dot(sun), s = top - h;
  for (int i = 0; i < 3; ++i) {
    const double br = kBetaR[static_cast<size_t>(i)], bm = 21e-6, bext = br + 1.1 * bm;
    const double expected =
        2.0 * (br * rayleigh_phase(mu) + bm * cornette_shanks_phase(mu, 0.76)) / bext * (1 - std::exp(-bext * s));
    BOOST_TEST(static_cast<double>(L[i]) == expected, boost::test_tools::tolerance(2e-6));
  }
}

// With the real sun table: sun at the zenith, view up through a homogeneous shell. Every point
// sees the same total optical depth beta_ext * s, so L = E (beta_R p_R + beta_M p_M) s exp(-beta_ext s).
BOOST_AUTO_TEST_CASE(constant_density_sun_at_zenith_matches_closed_form) {
  const double top = 10e3, h = 1.0;
  const AtmosphereModel atm(test::simple_atmosphere(ProfileKind::Constant, top, kNm, kBetaR, 21e-6),
                            WavelengthGrid::from_list(kNm));
  const SunColumnTable table(atm, {256, 512, 64});
  const TableSunColumns cols(table);
  const SingleScattering ss(atm, cols, {16});
  const Vec3 o(0, 0, R + h), up(0, 0, 1);
  const Spectrum L = radiance(ss, o, up, up);
  const double s = top - h;
  for (int i = 0; i < 3; ++i) {
    const double br = kBetaR[static_cast<size_t>(i)], bm = 21e-6, bext = br + 1.1 * bm;
    const double expected = (br * rayleigh_phase(1) + bm * cornette_shanks_phase(1, 0.76)) * s * std::exp(-bext * s);
    BOOST_TEST(static_cast<double>(L[i]) == expected, boost::test_tools::tolerance(1e-4));
  }
}

// Exponential atmosphere, thin limit: with tiny coefficients, extinction vanishes and the zenith
// radiance is E beta p times the vertical column H (1 - exp(-top / H)).
BOOST_AUTO_TEST_CASE(optically_thin_exponential_zenith_is_the_column) {
  const double top = 60e3;
  const std::vector<double> tiny = {1e-12, 1e-12, 1e-12};
  const AtmosphereModel atm(test::simple_atmosphere(ProfileKind::Exponential, top, kNm, tiny, 0.0),
                            WavelengthGrid::from_list(kNm));
  const SunColumnTable table(atm, {128, 256, 64});
  const TableSunColumns cols(table);
  const SingleScattering ss(atm, cols, {32});
  const Vec3 up(0, 0, 1);
  const Spectrum L = radiance(ss, Vec3(0, 0, R), up, direction_from_angles(0, 30));
  const double expected = 1e-12 * rayleigh_phase(0.5) * 8000 * (1 - std::exp(-top / 8000));
  BOOST_TEST(static_cast<double>(L[0]) == expected, boost::test_tools::tolerance(1e-5));
}

// The night side receives no single scattering: sun 30 degrees below the horizon, the whole
// 60 km column above the camera is in the planet's shadow.
BOOST_AUTO_TEST_CASE(planet_shadow_gives_black_zenith) {
  const AtmosphereModel atm(test::simple_atmosphere(ProfileKind::Exponential, 60e3, kNm, kBetaR, 21e-6),
                            WavelengthGrid::from_list(kNm));
  const SunColumnTable table(atm, {64, 128, 32});
  const TableSunColumns cols(table);
  const SingleScattering ss(atm, cols, {32});
  const Spectrum L = radiance(ss, Vec3(0, 0, R + 1), Vec3(0, 0, 1), direction_from_angles(0, -30));
  BOOST_TEST(L.maxCoeff() == 0.0f);
  // At -3 degrees the upper atmosphere is still lit: twilight.
  const Spectrum twilight = radiance(ss, Vec3(0, 0, R + 1), Vec3(0, 0, 1), direction_from_angles(0, -3));
  BOOST_TEST(twilight.minCoeff() > 0.0f);
}

BOOST_AUTO_TEST_CASE(views_from_space) {
  const AtmosphereModel atm(test::simple_atmosphere(ProfileKind::Exponential, 60e3, kNm, kBetaR, 21e-6),
                            WavelengthGrid::from_list(kNm));
  const SunColumnTable table(atm, {64, 128, 32});
  const TableSunColumns cols(table);
  const SingleScattering ss(atm, cols, {64});
  const Vec3 o(0, 0, R + 1000e3), sun = direction_from_angles(90, 0);
  BOOST_TEST(radiance(ss, o, Vec3(0, 0, 1), sun).maxCoeff() == 0.0f);  // looking into space
  // Looking down at the limb on the day side: lit air, finite and positive.
  const double limb = std::asin((R + 20e3) / (R + 1000e3));
  const Vec3 d(std::sin(limb), 0, -std::cos(limb));
  const Spectrum L = radiance(ss, o, d, sun);
  BOOST_TEST(L.minCoeff() > 0.0f);
  BOOST_TEST(L.allFinite());
  // Blue scatters more: the limb is bluer than it is red.
  BOOST_TEST(L[0] > L[2]);
}

// Spherical symmetry: the same sky seen from another point of the planet, with the sun and view
// rotated alike, is the same.
BOOST_AUTO_TEST_CASE(rotational_symmetry) {
  const AtmosphereModel atm(test::simple_atmosphere(ProfileKind::Exponential, 60e3, kNm, kBetaR, 21e-6),
                            WavelengthGrid::from_list(kNm));
  const SunColumnTable table(atm);
  const TableSunColumns cols(table);
  const SingleScattering ss(atm, cols, {64});
  const Vec3 o(0, 0, R + 100), d = direction_from_angles(20, 5), s = direction_from_angles(200, 10);
  const Eigen::Matrix3d rot = Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  const Spectrum a = radiance(ss, o, d, s), b = radiance(ss, rot * o, rot * d, rot * s);
  for (int i = 0; i < 3; ++i)
    BOOST_TEST(static_cast<double>(a[i]) == static_cast<double>(b[i]), boost::test_tools::tolerance(1e-4));
}

namespace {
// The default 64 view segments against 4096, from the ground, for every combination of the sun's
// and the view's elevations and the view's azimuths (degrees).
void check_default_segments_converged(double beta_mie, const std::vector<double>& suns,
                                      const std::vector<double>& views, const std::vector<double>& azimuths,
                                      double tolerance) {
  const AtmosphereModel atm(test::simple_atmosphere(ProfileKind::Exponential, 60e3, kNm, kBetaR, beta_mie),
                            WavelengthGrid::from_list(kNm));
  const SunColumnTable table(atm);
  const TableSunColumns cols(table);
  const SingleScattering coarse(atm, cols, {64}), fine(atm, cols, {4096});
  for (double sun_el : suns)
    for (double view_el : views)
      for (double view_az : azimuths) {
        const Vec3 o(0, 0, R + 1), d = direction_from_angles(view_az, view_el), s = direction_from_angles(0, sun_el);
        const Spectrum a = radiance(coarse, o, d, s), b = radiance(fine, o, d, s);
        for (int i = 0; i < 3; ++i)
          BOOST_TEST(static_cast<double>(a[i]) == static_cast<double>(b[i]), boost::test_tools::tolerance(tolerance));
      }
}
}  // namespace

// The quadrature converges: the default 64 segments agree with 4096 to 0.5 % for low and high
// suns and for rays from the zenith to the horizon.
BOOST_AUTO_TEST_CASE(default_quadrature_is_converged) {
  check_default_segments_converged(21e-6, {30.0, 5.0, 1.0, -2.0}, {90.0, 30.0, 5.0, 1.0, 0.0}, {0.0, 90.0, 180.0},
                                   5e-3);
}

// In hazy air a ray near the horizon gathers almost all its light in the first tens of kilometres,
// where its optical depth grows by more than 1 per 12 km segment if the nodes are spread evenly
// over its 770 km (that march was up to 0.8 % high here). The nodes follow the air's and the
// aerosol's columns (piece_node_positions), so 64 segments agree with 4096 to 1e-3.
BOOST_AUTO_TEST_CASE(hazy_horizon_rays_are_resolved_by_the_default_segments) {
  check_default_segments_converged(150e-6, {30.0, 5.0}, {3.0, 1.0, 0.0}, {0.0, 180.0}, 1e-3);
}

// Aerial perspective: a surface at distance d along a ray in a homogeneous medium lit without
// attenuation receives L = E beta_sca p / beta_ext (1 - exp(-beta_ext d)) in front of it and is
// seen through T = exp(-beta_ext d).
BOOST_AUTO_TEST_CASE(distance_cap_matches_closed_form) {
  const double top = 10e3, h = 1.0, d = 3000.0;
  const AtmosphereModel atm(test::simple_atmosphere(ProfileKind::Constant, top, kNm, kBetaR, 21e-6),
                            WavelengthGrid::from_list(kNm));
  const ZeroSunColumns zero;
  const SingleScattering ss(atm, zero, {16});
  const Vec3 o(0, 0, R + h), up(0, 0, 1), sun = direction_from_angles(0, 40);
  ScatteringWorkspace ws(3);
  Spectrum L(3), T(3);
  ScatteringSources src;
  src.max_distance_m = d;
  src.transmittance = &T;
  ss.radiance(o, up, sun, Spectrum::Ones(3), src, ws, L);
  const double mu = up.dot(sun);
  for (int i = 0; i < 3; ++i) {
    const double br = kBetaR[static_cast<size_t>(i)], bm = 21e-6, bext = br + 1.1 * bm;
    BOOST_TEST(static_cast<double>(T[i]) == std::exp(-bext * d), boost::test_tools::tolerance(1e-6));
    const double expected =
        (br * rayleigh_phase(mu) + bm * cornette_shanks_phase(mu, 0.76)) / bext * (1 - std::exp(-bext * d));
    BOOST_TEST(static_cast<double>(L[i]) == expected, boost::test_tools::tolerance(2e-6));
  }
  // Without a cap the transmittance is to the top of the atmosphere.
  src.max_distance_m = std::numeric_limits<double>::infinity();
  ss.radiance(o, up, sun, Spectrum::Ones(3), src, ws, L);
  BOOST_TEST(static_cast<double>(T[0]) == std::exp(-(kBetaR[0] + 1.1 * 21e-6) * (top - h)),
             boost::test_tools::tolerance(1e-5));
}

// Rays of one zenith angle share their nodes (radiance_parts_same_zenith, the sky-view table's
// rows): the same parts as integrating each ray alone, to rounding, for rays lit throughout, rays
// partly in the planet's shadow (sun below the horizon), and rays that end on the ground (camera
// at 2 km looking down).
BOOST_AUTO_TEST_CASE(rays_of_one_zenith_angle_share_nodes_exactly) {
  const AtmosphereModel atm(test::simple_atmosphere(ProfileKind::Exponential, 60e3, kNm, kBetaR, 21e-6),
                            WavelengthGrid::from_list(kNm));
  const SunColumnTable table(atm);
  const TableSunColumns cols(table);
  const SingleScattering ss(atm, cols, {64});
  const int n = 3, m = 16;
  ScatteringWorkspace ws(n);
  int compared = 0;
  for (double height : {1.0, 2000.0})
    for (double sun_el : {30.0, 2.0, -4.0})
      for (double view_el : {60.0, 3.0, 0.2, -1.0, -30.0}) {
        const Vec3 o(0, 0, R + height), s = direction_from_angles(10, sun_el);
        std::vector<Vec3> dirs;
        for (int j = 0; j < m; ++j) dirs.push_back(direction_from_angles(10 + 180.0 * j / (m - 1), view_el));
        std::vector<RadianceParts> row(m, RadianceParts(n));
        ss.radiance_parts_same_zenith(o, dirs.data(), m, s, ScatteringSources{}, ws, row.data());
        for (int j = 0; j < m; ++j) {
          RadianceParts alone(n);
          ss.radiance_parts(o, dirs[static_cast<size_t>(j)], s, ScatteringSources{}, ws, alone);
          const RadianceParts& shared = row[static_cast<size_t>(j)];
          for (int i = 0; i < n; ++i) {
            const auto close = [](float a, float b) {
              return std::abs(a - b) <= 1e-5f * std::max(std::abs(b), 1e-30f);
            };
            for (size_t k = 0; k < alone.scattered.size(); ++k)
              BOOST_TEST(close(shared.scattered[k][i], alone.scattered[k][i]));
            BOOST_TEST(close(shared.phase_free[i], alone.phase_free[i]));
          }
          BOOST_TEST(shared.scattered.size() == 2u);  // air and aerosol
          compared += alone.scattered[0].maxCoeff() > 0.0f;
        }
      }
  BOOST_TEST(compared > 100);  // most rays see light
}

BOOST_AUTO_TEST_SUITE_END()  // test_single_scattering
