#include <boost/test/unit_test.hpp>

#include <array>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <vector>

#include "atmosphere_fixtures.hpp"
#include "base/quadrature.hpp"
#include "scratch_folder.hpp"
#include "skyspec/camera.hpp"
#include "skyspec/error.hpp"
#include "skyspec/phase_function.hpp"
#include "skyspec/units.hpp"
#include "transport/multiple_scattering.hpp"
#include "transport/spherical_harmonics.hpp"

BOOST_AUTO_TEST_SUITE(test_multiple_scattering)

using namespace skyspec;

namespace {
const std::vector<double>& kNm = test::kSeedNm;
const std::vector<double>& kBetaR = test::kSeedBetaRayleigh;

// Tables small enough for a unit test: `orders` orders over altitudes x sun angles entries, of the
// given spherical-harmonic degree (0: isotropic, the settings' own default).
MultipleScatteringSettings small_tables(int orders, int altitudes, int sun_angles, int degree = 0) {
  MultipleScatteringSettings ms;
  ms.orders = orders;
  ms.altitude_samples = altitudes;
  ms.sun_samples = sun_angles;
  ms.angular_degree = degree;
  return ms;
}

// The hazy test atmosphere of the convergence checks: the seed's air and an aerosol of 60e-6 m^-1
// at the ground over a ground of albedo 0.3.
AtmosphereSpec hazy_air() {
  AtmosphereSpec spec = test::simple_atmosphere(ProfileKind::Exponential, 60e3, kNm, kBetaR, 60e-6);
  spec.ground.albedo = 0.3;
  return spec;
}

// Upward flux leaving the top of the atmosphere at the sub-solar point:
// F_up = integral over downward directions of L |mu| d omega (Gauss-Legendre in mu, azimuth
// symmetric for a sun at the zenith).
Spectrum upward_flux_at_top(const SingleScattering& ss, const ScatteringSources& src, double r) {
  const int n = ss.atmosphere().grid().size();
  ScatteringWorkspace ws(n);
  Spectrum L(n), flux = Spectrum::Zero(n);
  std::vector<double> mu, w;
  gauss_legendre(48, -1.0, 0.0, mu, w);
  for (size_t i = 0; i < mu.size(); ++i) {
    const Vec3 d(std::sqrt(1 - mu[i] * mu[i]), 0, mu[i]);
    ss.radiance(Vec3(0, 0, r), d, Vec3(0, 0, 1), Spectrum::Ones(n), src, ws, L);
    flux += static_cast<float>(2 * kPi * w[i] * std::abs(mu[i])) * L;
  }
  return flux;
}
}  // namespace

// A conservative atmosphere (no absorption) over a white ground reflects all the sunlight it
// receives. On a planet so large that the atmosphere is a flat slab, the upward flux leaving the
// top above the sub-solar point equals the incoming flux E = 1, less the orders not counted and
// the quadrature error of the tables.
BOOST_AUTO_TEST_CASE(conservative_atmosphere_over_white_ground_conserves_energy) {
  AtmosphereSpec spec = test::simple_atmosphere(ProfileKind::Exponential, 60e3, kNm, kBetaR, 21e-6, 1.0);
  spec.planet_radius_m = 1e9;
  spec.ground.albedo = 1.0;
  const test::IntegratorChain chain(spec, kNm, {128, 256, 64}, 64);
  const SingleScattering& ss = chain.integrator;
  MultipleScatteringSettings ms = small_tables(30, 16, 32);
  // The isotropic tables (degree 0) and the angular ones of the default quality (degree 10; 12
  // orders and the geometric series of the rest, for time).
  for (int degree : {0, 10}) {
    ms.angular_degree = degree;
    ms.orders = degree == 0 ? 30 : 12;
    const ScatteringOrders orders(ss, ms);
    const Spectrum flux = upward_flux_at_top(ss, ScatteringSources{true, &orders}, spec.planet_radius_m + 59.9e3);
    for (int i = 0; i < 3; ++i) {
      BOOST_TEST_MESSAGE("degree " << degree << ": upward flux at " << kNm[static_cast<size_t>(i)]
                                   << " nm: " << flux[i]);
      // 0.5 %: the higher orders are integrated along rays by the log-mean rule (they were within
      // 2 % by the trapezoid rule, 1.019 at 440 nm).
      BOOST_TEST(static_cast<double>(flux[i]) == 1.0, boost::test_tools::tolerance(0.005));
    }
  }
  // Single scattering alone falls well short: the other orders carry real energy.
  const Spectrum single = upward_flux_at_top(ss, ScatteringSources{true, nullptr}, spec.planet_radius_m + 59.9e3);
  BOOST_TEST(single[0] < 0.95f);  // of the incoming flux, which the orders together return
}

// Below a terrain's skyline: the whole source, its part below the skyline with the gradient's
// correction, and order 2's part, summed in one pass over each table's entries
// (source_above_skyline_with), are exactly what the separate look-ups give: the whole source
// (source()), each table's part below the skyline (source_below_skyline), their difference.
BOOST_AUTO_TEST_CASE(skyline_sums_in_one_pass_equal_the_separate_look_ups) {
  AtmosphereSpec spec = test::simple_atmosphere(ProfileKind::Exponential, 60e3, kNm, kBetaR, 21e-6);
  spec.ground.albedo = 0.2;
  const test::IntegratorChain chain(spec, kNm, {64, 128, 64}, 32);
  const ScatteringOrders orders(chain.integrator, small_tables(4, 8, 16, 6));
  const SourceTable &sum = orders.sum(), &second = orders.order(2);
  const int media = sum.media_count(), n = sum.wavelength_count();
  BOOST_TEST_REQUIRE(media == 2);
  const size_t size = static_cast<size_t>(n) + SourceTable::kLookupSlack;
  std::vector<std::vector<float>> buffers(static_cast<size_t>(9 * media), std::vector<float>(size));
  const auto ptrs = [&](int which) {
    std::array<float*, kMaxMedia> p{};
    for (int s = 0; s < media; ++s) p[static_cast<size_t>(s)] = buffers[static_cast<size_t>(which * media + s)].data();
    return p;
  };
  auto out = ptrs(0), hidden = ptrs(1), share = ptrs(2), multiple = ptrs(3), below = ptrs(4);
  auto whole = ptrs(5), hidden_ref = ptrs(6), below_ref = ptrs(7);
  for (const double r : {6360e3 + 5.0, 6360e3 + 1500.0, 6360e3 + 21e3})
    for (const double mu_sun : {0.9, 0.2, -0.05})
      for (const double mu_view : {0.3, 0.02, -0.4})
        for (const double gamma : {0.01, 0.2, 0.9}) {
          const double nu = mu_sun * mu_view + 0.5 * std::sqrt((1 - mu_sun * mu_sun) * (1 - mu_view * mu_view));
          BOOST_TEST_CONTEXT("r " << r << ", mu_sun " << mu_sun << ", mu_view " << mu_view << ", gamma " << gamma) {
            BOOST_TEST(sum.source_above_skyline_with(&second, below.data(), r, mu_sun, mu_view, nu, gamma, out.data(),
                                                     hidden.data(), share.data(), multiple.data()));
            sum.source(r, mu_sun, mu_view, nu, whole.data());
            sum.source_below_skyline(r, mu_sun, mu_view, nu, gamma, hidden_ref.data());
            second.source_below_skyline(r, mu_sun, mu_view, nu, gamma, below_ref.data());
            for (int s = 0; s < media; ++s)
              for (int i = 0; i < n; ++i) {
                const size_t si = static_cast<size_t>(s), ii = static_cast<size_t>(i);
                BOOST_TEST(hidden[si][ii] == hidden_ref[si][ii]);
                BOOST_TEST(multiple[si][ii] == hidden_ref[si][ii]);
                BOOST_TEST(out[si][ii] == whole[si][ii] - hidden_ref[si][ii]);
                BOOST_TEST(below[si][ii] == below_ref[si][ii]);
              }
          }
        }
}

// Each order carries less light than the one before (Earth-like atmosphere, black ground).
BOOST_AUTO_TEST_CASE(orders_decrease) {
  const test::IntegratorChain chain(test::simple_atmosphere(ProfileKind::Exponential, 60e3, kNm, kBetaR, 21e-6), kNm,
                                    {64, 128, 64}, 32);
  const SingleScattering& ss = chain.integrator;
  MultipleScatteringSettings ms = small_tables(6, 12, 24);
  const ScatteringOrders orders(ss, ms);
  double previous = orders.order(2).mean_source();
  BOOST_TEST(previous > 0.0);
  for (int k = 3; k <= 6; ++k) {
    const double m = orders.order(k).mean_source();
    BOOST_TEST_MESSAGE("order " << k << ": mean source " << m << " (ratio " << m / previous << ")");
    BOOST_TEST(m < previous);
    BOOST_TEST(m > 0.0);
    previous = m;
  }
}

// The single-scattering part of a render with higher orders is the foundation's single
// scattering: the radiance splits exactly into order 1 and the rest.
BOOST_AUTO_TEST_CASE(single_scattering_part_is_unchanged) {
  AtmosphereSpec spec = test::simple_atmosphere(ProfileKind::Exponential, 60e3, kNm, kBetaR, 21e-6);
  spec.ground.albedo = 0.3;
  const test::IntegratorChain chain(spec, kNm, {64, 128, 64}, 64);
  const SingleScattering& ss = chain.integrator;
  MultipleScatteringSettings ms = small_tables(3, 8, 16);
  const ScatteringOrders orders(ss, ms);
  ScatteringWorkspace ws(3);
  Spectrum all(3), higher(3), single(3);
  const Vec3 o(0, 0, 6360e3 + 2), s = direction_from_angles(0, 12);
  for (double el : {60.0, 10.0, 1.0, -5.0}) {
    const Vec3 d = direction_from_angles(120, el);
    ss.radiance(o, d, s, Spectrum::Ones(3), ScatteringSources{true, &orders}, ws, all);
    ss.radiance(o, d, s, Spectrum::Ones(3), ScatteringSources{false, &orders}, ws, higher);
    ss.radiance(o, d, s, Spectrum::Ones(3), ScatteringSources{true, nullptr}, ws, single);
    for (int i = 0; i < 3; ++i)
      BOOST_TEST(static_cast<double>(all[i] - higher[i]) == static_cast<double>(single[i]),
                 boost::test_tools::tolerance(1e-5));
    BOOST_TEST(higher.minCoeff() > 0.0f);
  }
}

BOOST_AUTO_TEST_CASE(gauss_legendre_integrates_polynomials_exactly) {
  std::vector<double> x, w;
  gauss_legendre(6, -0.3, 2.0, x, w);
  double integral = 0.0;
  for (size_t i = 0; i < x.size(); ++i) integral += w[i] * std::pow(x[i], 11);  // degree 2n - 1
  const double exact = (std::pow(2.0, 12) - std::pow(-0.3, 12)) / 12.0;
  BOOST_TEST(integral == exact, boost::test_tools::tolerance(1e-12));
}

// The disk cache gives back exactly the tables it was given, and nothing for another key or a
// damaged file.
BOOST_AUTO_TEST_CASE(tables_round_trip_through_the_cache) {
  const test::IntegratorChain chain(test::simple_atmosphere(ProfileKind::Exponential, 60e3, kNm, kBetaR, 21e-6), kNm,
                                    {32, 64, 32}, 16);
  const AtmosphereModel& atm = chain.atm;
  const SingleScattering& ss = chain.integrator;
  MultipleScatteringSettings ms = small_tables(3, 6, 8);
  const ScatteringOrders built(ss, ms);
  const test::ScratchFolder dir("ms-cache");
  const std::string path = (dir.path / "orders.bin").string();
  BOOST_REQUIRE(built.save(path, "key A"));
  const auto loaded = ScatteringOrders::load(path, "key A", atm, ms);
  BOOST_REQUIRE(loaded);
  float a[3], b[3], a2[3], b2[3];
  for (double mu : {-0.3, 0.0, 0.4, 1.0}) {
    built.source(6360e3 + 1234, mu, 0.3, 0.5, test::pair_of(a, a2));
    loaded->source(6360e3 + 1234, mu, 0.3, 0.5, test::pair_of(b, b2));
    for (int i = 0; i < 3; ++i) BOOST_TEST(a[i] == b[i]);
    for (int i = 0; i < 3; ++i) BOOST_TEST(a2[i] == b2[i]);
    built.ground_irradiance(mu, a);
    loaded->ground_irradiance(mu, b);
    for (int i = 0; i < 3; ++i) BOOST_TEST(a[i] == b[i]);
  }
  // The cache keeps what renders read: order 2's table (the skyline's correction) and the sum.
  BOOST_TEST(loaded->order(2).mean_source() == built.order(2).mean_source());
  BOOST_TEST(loaded->sum().mean_source() == built.sum().mean_source());
  BOOST_CHECK_THROW(loaded->order(3), skyspec::Error);
  BOOST_CHECK_THROW(built.order(4), skyspec::Error);  // beyond the highest order
  BOOST_TEST(!ScatteringOrders::load(path, "key B", atm, ms));
  ms.sun_samples = 9;
  BOOST_TEST(!ScatteringOrders::load(path, "key A", atm, ms));
  ms.sun_samples = 8;
  BOOST_TEST(dir.entries().size() == 1u);  // no temporary file left by save()

  // Damaged files are rebuilt, never trusted: truncated, one value changed (the checksum no longer
  // holds), garbage after a valid header, empty.
  std::string bytes;
  {
    std::ifstream in(path, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  auto rewrite = [&](const std::string& content) {
    std::ofstream(path, std::ios::binary | std::ios::trunc) << content;
    return ScatteringOrders::load(path, "key A", atm, ms) == nullptr;
  };
  BOOST_TEST(rewrite(bytes.substr(0, bytes.size() - 1)));
  BOOST_TEST(rewrite(bytes.substr(0, bytes.size() / 2)));
  std::string tampered = bytes;
  tampered[tampered.size() / 2] = static_cast<char>(tampered[tampered.size() / 2] ^ 0x40);  // a table value changed
  BOOST_TEST(rewrite(tampered));
  BOOST_TEST(rewrite("skyspec scattering orders v2\n garbage"));
  BOOST_TEST(rewrite(""));
  BOOST_TEST(!rewrite(bytes));  // the intact file still loads
}

// A field of degree 2 in the local frame (x towards the sun's azimuth, z up), put into a table by
// its harmonics: each species' source towards any view direction is the integral of its phase
// function times the field, computed here by brute-force quadrature (exact truncation: the field
// has no harmonics above degree 2, whatever the phase function's).
BOOST_AUTO_TEST_CASE(angular_source_is_the_phase_weighted_field) {
  const AtmosphereModel atm(test::simple_atmosphere(ProfileKind::Exponential, 60e3, kNm, kBetaR, 21e-6),
                            WavelengthGrid::from_list(kNm));
  const auto moments = PhaseMoments::of(atm, 4);
  SourceTable table(atm.planet_radius_m(), atm.top_radius_m(), 4, 4, moments);
  auto field = [](const Vec3& w, int i) {
    return (1.0 + i) * (1.0 + 0.5 * w.z() + 0.3 * w.z() * w.z() + 0.2 * w.x() + 0.1 * w.x() * w.z());
  };
  // The harmonics of the field (Gauss-Legendre x midpoint: exact for these integrands).
  const int n_c = table.harmonic_count();
  std::vector<double> mu, wt, y(static_cast<size_t>(n_c));
  gauss_legendre(16, -1.0, 1.0, mu, wt);
  std::vector<double> a(static_cast<size_t>(n_c * 3), 0.0);
  for (size_t i = 0; i < mu.size(); ++i)
    for (int j = 0; j < 32; ++j) {
      const double phi = (j + 0.5) * 2 * kPi / 32, st = std::sqrt(1 - mu[i] * mu[i]);
      const Vec3 w(st * std::cos(phi), st * std::sin(phi), mu[i]);
      symmetric_harmonics(table.degree(), mu[i], std::cos(phi), y.data());
      for (int c = 0; c < n_c; ++c)
        for (int l = 0; l < 3; ++l)
          a[static_cast<size_t>(c * 3 + l)] += wt[i] * 2 * kPi / 32 * y[static_cast<size_t>(c)] * field(w, l);
    }
  for (int ih = 0; ih < 4; ++ih)
    for (int im = 0; im < 4; ++im)
      for (int c = 0; c < n_c; ++c)
        for (int l = 0; l < 3; ++l)
          table.j_at(ih, im)[c * 3 + l] = static_cast<float>(a[static_cast<size_t>(c * 3 + l)]);
  table.prepare();
  // Views at several zenith angles and azimuths, the sun at mu_s = 0.4.
  const double mu_s = 0.4, ss = std::sqrt(1 - mu_s * mu_s);
  std::vector<double> fmu, fw;
  gauss_legendre(200, -1.0, 1.0, fmu, fw);
  for (double mu_v : {-0.5, 0.05, 0.7}) {
    for (double phi_v : {0.0, 1.2, 2.8}) {
      const double sv = std::sqrt(1 - mu_v * mu_v);
      const Vec3 v(sv * std::cos(phi_v), sv * std::sin(phi_v), mu_v);
      const double nu = mu_v * mu_s + sv * ss * std::cos(phi_v);
      float jr[3], jm[3];
      table.source(atm.planet_radius_m() + 1000.0, mu_s, mu_v, nu, test::pair_of(jr, jm));
      for (int l = 0; l < 3; ++l) {
        double er = 0.0, em = 0.0;
        for (size_t i = 0; i < fmu.size(); ++i)
          for (int j = 0; j < 400; ++j) {
            const double phi = (j + 0.5) * 2 * kPi / 400, st = std::sqrt(1 - fmu[i] * fmu[i]);
            const Vec3 w(st * std::cos(phi), st * std::sin(phi), fmu[i]);
            const double dw = fw[i] * 2 * kPi / 400, c = v.dot(w);
            er += dw * rayleigh_phase(c, atm.medium("air")->phase.rayleigh_gamma[l]) * field(w, l);
            em += dw * atm.medium("aerosol")->phase.at(l, c) * field(w, l);
          }
        BOOST_TEST(jr[l] == er, boost::test_tools::tolerance(2e-5));
        BOOST_TEST(jm[l] == em, boost::test_tools::tolerance(1e-3));
      }
    }
  }
}

// Degree 0 is the isotropic approximation: every species' source is the field's mean.
BOOST_AUTO_TEST_CASE(degree_zero_is_the_mean_radiance) {
  const AtmosphereModel atm(test::simple_atmosphere(ProfileKind::Exponential, 60e3, kNm, kBetaR, 21e-6),
                            WavelengthGrid::from_list(kNm));
  SourceTable table(atm.planet_radius_m(), atm.top_radius_m(), 4, 4, PhaseMoments::of(atm, 0));
  BOOST_TEST(table.harmonic_count() == 1);
  for (int ih = 0; ih < 4; ++ih)
    for (int im = 0; im < 4; ++im)
      for (int l = 0; l < 3; ++l) table.j_at(ih, im)[l] = static_cast<float>(std::sqrt(4 * kPi) * 0.25 * (l + 1));
  float jr[3], jm[3];
  // Not prepared after it was written: refused rather than read with stale look-up data.
  BOOST_CHECK_THROW(table.source(atm.planet_radius_m() + 500.0, 0.3, 0.2, 0.0, test::pair_of(jr, jm)),
                    std::logic_error);
  table.prepare();
  for (double nu : {-1.0, 0.0, 0.9}) {
    table.source(atm.planet_radius_m() + 500.0, 0.3, 0.2, nu, test::pair_of(jr, jm));
    for (int l = 0; l < 3; ++l) {
      BOOST_TEST(jr[l] == 0.25 * (l + 1), boost::test_tools::tolerance(1e-6));
      BOOST_TEST(jm[l] == 0.25 * (l + 1), boost::test_tools::tolerance(1e-6));
    }
  }
}

// The rows: the ground and the top, the lowest kilometre with a third of 16 rows over 60 km, the
// spacing growing upwards, and the look-up's coordinate the inverse of the rows' altitudes. A
// field linear in altitude between two rows is read back exactly at any altitude between them
// (the look-up interpolates in the row coordinate, so only its rows are exact: it is checked here
// at the rows and at their midpoints in the coordinate).
BOOST_AUTO_TEST_CASE(altitude_rows_are_dense_near_the_ground) {
  const AtmosphereModel atm(test::simple_atmosphere(ProfileKind::Exponential, 60e3, kNm, kBetaR, 21e-6),
                            WavelengthGrid::from_list(kNm));
  const int rows = 16;
  SourceTable table(atm.planet_radius_m(), atm.top_radius_m(), rows, 4, PhaseMoments::of(atm, 0));
  BOOST_TEST(table.altitude_m(0) == 0.0, boost::test_tools::tolerance(1e-9));
  BOOST_TEST(table.altitude_m(rows - 1) == 60e3, boost::test_tools::tolerance(1e-9));
  int below_1km = 0;
  for (int i = 0; i < rows; ++i) {
    const double h = table.altitude_m(i);
    if (h < 1000.0) ++below_1km;
    BOOST_TEST(table.row_coordinate_of_altitude(h) * (rows - 1) == static_cast<double>(i),
               boost::test_tools::tolerance(1e-9));
    if (i >= 2) BOOST_TEST(h - table.altitude_m(i - 1) > table.altitude_m(i - 1) - table.altitude_m(i - 2));
  }
  BOOST_TEST(below_1km == 5);  // 0, 0.13, 0.31, 0.57, 0.93 km
  BOOST_TEST(table.altitude_m(1) < 200.0);
  // Each row holds its own altitude as the mean radiance; reading between rows gives the blend in
  // the row coordinate.
  for (int ih = 0; ih < rows; ++ih)
    for (int im = 0; im < 4; ++im)
      for (int l = 0; l < 3; ++l) table.j_at(ih, im)[l] = static_cast<float>(std::sqrt(4 * kPi) * table.altitude_m(ih));
  table.prepare();
  float jr[3], jm[3];
  for (int i = 0; i + 1 < rows; ++i) {
    const double x = (i + 0.5) / (rows - 1);
    const double h = table.altitude_of_row_coordinate(x);
    table.source(atm.planet_radius_m() + h, 0.3, 0.2, 0.0, test::pair_of(jr, jm));
    const double expected = 0.5 * (table.altitude_m(i) + table.altitude_m(i + 1));
    BOOST_TEST(jr[0] == expected, boost::test_tools::tolerance(1e-5));
  }
}

namespace {
// The sun-angle coordinate of the tables (SourceTable::mu_sun): u in [0, 1] to mu_s.
double sun_column_cosine(double u) {
  const double c = SourceTable::kSunColumnCentre, w = SourceTable::kSunColumnWidth;
  const double a = std::asinh((-1.0 - c) / w), b = std::asinh((1.0 - c) / w);
  return c + w * std::sinh(a + u * (b - a));
}
}  // namespace

// The sun-angle columns run from -1 to 1, closest together just below the horizon (where the
// planet's shadow crosses the air and the sources fall steeply) and furthest apart at the zenith:
// with the default 72, under 0.5 degrees apart around the horizon, as in 144 of the earlier
// columns (twice as dense there as uniform).
BOOST_AUTO_TEST_CASE(sun_columns_are_densest_just_below_the_horizon) {
  const AtmosphereModel atm(test::simple_atmosphere(ProfileKind::Exponential, 60e3, kNm, kBetaR, 21e-6),
                            WavelengthGrid::from_list(kNm));
  SourceTable table(atm.planet_radius_m(), atm.top_radius_m(), 2, 72, PhaseMoments::of(atm, 0));
  BOOST_TEST(table.mu_sun(0) == -1.0);
  BOOST_TEST(table.mu_sun(71) == 1.0);
  double finest = 2.0, at = 0.0;
  for (int i = 0; i + 1 < 72; ++i) {
    const double step = table.mu_sun(i + 1) - table.mu_sun(i);
    BOOST_TEST(step > 0.0);
    BOOST_TEST(table.mu_sun(i) == sun_column_cosine(i / 71.0), boost::test_tools::tolerance(1e-12));
    if (step < finest) finest = step, at = 0.5 * (table.mu_sun(i) + table.mu_sun(i + 1));
  }
  BOOST_TEST(std::abs(at - SourceTable::kSunColumnCentre) < finest);
  BOOST_TEST(std::asin(finest) * 180.0 / kPi < 0.5);
  BOOST_TEST(table.mu_sun(71) - table.mu_sun(70) > 10.0 * finest);
}

// Between two sun-angle columns whose mean radiances differ by more than SourceTable::kSteepRatio
// (1.25; inside the planet's shadow the sources fall by orders of magnitude per column) the lookup
// follows an exponential, not a straight line; where they are closer it stays linear.
BOOST_AUTO_TEST_CASE(steep_sun_angle_decays_are_interpolated_exponentially) {
  const AtmosphereModel atm(test::simple_atmosphere(ProfileKind::Exponential, 60e3, kNm, kBetaR, 21e-6),
                            WavelengthGrid::from_list(kNm));
  SourceTable table(atm.planet_radius_m(), atm.top_radius_m(), 2, 3, PhaseMoments::of(atm, 0));
  const double norm = std::sqrt(4 * kPi);  // a_00 = sqrt(4 pi) x the mean radiance
  // Column 0 (mu = -1) and 1 (mu = 0): the first wavelength falls 1000-fold, the others by 1.5.
  for (int ih = 0; ih < 2; ++ih) {
    for (int l = 0; l < 3; ++l) table.j_at(ih, 1)[l] = static_cast<float>(norm);
    table.j_at(ih, 0)[0] = static_cast<float>(1e-3 * norm);
    for (int l = 1; l < 3; ++l) table.j_at(ih, 0)[l] = static_cast<float>(norm / 1.5);
  }
  BOOST_TEST(table.mu_sun(0) == -1.0);
  BOOST_TEST(table.mu_sun(2) == 1.0);
  // Halfway in the table's coordinate between columns 0 and 1 (u = 1/4): the geometric mean for the
  // steep wavelength (the whole row is then scaled, as all of a row's wavelengths share the blend).
  const double half = sun_column_cosine(0.25);
  BOOST_TEST(half > -1.0);
  BOOST_TEST(half < table.mu_sun(1));
  table.prepare();
  float jr[3], jm[3];
  table.source(atm.planet_radius_m() + 1000.0, half, 0.5, 0.2, test::pair_of(jr, jm));
  BOOST_TEST(jr[0] == std::sqrt(1e-3), boost::test_tools::tolerance(1e-4));
  // A factor 1.5 between the columns: the geometric mean sqrt(1/1.5) = 0.8165 against the linear
  // 0.8333; the blend follows the exponential there too, once any wavelength of the row is steep.
  BOOST_TEST(jr[1] == std::sqrt(1.0 / 1.5), boost::test_tools::tolerance(1e-4));
  // A factor 1.5 alone is steep too: the geometric mean.
  for (int ih = 0; ih < 2; ++ih) table.j_at(ih, 0)[0] = static_cast<float>(norm / 1.5);
  table.prepare();
  table.source(atm.planet_radius_m() + 1000.0, half, 0.5, 0.2, test::pair_of(jr, jm));
  for (int l = 0; l < 3; ++l) BOOST_TEST(jr[l] == std::sqrt(1.0 / 1.5), boost::test_tools::tolerance(1e-4));
  // No wavelength steeper than 1.2: linear.
  for (int ih = 0; ih < 2; ++ih)
    for (int l = 0; l < 3; ++l) table.j_at(ih, 0)[l] = static_cast<float>(norm / 1.2);
  table.prepare();
  table.source(atm.planet_radius_m() + 1000.0, half, 0.5, 0.2, test::pair_of(jr, jm));
  for (int l = 0; l < 3; ++l) BOOST_TEST(jr[l] == 0.5 * (1.0 + 1.0 / 1.2), boost::test_tools::tolerance(1e-5));
}

// Read up to a lower degree, a table gives exactly what a table holding only those harmonics gives;
// up to its own degree or more, what source() gives.
BOOST_AUTO_TEST_CASE(source_to_a_lower_degree_drops_the_higher_harmonics) {
  const AtmosphereModel atm(test::simple_atmosphere(ProfileKind::Exponential, 60e3, kNm, kBetaR, 21e-6),
                            WavelengthGrid::from_list(kNm));
  const auto moments = PhaseMoments::of(atm, 6);
  SourceTable full(atm.planet_radius_m(), atm.top_radius_m(), 3, 4, moments);
  SourceTable low(atm.planet_radius_m(), atm.top_radius_m(), 3, 4, moments, 2);
  BOOST_REQUIRE(full.degree() == 6);
  BOOST_REQUIRE(low.degree() == 2);
  for (int ih = 0; ih < 3; ++ih)
    for (int im = 0; im < 4; ++im)
      for (int c = 0; c < full.harmonic_count(); ++c)
        for (int l = 0; l < 3; ++l) {
          // A mean radiance well above the other harmonics (a positive field), varying over the table.
          const float v = c == 0 ? static_cast<float>(10.0 + ih + 0.5 * im + l)
                                 : static_cast<float>(0.3 * std::sin(1.0 + c + 2.0 * ih + im + 0.7 * l));
          full.j_at(ih, im)[c * 3 + l] = v;
          if (c < low.harmonic_count()) low.j_at(ih, im)[c * 3 + l] = v;
        }
  full.prepare();
  low.prepare();
  float r1[3], m1[3], r2[3], m2[3];
  for (double mu_s : {-0.2, 0.35}) {
    for (double mu_v : {-0.4, 0.1, 0.9}) {
      const double nu = mu_v * mu_s + 0.5 * std::sqrt((1 - mu_v * mu_v) * (1 - mu_s * mu_s));
      full.source_to_degree(2, atm.planet_radius_m() + 3000.0, mu_s, mu_v, nu, test::pair_of(r1, m1));
      low.source(atm.planet_radius_m() + 3000.0, mu_s, mu_v, nu, test::pair_of(r2, m2));
      for (int l = 0; l < 3; ++l) {
        BOOST_TEST(r1[l] == r2[l], boost::test_tools::tolerance(1e-6f));
        BOOST_TEST(m1[l] == m2[l], boost::test_tools::tolerance(1e-6f));
      }
      full.source_to_degree(9, atm.planet_radius_m() + 3000.0, mu_s, mu_v, nu, test::pair_of(r1, m1));
      full.source(atm.planet_radius_m() + 3000.0, mu_s, mu_v, nu, test::pair_of(r2, m2));
      for (int l = 0; l < 3; ++l) {
        BOOST_TEST(r1[l] == r2[l]);
        BOOST_TEST(m1[l] == m2[l]);
      }
      // The aerosol's moments above degree 2 are not zero: the dropped harmonics mattered.
      low.source(atm.planet_radius_m() + 3000.0, mu_s, mu_v, nu, test::pair_of(r1, m1));
      BOOST_TEST(std::abs(m1[0] - m2[0]) > 1e-4f * std::abs(m2[0]));
    }
  }
}

// Each order's directions (quadrature_of_order) have converged: twice the nodes in every
// dimension moves the sky's radiance by less than three quarters of the 1 % the multiple
// scattering is validated to, in a hazy atmosphere (three times the seed's aerosol) over a grey
// ground, at the default degree.
BOOST_AUTO_TEST_CASE(direction_quadrature_of_the_orders_has_converged) {
  const test::IntegratorChain chain(hazy_air(), kNm, {64, 128, 64}, 64);
  const SingleScattering& ss = chain.integrator;
  MultipleScatteringSettings ms = small_tables(4, 8, 16, 10);
  const ScatteringOrders coarse(ss, ms);
  ms.quadrature_refinement = 2;
  const ScatteringOrders fine(ss, ms);
  BOOST_TEST(ScatteringOrders::quadrature_of_order(10, 2, 2).rays() ==
             4 * ScatteringOrders::quadrature_of_order(10, 2).rays());
  ScatteringWorkspace ws(3);
  Spectrum a(3), b(3);
  const Vec3 o(0, 0, 6360e3 + 2), s = direction_from_angles(0, 10);
  double worst = 0.0;
  for (double az : {0.0, 90.0, 180.0})
    for (double el : {1.0, 45.0, 90.0}) {
      const Vec3 d = direction_from_angles(az, el);
      ss.radiance(o, d, s, Spectrum::Ones(3), ScatteringSources{true, &coarse}, ws, a);
      ss.radiance(o, d, s, Spectrum::Ones(3), ScatteringSources{true, &fine}, ws, b);
      for (int i = 0; i < 3; ++i) {
        BOOST_TEST_MESSAGE("az " << az << " el " << el << " " << kNm[static_cast<size_t>(i)]
                                 << " nm: " << a[i] / b[i] - 1);
        worst = std::max(worst, std::abs(static_cast<double>(a[i] / b[i]) - 1.0));
      }
    }
  BOOST_TEST_MESSAGE("largest change of the radiance with twice the direction nodes: " << worst);
  BOOST_TEST(worst < 0.0075);
}

// Rain's light scattered once is as sharp as its drops' matrix (the bows a degree or two wide, the
// table every tenth of a degree about them), far sharper than order 2's directions are apart:
// each direction takes the matrix's mean over its patch of the quadrature (integrate_order). Twice
// the directions in every dimension then move the sky little, at every wavelength alike, where the
// directions' own values moved it by several per cent one way or the other as the bows' angles
// changed with the wavelength (docs/bows-and-halos.md gives both).
BOOST_AUTO_TEST_CASE(rain_order_two_has_converged_in_direction) {
  AtmosphereSpec spec = test::simple_atmosphere(ProfileKind::Exponential, 60e3, kNm, kBetaR, 0.0);
  spec.rain.enabled = true;
  spec.rain.rate_mm_per_h = 2.0;
  const test::IntegratorChain chain(spec, kNm, {64, 128, 64}, 64);
  const SingleScattering& ss = chain.integrator;
  MultipleScatteringSettings ms = small_tables(2, 8, 24, 10);
  const ScatteringOrders coarse(ss, ms);
  ms.quadrature_refinement = 2;
  const ScatteringOrders fine(ss, ms);
  ScatteringWorkspace ws(3);
  Spectrum single(3), a(3), b(3);
  const Vec3 o(0, 0, 6360e3 + 2), s = direction_from_angles(180, 25);
  double worst = 0.0;
  for (double az : {0.0, 90.0, 180.0})
    for (double el : {3.0, 20.0, 60.0}) {
      const Vec3 d = direction_from_angles(az, el);
      // Order 2 alone: the radiance with the tables less the light scattered once.
      ss.radiance(o, d, s, Spectrum::Ones(3), ScatteringSources{true, nullptr}, ws, single);
      ss.radiance(o, d, s, Spectrum::Ones(3), ScatteringSources{true, &coarse}, ws, a);
      ss.radiance(o, d, s, Spectrum::Ones(3), ScatteringSources{true, &fine}, ws, b);
      for (int i = 0; i < 3; ++i) {
        const double change = (a[i] - single[i]) / (b[i] - single[i]) - 1.0;
        BOOST_TEST_MESSAGE("az " << az << " el " << el << " " << kNm[static_cast<size_t>(i)] << " nm: order 2 "
                                 << change);
        worst = std::max(worst, std::abs(change));
      }
    }
  BOOST_TEST_MESSAGE("largest change of order 2 with twice the direction nodes: " << worst);
  BOOST_TEST(worst < 0.01);
}

// The tables' rays: 24 segments for order 2 and 16 for the orders after it (the defaults) against
// 48 for every order, in the same hazy air, with the sun up and 4 degrees below the horizon
// (where the higher orders are most of the light).
BOOST_AUTO_TEST_CASE(segments_along_the_tables_rays_have_converged) {
  const test::IntegratorChain chain(hazy_air(), kNm, {64, 128, 64}, 64);
  const SingleScattering& ss = chain.integrator;
  MultipleScatteringSettings ms = small_tables(4, 8, 16, 4);
  BOOST_TEST(ScatteringOrders::segments_of_order(ms, 2) == 24);
  BOOST_TEST(ScatteringOrders::segments_of_order(ms, 3) == 16);
  const ScatteringOrders coarse(ss, ms);
  ms.view_segments = ms.higher_order_segments = 48;
  const ScatteringOrders fine(ss, ms);
  ScatteringWorkspace ws(3);
  Spectrum a(3), b(3);
  const Vec3 o(0, 0, 6360e3 + 2);
  double worst = 0.0;
  for (double sun : {10.0, -4.0})
    for (double az : {0.0, 90.0, 180.0})
      for (double el : {1.0, 45.0, 90.0}) {
        const Vec3 d = direction_from_angles(az, el), s = direction_from_angles(0, sun);
        ss.radiance(o, d, s, Spectrum::Ones(3), ScatteringSources{true, &coarse}, ws, a);
        ss.radiance(o, d, s, Spectrum::Ones(3), ScatteringSources{true, &fine}, ws, b);
        for (int i = 0; i < 3; ++i) worst = std::max(worst, std::abs(static_cast<double>(a[i] / b[i]) - 1.0));
      }
  BOOST_TEST_MESSAGE("largest change of the radiance with 48 segments along every table ray: " << worst);
  BOOST_TEST(worst < 0.005);
}

BOOST_AUTO_TEST_SUITE_END()
