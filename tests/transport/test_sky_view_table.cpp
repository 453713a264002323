#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <vector>

#include "atmosphere_fixtures.hpp"
#include "skyspec/camera.hpp"
#include "skyspec/error.hpp"
#include "skyspec/units.hpp"
#include "transport/sky_view_table.hpp"

BOOST_AUTO_TEST_SUITE(test_sky_view_table)

using namespace skyspec;

namespace {
constexpr double R = 6360e3;

// A higher-order source that varies with altitude, sun angle and view direction, and lights the ground.
struct SmoothSource : InScatteringSource {
  void source(double r_m, double mu_sun, double mu_view, double nu, float* const* out) const override {
    float *rayleigh = out[0], *mie = out[1];  // the air's and the aerosol's
    for (int i = 0; i < 3; ++i) {
      rayleigh[i] =
          static_cast<float>(0.02 * (1 + i) * std::exp(-(r_m - R) / 9000.0) * (1.2 + mu_sun) * (1.1 + 0.1 * nu));
      mie[i] =
          static_cast<float>(0.03 * (1 + i) * std::exp(-(r_m - R) / 9000.0) * (1.2 + mu_sun) * (1.5 + 0.3 * mu_view));
    }
  }
  void ground_irradiance(double mu_sun, float* out) const override {
    for (int i = 0; i < 3; ++i) out[i] = static_cast<float>(0.1 * (1.0 + mu_sun));
  }
};

struct Fixture {
  test::IntegratorChain chain;
  const AtmosphereModel& atm;
  const SingleScattering& integrator;
  SmoothSource higher;
  ScatteringSources sources;
  explicit Fixture(double albedo = 0.3)
      : chain(make_spec(albedo), test::kSeedNm, SunColumnTable::Resolution{}, 64),
        atm(chain.atm),
        integrator(chain.integrator),
        sources{true, &higher} {}
  static AtmosphereSpec make_spec(double albedo) {
    AtmosphereSpec a =
        test::simple_atmosphere(ProfileKind::Exponential, 60e3, test::kSeedNm, test::kSeedBetaRayleigh, 21e-6);
    a.ground.albedo = albedo;
    return a;
  }
  RadianceParts direct(const Vec3& o, const Vec3& d, const Vec3& s) const {
    ScatteringWorkspace ws(3);
    RadianceParts p(3);
    integrator.radiance_parts(o, d, s, sources, ws, p);
    return p;
  }
};

// Largest relative difference over the parts and wavelengths, relative to the largest part.
double relative_difference(const RadianceParts& a, const RadianceParts& b) {
  double worst = 0.0;
  for (int i = 0; i < 3; ++i) {
    double scale = std::max(std::abs(b.phase_free[i]), 1e-30f);
    for (const Spectrum& part : b.scattered) scale = std::max(scale, static_cast<double>(std::abs(part[i])));
    worst = std::max(worst, std::abs(a.phase_free[i] - b.phase_free[i]) / scale);
    for (size_t k = 0; k < a.scattered.size(); ++k)
      worst = std::max(worst, std::abs(a.scattered[k][i] - b.scattered[k][i]) / scale);
  }
  return worst;
}

Vec3 random_direction(std::mt19937_64& rng) {
  std::normal_distribution<double> g;
  return Vec3(g(rng), g(rng), g(rng)).normalized();
}
}  // namespace

BOOST_AUTO_TEST_CASE(applies_only_inside_the_atmosphere) {
  const Fixture f;
  BOOST_TEST(SkyViewTable::applicable(f.atm, Vec3(0, 0, R + 1)));
  BOOST_TEST(SkyViewTable::applicable(f.atm, Vec3(0, 0, R)));
  BOOST_TEST(!SkyViewTable::applicable(f.atm, Vec3(0, 0, R - 1)));
  BOOST_TEST(!SkyViewTable::applicable(f.atm, Vec3(0, 0, R + 60e3)));
}

// At its own rays the table returns what the integrator gives there: the mapping from directions
// to table coordinates inverts the one from coordinates to directions, on both sides.
BOOST_AUTO_TEST_CASE(reproduces_its_nodes) {
  const Fixture f;
  const Vec3 o(0, 0, R + 500), s = direction_from_angles(30, 20);
  const SkyViewResolution res{16, 12, 9};
  const SkyViewTable t(f.integrator, f.sources, o, s, res, 2);
  RadianceParts p(3);
  for (bool sky : {true, false})
    for (int row = 0; row < (sky ? res.sky_rows : res.ground_rows); ++row)
      for (int col = 0; col < res.azimuths; ++col) {
        const Vec3 d = t.direction(sky, row, col);
        BOOST_TEST_CONTEXT("sky side " << sky << " row " << row << " column " << col) {
          BOOST_TEST((d.dot(o.normalized()) > -std::sqrt(1.0 - R * R / (o.norm() * o.norm()))) == sky);  // the horizon
          BOOST_TEST(t.lookup(d, p));
          BOOST_TEST(relative_difference(p, f.direct(o, d, s)) < 2e-5);
        }
      }
}

// A table of the sky alone answers for directions above the horizon only.
BOOST_AUTO_TEST_CASE(sky_side_only) {
  const Fixture f;
  const Vec3 o(0, 0, R + 100), s = direction_from_angles(0, 20);
  SkyViewResolution res{16, 8, 8};
  res.ground_side = false;
  const SkyViewTable t(f.integrator, f.sources, o, s, res, 1);
  RadianceParts p(3);
  BOOST_TEST(t.lookup(direction_from_angles(10, 0.0), p));  // the horizon is 0.32 deg below
  BOOST_TEST(!t.lookup(direction_from_angles(10, -0.5), p));
  BOOST_TEST(!t.lookup(Vec3(0, 0, -1), p));
}

// The rays are marched in the table's own frame: a table for the sun at another azimuth, or for a
// camera elsewhere at the same radius, has the same entries, so reoriented() serves it with the
// same values; a table for another sun zenith angle or radius cannot be reoriented.
BOOST_AUTO_TEST_CASE(entries_depend_on_the_sun_zenith_and_the_radius_only) {
  const Fixture f;
  const Vec3 o(0, 0, R + 300);
  const SkyViewResolution res{16, 8, 9};
  const SkyViewTable north(f.integrator, f.sources, o, direction_from_angles(0, 25), res, 2);
  const SkyViewTable west(f.integrator, f.sources, o, direction_from_angles(271.5, 25), res, 2);
  const SkyViewTable turned = north.reoriented(o, direction_from_angles(271.5, 25));
  std::mt19937_64 rng(11);
  RadianceParts a(3), b(3);
  for (int i = 0; i < 300; ++i) {
    const Vec3 d = random_direction(rng);
    BOOST_TEST_CONTEXT("direction " << d.transpose()) {
      BOOST_TEST(west.lookup(d, a) == turned.lookup(d, b));
      for (int k = 0; k < 3; ++k) {
        BOOST_TEST(a.phase_free[k] == b.phase_free[k]);
        for (size_t s = 0; s < a.scattered.size(); ++s) BOOST_TEST(a.scattered[s][k] == b.scattered[s][k]);
      }
    }
  }
  // Another camera at the same radius: the same sky about its own zenith.
  const Vec3 elsewhere = (R + 300) * Vec3(0.6, 0.0, 0.8), up = elsewhere.normalized();
  const Vec3 east(0, 1, 0), north_there = up.cross(east);
  const Vec3 sun_there = std::cos(degrees_to_radians(25)) * north_there + std::sin(degrees_to_radians(25)) * up;
  const SkyViewTable there(f.integrator, f.sources, elsewhere, sun_there, res, 2);
  const Vec3 d_here = direction_from_angles(40, 30),
             d_there = d_here.z() * up + d_here.y() * north_there + d_here.x() * east;
  BOOST_TEST(there.lookup(d_there, a));
  BOOST_TEST(north.lookup(d_here, b));
  BOOST_TEST(relative_difference(a, b) < 1e-5);
  BOOST_CHECK_THROW(north.reoriented(o, direction_from_angles(0, 26)), Error);
  BOOST_CHECK_THROW(north.reoriented(o + Vec3(0, 0, 1), direction_from_angles(0, 25)), Error);
}

// Mirror symmetry about the vertical plane through the sun, and no dependence on thread count.
BOOST_AUTO_TEST_CASE(symmetric_and_deterministic) {
  const Fixture f;
  const Vec3 o(0, 0, R + 1), s = direction_from_angles(0, 10);
  const SkyViewTable one(f.integrator, f.sources, o, s, {32, 16, 16}, 1),
      two(f.integrator, f.sources, o, s, {32, 16, 16}, 2);
  std::mt19937_64 rng(7);
  RadianceParts a(3), b(3), c(3);
  for (int i = 0; i < 200; ++i) {
    const Vec3 d = random_direction(rng);
    const Vec3 mirrored(-d.x(), d.y(), d.z());  // the sun lies in the y-z plane (azimuth 0 = north)
    one.lookup(d, a);
    one.lookup(mirrored, b);
    two.lookup(d, c);
    BOOST_TEST(relative_difference(a, b) < 1e-6);
    for (size_t k = 0; k < a.scattered.size(); ++k) BOOST_TEST((a.scattered[k] == c.scattered[k]).all());
    BOOST_TEST((a.phase_free == c.phase_free).all());
  }
}

// lookup_many gives lookup()'s values exactly, for directions that share the rows' mix with the
// one before (rows of a level panorama: the same zenith angle at neighbouring azimuths, about five
// to a column of the table) and for
// directions that do not (random, on both sides of the horizon, below the ground included).
BOOST_AUTO_TEST_CASE(lookup_many_equals_lookup) {
  const Fixture f;
  const Vec3 o(0, 0, R + 500), s = direction_from_angles(0, 20);
  const SkyViewTable table(f.integrator, f.sources, o, s, {32, 16, 16}, 1);
  std::vector<Vec3> dirs;
  for (const double elevation : {60.0, 5.0, 0.0, -3.0, -40.0})
    for (int k = 0; k < 150; ++k) dirs.push_back(direction_from_angles(k * 2.4, elevation));
  std::mt19937_64 rng(11);
  for (int k = 0; k < 200; ++k) dirs.push_back(random_direction(rng));
  const int n = static_cast<int>(dirs.size()), entry = table.parts() * 3;
  std::vector<float> many(static_cast<size_t>(n) * entry);
  std::unique_ptr<bool[]> found(new bool[static_cast<size_t>(n)]);
  table.lookup_many(n, dirs.data(), many.data(), found.get());
  RadianceParts one(3);
  for (int i = 0; i < n; ++i) {
    BOOST_TEST_REQUIRE(found[i] == table.lookup(dirs[static_cast<size_t>(i)], one));
    if (!found[i]) continue;
    const float* m = many.data() + static_cast<size_t>(i) * entry;
    for (size_t p = 0; p < one.scattered.size(); ++p)
      for (int l = 0; l < 3; ++l) BOOST_TEST(m[p * 3 + static_cast<size_t>(l)] == one.scattered[p][l]);
    for (int l = 0; l < 3; ++l) BOOST_TEST(m[one.scattered.size() * 3 + static_cast<size_t>(l)] == one.phase_free[l]);
  }
}

// Interpolated against marched, over random directions on both sides of the horizon, for a sun
// high, low, grazing and below the horizon, and cameras on the ground and in the air: the 99th
// percentile of the relative difference stays below 1e-3 at the default resolution, a fifth of
// the 0.5 % error budget of a render (the quadrature along the ray has the rest).
BOOST_AUTO_TEST_CASE(interpolation_error_at_default_resolution) {
  const Fixture f;
  for (double height : {1.0, 2000.0})
    for (double sun_el : {30.0, 10.0, 2.0, -3.0}) {
      const Vec3 o(0, 0, R + height), s = direction_from_angles(0, sun_el);
      const SkyViewTable t(f.integrator, f.sources, o, s, SkyViewResolution{}, 2);
      std::mt19937_64 rng(11);
      std::vector<double> errors;
      RadianceParts p(3);
      double worst = 0.0;
      Vec3 worst_dir;
      for (int i = 0; i < 2000; ++i) {
        Vec3 d = random_direction(rng);
        if (i % 2) d.z() *= 0.05;  // half of them within a few degrees of the horizon
        d.normalize();
        t.lookup(d, p);
        errors.push_back(relative_difference(p, f.direct(o, d, s)));
        if (errors.back() > worst) {
          worst = errors.back();
          worst_dir = d;
        }
      }
      std::sort(errors.begin(), errors.end());
      const double p99 = errors[errors.size() * 99 / 100];
      BOOST_TEST_MESSAGE("camera " << height << " m, sun " << sun_el << " deg: p50 " << errors[errors.size() / 2]
                                   << " p99 " << p99 << " max " << worst << " at elevation "
                                   << std::asin(worst_dir.z()) * 180 / M_PI << " deg");
      BOOST_TEST_CONTEXT("camera " << height << " m, sun " << sun_el << " deg") { BOOST_TEST(p99 < 1e-3); }
    }
}

// ScatteringSources::higher_light = false: the march the higher-order source shapes, without its
// light. What was scattered once is the same to the last bit; the phase-free part lacks exactly the
// source's light (the ground lit by the sky, the air by the source).
BOOST_AUTO_TEST_CASE(a_march_without_the_higher_orders_light_keeps_the_light_scattered_once) {
  const Fixture f;
  const Vec3 o(0, 0, R + 1.0);
  for (double sun_el : {30.0, -3.0})
    for (const Vec3& d :
         {direction_from_angles(30, 20), direction_from_angles(200, 1), direction_from_angles(90, -20)}) {
      const Vec3 s = direction_from_angles(0, sun_el);
      ScatteringSources without = f.sources;
      without.higher_light = false;
      ScatteringWorkspace ws(3);
      RadianceParts a(3), b(3);
      f.integrator.radiance_parts(o, d, s, f.sources, ws, a);
      f.integrator.radiance_parts(o, d, s, without, ws, b);
      BOOST_TEST_CONTEXT("sun " << sun_el << " deg, direction " << d.transpose()) {
        for (size_t k = 0; k < a.scattered.size(); ++k)
          for (int i = 0; i < 3; ++i) BOOST_TEST(a.scattered[k][i] == b.scattered[k][i]);
        for (int i = 0; i < 3; ++i)
          BOOST_TEST(b.phase_free[i] < 0.99f * a.phase_free[i]);  // the source lights every ray
      }
    }
}

// The higher orders' light from a coarser table (SkyViewResolution::higher_sky_rows): the light
// scattered once is the table's own (its entries the same), the higher orders' within 1e-3 of the
// table marched with them at every ray (99th percentile over random directions, as above; the
// smooth source here interpolates far better than that).
BOOST_AUTO_TEST_CASE(the_higher_orders_from_a_coarser_table) {
  const Fixture f;
  for (double sun_el : {10.0, -3.0}) {
    const Vec3 o(0, 0, R + 1.0), s = direction_from_angles(0, sun_el);
    const SkyViewTable full(f.integrator, f.sources, o, s, SkyViewResolution{}, 2);
    SkyViewResolution res;
    res.higher_sky_rows = 32;
    res.higher_azimuths = 32;
    const SkyViewTable coarse(f.integrator, f.sources, o, s, res, 2);
    std::mt19937_64 rng(5);
    std::vector<double> errors;
    bool differs = false;
    RadianceParts a(3), b(3);
    for (int i = 0; i < 2000; ++i) {
      Vec3 d = random_direction(rng);
      if (i % 2) d.z() *= 0.05;
      d.normalize();
      full.lookup(d, a);
      coarse.lookup(d, b);
      for (size_t k = 0; k < a.scattered.size(); ++k)
        for (int l = 0; l < 3; ++l) BOOST_TEST_REQUIRE(a.scattered[k][l] == b.scattered[k][l]);
      differs = differs || (a.phase_free - b.phase_free).abs().maxCoeff() > 0.0f;
      errors.push_back(relative_difference(b, a));
    }
    std::sort(errors.begin(), errors.end());
    BOOST_TEST_MESSAGE("sun " << sun_el << " deg: p50 " << errors[errors.size() / 2] << " p99 "
                              << errors[errors.size() * 99 / 100] << " max " << errors.back());
    BOOST_TEST_CONTEXT("sun " << sun_el << " deg") {
      BOOST_TEST(differs);  // the coarse table's light, not the rays' own
      BOOST_TEST(errors[errors.size() * 99 / 100] < 1e-3);
    }
  }
}

BOOST_AUTO_TEST_SUITE_END()  // test_sky_view_table
