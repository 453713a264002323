#include <boost/test/unit_test.hpp>

#include <cmath>
#include <limits>
#include <random>

#include "atmosphere_fixtures.hpp"
#include "skyspec/error.hpp"
#include "skyspec/phase_function.hpp"
#include "skyspec/terrain.hpp"
#include "skyspec/units.hpp"
#include "transport/single_scattering.hpp"

BOOST_AUTO_TEST_SUITE(test_terrain)

using namespace skyspec;

namespace {
constexpr double R = 6360e3;
constexpr double kInf = std::numeric_limits<double>::infinity();

// A notched ridge 20 km west of the reference point, 1.5 km high, on a 100 m grid.
RidgeSpec notched_ridge() {
  RidgeSpec r;
  r.notch_spacing_m = 6000.0;
  return r;
}
const Terrain& ridge_terrain() {
  static const Terrain t(ridge_heights(notched_ridge(), 100.0), R);
  return t;
}

// The first t in [0, t_max] where the ray is at or below the surface, by marching `step` metres
// and bisecting: independent of the quadtree.
double marched_hit(const Terrain& terrain, const Vec3& o, const Vec3& d, double t_max, double step) {
  double prev = 0.0;
  if (terrain.clearance(o) <= 0.0) return 0.0;
  for (double t = step; t <= t_max; t += step) {
    if (terrain.clearance(o + t * d) <= 0.0) {
      double a = prev, b = t;
      for (int i = 0; i < 60; ++i) {
        const double m = 0.5 * (a + b);
        (terrain.clearance(o + m * d) > 0.0 ? a : b) = m;
      }
      return b;
    }
    prev = t;
  }
  return kInf;
}

struct ZeroSunColumns : SunColumns {
  Columns at(double, double) const override { return Columns{}; }
};
}  // namespace

BOOST_AUTO_TEST_CASE(grid_heights_follow_the_analytic_ridge) {
  const Terrain& t = ridge_terrain();
  BOOST_TEST(t.max_height_m() == 1500.0, boost::test_tools::tolerance(1e-3));
  // The crest 20 km west; a notch's bottom at 3 km north of the axis: 1500 (1 - 0.6).
  BOOST_TEST(t.height_at(-20000.0, 0.0) == 1500.0, boost::test_tools::tolerance(1e-6));
  BOOST_TEST(t.height_at(-20000.0, 3000.0) == 600.0, boost::test_tools::tolerance(1e-6));
  BOOST_TEST(t.height_at(0.0, 0.0) == 0.0);
  // Between samples the grid is bilinear: within 1 % of the smooth profile's height.
  for (double e : {-21234.0, -19876.5, -22222.2})
    BOOST_TEST(std::abs(t.height_at(e, 1234.5) - ridge_height_at(notched_ridge(), e, 1234.5)) < 15.0);
  // The normal on the crest's flank faces away from it (east, on the east flank) and up.
  const Vec3 flank = (R + t.height_at(-19000.0, 0.0)) * Vec3(-19000.0, 0.0, R).normalized();
  const Vec3 n = t.normal_under(flank);
  BOOST_TEST(n.x() > 0.2);
  BOOST_TEST(n.z() > 0.5);
}

BOOST_AUTO_TEST_CASE(rays_meet_the_surface_where_marching_finds_it) {
  const Terrain& terrain = ridge_terrain();
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> az(200.0, 340.0), el(-4.0, 6.0);
  const Vec3 o(0.0, 0.0, R + 400.0);
  int hits = 0;
  for (int i = 0; i < 120; ++i) {
    const Vec3 d = direction_from_angles(az(rng), el(rng));
    const double t_max = std::min(60000.0, sphere_entry_distance(o, d, R));  // up to the sphere's ground
    const double expected = marched_hit(terrain, o, d, t_max, 2.0);
    const double found = terrain.intersect(o, d, 0.0, t_max);
    if (std::isfinite(expected)) ++hits;
    // A 2 m march can step over a sliver it grazes; the quadtree finds it then, nothing else.
    if (std::isfinite(expected) && std::isfinite(found))
      BOOST_TEST(std::abs(found - expected) < 0.01);
    else
      BOOST_TEST(std::isfinite(found) == std::isfinite(expected), "ray " << i << ": " << found << " vs " << expected);
  }
  BOOST_TEST(hits > 20);  // the case covers both
  BOOST_TEST(hits < 110);
}

BOOST_AUTO_TEST_CASE(sun_visibility_matches_marching) {
  const Terrain& terrain = ridge_terrain();
  const Vec3 s = direction_from_angles(270.0, 2.0);  // low in the west, behind the ridge
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> east(-19000.0, 30000.0), north(-30000.0, 30000.0), alt(10.0, 2500.0);
  int dark = 0;
  for (int i = 0; i < 200; ++i) {
    const double e = east(rng), n = north(rng);
    const Vec3 p = (R + terrain.height_at(e, n) + alt(rng)) * Vec3(e, n, R).normalized();
    const bool marched = std::isfinite(marched_hit(terrain, p, s, 100000.0, 5.0));
    BOOST_TEST(terrain.shadowed(p, s) == marched, "point " << i);
    dark += marched;
  }
  BOOST_TEST(dark > 20);
  BOOST_TEST(dark < 180);
}

// The sunlit parts of view rays against the visibility probed every 0.5 m.
BOOST_AUTO_TEST_CASE(sunlit_parts_match_dense_probes) {
  const Terrain& terrain = ridge_terrain();
  const Vec3 s = direction_from_angles(270.0, 2.5);
  const Vec3 o(0.0, 0.0, R + 300.0);
  for (double az : {300.0, 0.0, 60.0, 90.0, 120.0}) {
    const Vec3 d = direction_from_angles(az, 1.0);
    const double t1 = 40000.0;
    std::vector<Interval> parts;
    terrain.sunlit_parts(o, d, 0.0, t1, s, parts);
    double lit = 0.0, probed = 0.0;
    for (const Interval& p : parts) lit += p.length_m();
    const double step = 0.5;
    for (double t = 0.5 * step; t < t1; t += step) probed += terrain.shadowed(o + t * d, s) ? 0.0 : step;
    BOOST_TEST(std::abs(lit - probed) < 2.0, "azimuth " << az << ": " << lit << " m lit vs " << probed << " m probed");
    for (size_t k = 1; k < parts.size(); ++k) BOOST_TEST(parts[k].t0_m > parts[k - 1].t1_m);
  }
}

// Single scattering in a homogeneous layer lit by an unattenuated sun, along a ray that runs in
// and out of the notched ridge's shadows: the integrator against the brute-force integral
// E beta p int exp(-beta_ext t) V(t) dt, V the visibility of the sun probed every 0.25 m.
BOOST_AUTO_TEST_CASE(single_scattering_in_terrain_shadow_matches_brute_force) {
  const std::vector<double> nm = {550};
  const AtmosphereModel atm(test::simple_atmosphere(ProfileKind::Constant, 10e3, nm, {13.5e-6}, 0.0),
                            WavelengthGrid::from_list(nm));
  const ZeroSunColumns zero;
  const SingleScattering ss(atm, zero, {64});
  const Terrain& terrain = ridge_terrain();
  const Vec3 s = direction_from_angles(270.0, 2.5);
  const Vec3 o(0.0, 0.0, R + 300.0);
  const double beta = 13.5e-6;
  for (double az : {20.0, 70.0, 150.0}) {
    const Vec3 d = direction_from_angles(az, 0.5);
    ScatteringSources sources;
    sources.terrain = &terrain;
    sources.max_distance_m = 60000.0;  // the layer ends at the distance cap
    ScatteringWorkspace ws(1);
    Spectrum L(1);
    ss.radiance(o, d, s, Spectrum::Constant(1, 1.0f), sources, ws, L);
    double brute = 0.0, unshadowed = 0.0;
    const double step = 0.25;
    for (double t = 0.5 * step; t < 60000.0; t += step) {
      const double f = beta * std::exp(-beta * t) * step;
      unshadowed += f;
      if (!terrain.shadowed(o + t * d, s)) brute += f;
    }
    brute *= rayleigh_phase(d.dot(s));
    unshadowed *= rayleigh_phase(d.dot(s));
    BOOST_TEST(brute < 0.95 * unshadowed);  // the ray does cross shadows
    BOOST_TEST(static_cast<double>(L[0]) == brute, boost::test_tools::tolerance(1e-4));
  }
}

namespace {
// Three wavelengths of air and haze over a ground of albedo 0.3; a grid of height 0, 20 km square,
// centred on the reference point.
const test::IntegratorChain& flat_ground_chain() {
  static const std::vector<double> nm = {440, 550, 680};
  static const test::IntegratorChain chain = [] {
    AtmosphereSpec spec = test::simple_atmosphere(ProfileKind::Exponential, 60e3, nm, {33.1e-6, 13.5e-6, 5.8e-6}, 8e-6);
    spec.ground.albedo = 0.3;
    return test::IntegratorChain(spec, nm, {128, 256, 64}, 64);
  }();
  return chain;
}
HeightGrid flat_grid() {
  HeightGrid flat;
  flat.columns = flat.rows = 201;
  flat.spacing_m = 100.0;
  flat.east0_m = flat.north0_m = -10000.0;
  flat.height_m.assign(201 * 201, 0.0f);
  return flat;
}
}  // namespace

// Terrain of height 0 everywhere is the sphere's ground: the same light, ground included.
BOOST_AUTO_TEST_CASE(flat_terrain_is_the_ground) {
  const test::IntegratorChain& chain = flat_ground_chain();
  const HeightGrid flat = flat_grid();
  const Terrain terrain(flat, 6360e3);
  const Vec3 o(0.0, 0.0, 6360e3 + 500.0), s = direction_from_angles(120.0, 15.0);
  for (double el : {-20.0, -2.0, 3.0, 40.0}) {
    const Vec3 d = direction_from_angles(30.0, el);
    ScatteringSources with;
    with.terrain = &terrain;
    ScatteringWorkspace ws(3);
    Spectrum a(3), b(3);
    chain.integrator.radiance(o, d, s, Spectrum::Ones(3), ScatteringSources{}, ws, a);
    chain.integrator.radiance(o, d, s, Spectrum::Ones(3), with, ws, b);
    for (int i = 0; i < 3; ++i) BOOST_TEST(b[i] == a[i], boost::test_tools::tolerance(1e-5f));
  }
}

// The terrain's own albedo and its map: the light its surface reflects is the ground's times
// (own albedo x map factor) / ground albedo, wavelength by wavelength; the air's is unchanged.
BOOST_AUTO_TEST_CASE(terrain_albedo_and_map_scale_the_reflection) {
  const test::IntegratorChain& chain = flat_ground_chain();
  const HeightGrid flat = flat_grid();
  TerrainAlbedo own;
  own.spectrum = SpectrumD(3);
  own.spectrum << 0.05, 0.2, 0.9;
  own.map.assign(201 * 201, 1.0f);  // factor 0.25 west of the reference point, 1 east of it
  for (int r = 0; r < 201; ++r)
    for (int c = 0; c < 100; ++c) own.map[static_cast<size_t>(r) * 201 + c] = 0.25f;
  TerrainAlbedo black;
  black.spectrum = SpectrumD::Zero(3);
  const Terrain coloured(flat, 6360e3, own), dark(flat, 6360e3, black), plain(flat, 6360e3);
  BOOST_TEST(coloured.albedo_factor_under(Vec3(1370.0, 0.0, 6360e3)) == 1.0);
  BOOST_TEST(coloured.albedo_factor_under(Vec3(-1370.0, 0.0, 6360e3)) == 0.25);
  BOOST_TEST(coloured.albedo_factor_under(Vec3(-50.0, 0.0, 6360e3)) == 0.625);   // halfway across the edge's cell
  BOOST_TEST(coloured.albedo_factor_under(Vec3(-20000.0, 0.0, 6360e3)) == 1.0);  // beyond the grid
  const Vec3 o(0.0, 0.0, 6360e3 + 500.0), s = direction_from_angles(120.0, 15.0);
  for (double az : {90.0, 270.0}) {
    const Vec3 d = direction_from_angles(az, -20.0);  // the ground 1.37 km away, east or west
    const double factor = az == 90.0 ? 1.0 : 0.25;
    ScatteringWorkspace ws(3);
    Spectrum L(3), L_dark(3), L_plain(3);
    ScatteringSources with;
    with.terrain = &coloured;
    chain.integrator.radiance(o, d, s, Spectrum::Ones(3), with, ws, L);
    with.terrain = &dark;
    chain.integrator.radiance(o, d, s, Spectrum::Ones(3), with, ws, L_dark);
    with.terrain = &plain;
    chain.integrator.radiance(o, d, s, Spectrum::Ones(3), with, ws, L_plain);
    for (int i = 0; i < 3; ++i) {
      const double ratio = (L[i] - L_dark[i]) / (L_plain[i] - L_dark[i]);
      BOOST_TEST(ratio == own.spectrum[i] * factor / 0.3, boost::test_tools::tolerance(1e-4));
    }
  }
  own.spectrum[1] = 1.5;
  BOOST_CHECK_THROW((void)Terrain(flat, 6360e3, own), Error);
  own.spectrum[1] = 0.2;
  own.map.pop_back();
  BOOST_CHECK_THROW((void)Terrain(flat, 6360e3, own), Error);
}

BOOST_AUTO_TEST_CASE(malformed_grids_are_refused) {
  HeightGrid g;
  g.columns = g.rows = 2;
  g.spacing_m = 10.0;
  g.height_m = {0.0f, 1.0f, 2.0f};
  BOOST_CHECK_THROW((void)Terrain(g, R), Error);
  g.height_m = {0.0f, 1.0f, 2.0f, std::numeric_limits<float>::quiet_NaN()};
  BOOST_CHECK_THROW((void)Terrain(g, R), Error);
  g.height_m = {0.0f, 1.0f, 2.0f, -3.0f};
  BOOST_CHECK_THROW((void)Terrain(g, R), Error);
  g.height_m = {0.0f, 1.0f, 2.0f, 3.0f};
  g.spacing_m = 0.0;
  BOOST_CHECK_THROW((void)Terrain(g, R), Error);
  g.spacing_m = 5e6;  // reaches past 30 degrees of the planet
  BOOST_CHECK_THROW((void)Terrain(g, R), Error);
}

BOOST_AUTO_TEST_SUITE_END()
