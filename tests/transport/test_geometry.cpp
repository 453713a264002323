#include <boost/test/unit_test.hpp>

#include <cmath>
#include <random>

#include "skyspec/geometry.hpp"
#include "skyspec/vertical_cylinder.hpp"

BOOST_AUTO_TEST_SUITE(test_geometry)

using namespace skyspec;

namespace {
constexpr double R = 6360e3, Rt = 6420e3;
}

BOOST_AUTO_TEST_CASE(ray_from_outside_hits_both_sides) {
  const SphereHit h = intersect_sphere(Vec3(0, 0, -10), Vec3(0, 0, 1), 2.0);
  BOOST_TEST(h.hit);
  BOOST_TEST(h.t_near_m == 8.0, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(h.t_far_m == 12.0, boost::test_tools::tolerance(1e-12));
}

BOOST_AUTO_TEST_CASE(ray_from_inside_has_negative_near_root) {
  const SphereHit h = intersect_sphere(Vec3(0, 0, 0.5), Vec3(0, 0, 1), 2.0);
  BOOST_TEST(h.hit);
  BOOST_TEST(h.t_near_m == -2.5, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(h.t_far_m == 1.5, boost::test_tools::tolerance(1e-12));
}

BOOST_AUTO_TEST_CASE(missing_ray_and_sphere_behind) {
  BOOST_TEST(!intersect_sphere(Vec3(0, 3, -10), Vec3(0, 0, 1), 2.0).hit);
  const SphereHit behind = intersect_sphere(Vec3(0, 0, 10), Vec3(0, 0, 1), 2.0);
  BOOST_TEST(behind.hit);
  BOOST_TEST(behind.t_far_m < 0.0);  // callers reject hits behind the origin
}

BOOST_AUTO_TEST_CASE(tangent_ray_touches_once) {
  const SphereHit h = intersect_sphere(Vec3(-5, 2, 0), Vec3(1, 0, 0), 2.0);
  BOOST_TEST(h.hit);
  BOOST_TEST(h.t_near_m == 5.0, boost::test_tools::tolerance(1e-7));
  BOOST_TEST(h.t_far_m == 5.0, boost::test_tools::tolerance(1e-7));
}

BOOST_AUTO_TEST_CASE(origin_on_the_surface) {
  const SphereHit out = intersect_sphere(Vec3(0, 0, R), Vec3(0, 0, 1), R);
  BOOST_TEST(out.hit);
  BOOST_TEST(std::abs(out.t_far_m) < 1e-6);
  const SphereHit in = intersect_sphere(Vec3(0, 0, R), Vec3(0, 0, -1), R);
  BOOST_TEST(in.t_far_m == 2 * R, boost::test_tools::tolerance(1e-12));
}

// A camera 1 m above the ground looking horizontally must clear the ground, and its distance to
// the top of the atmosphere must be accurate: sqrt(Rt^2 - (R+1)^2) to better than a millimetre.
BOOST_AUTO_TEST_CASE(planet_scale_precision_horizontal_ray) {
  const Vec3 o(0, 0, R + 1.0), d(1, 0, 0);
  BOOST_TEST(!intersect_sphere(o, d, R).hit);
  const SphereHit top = intersect_sphere(o, d, Rt);
  const long double exact =
      std::sqrt(static_cast<long double>(Rt) * Rt - static_cast<long double>(R + 1.0) * (R + 1.0));
  BOOST_TEST(std::abs(top.t_far_m - static_cast<double>(exact)) < 1e-3);
}

// Looking slightly down from 1 m: the ground is hit at the distance where the ray's altitude is
// zero; checked against long double arithmetic.
BOOST_AUTO_TEST_CASE(planet_scale_precision_grazing_ground_hit) {
  const double h = 1.0, dip = 1e-3;  // radians below horizontal (horizon dip from 1 m is ~5.6e-4)
  const Vec3 o(0, 0, R + h), d(std::cos(dip), 0, -std::sin(dip));
  const SphereHit g = intersect_sphere(o, d, R);
  BOOST_TEST(g.hit);
  const long double r = R + h, b = -r * std::sin(static_cast<long double>(dip));
  const long double c = (r - R) * (r + R);
  const long double t_exact = -b - std::sqrt(b * b - c);
  BOOST_TEST(std::abs(g.t_near_m - static_cast<double>(t_exact)) < 1e-4);
  const Vec3 p = o + g.t_near_m * d;
  BOOST_TEST(std::abs(p.norm() - R) < 1e-4);
}

BOOST_AUTO_TEST_CASE(shadow_sun_overhead_everything_lit) {
  const IntervalSet lit = lit_intervals(Vec3(0, 0, R + 1), Vec3(1, 0, 0), 0, 1e6, Vec3(0, 0, 1), R);
  BOOST_TEST(lit.count == 1);
  BOOST_TEST(lit.parts[0].t0_m == 0.0);
  BOOST_TEST(lit.parts[0].t1_m == 1e6);
}

BOOST_AUTO_TEST_CASE(shadow_night_side_zenith_ray_is_dark) {
  // Sun 30 degrees below the horizon: the zenith column is in shadow up to ~984 km.
  const Vec3 s(0, std::cos(30 * M_PI / 180), -std::sin(30 * M_PI / 180));
  const IntervalSet lit = lit_intervals(Vec3(0, 0, R + 1), Vec3(0, 0, 1), 0, 60e3, s, R);
  BOOST_TEST(lit.count == 0);
  const IntervalSet far = lit_intervals(Vec3(0, 0, R + 1), Vec3(0, 0, 1), 0, 2e6, s, R);
  BOOST_TEST(far.count == 1);
  const double h_exit = R * (1 / std::cos(30 * M_PI / 180) - 1);
  BOOST_TEST(far.parts[0].t0_m == h_exit - 1, boost::test_tools::tolerance(1e-9));
}

// The cylinder test must agree with the definition: a point is lit iff the ray from it towards
// the sun does not hit the planet.
BOOST_AUTO_TEST_CASE(shadow_matches_sun_ray_test_at_random_points) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  int checked = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    Vec3 s(u(rng), u(rng), u(rng)), d(u(rng), u(rng), u(rng));
    if (s.norm() < 0.1 || d.norm() < 0.1) continue;
    s.normalize();
    d.normalize();
    const Vec3 o = Vec3(u(rng), u(rng), u(rng)) * 1.5 * R;
    const double t1 = 3 * R;
    const IntervalSet lit = lit_intervals(o, d, 0, t1, s, R);
    for (int k = 0; k < 50; ++k) {
      const double t = t1 * (k + 0.5) / 50;
      const Vec3 p = o + t * d;
      if (p.norm() <= R * 1.0001) continue;  // inside or touching the planet: not a sample point
      const SphereHit toward_sun = intersect_sphere(p, s, R);
      const bool blocked = toward_sun.hit && toward_sun.t_far_m > 0;
      bool in_lit = false;
      for (int i = 0; i < lit.count; ++i) in_lit |= t >= lit.parts[i].t0_m && t <= lit.parts[i].t1_m;
      // Skip points within a metre of a boundary (either answer is right there).
      bool near_boundary = false;
      for (int i = 0; i < lit.count; ++i)
        near_boundary |= std::abs(t - lit.parts[i].t0_m) < 1 || std::abs(t - lit.parts[i].t1_m) < 1;
      if (near_boundary) continue;
      BOOST_TEST(in_lit == !blocked);
      ++checked;
    }
  }
  BOOST_TEST(checked > 10000);
}

// A shower's cylinder (vertical_cylinder.hpp): 3 km wide, its axis 8 km north of the reference
// point. Horizontal lines through it are cut at the walls; the points found lie on them; a line
// along the axis runs inside for ever; the planet's far side is not inside.
BOOST_AUTO_TEST_CASE(vertical_cylinder_walls) {
  const VerticalCylinder c{Vec3(0.0, 8000.0, R).normalized(), 3000.0};
  const Vec3 o(0.0, 0.0, R + 2.0);
  BOOST_TEST(!c.contains(o));
  BOOST_TEST(c.contains(Vec3(0.0, 8000.0, R + 5000.0)));
  BOOST_TEST(!c.contains(-Vec3(0.0, 8000.0, R)));
  double t0 = 0.0, t1 = 0.0;
  const Vec3 north = Vec3(0.0, 1.0, 0.0);
  BOOST_TEST_REQUIRE(c.crossing(o, north, t0, t1));
  BOOST_TEST(t0 == 5000.0, boost::test_tools::tolerance(1e-6));  // to the wall's axis-perpendicular distance
  BOOST_TEST(t1 == 11000.0, boost::test_tools::tolerance(1e-6));
  // Every crossing's ends lie on the wall, its middle inside, for random lines near the shower.
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int crossed = 0;
  for (int k = 0; k < 2000; ++k) {
    const Vec3 p = o + Vec3(4000.0 * u(rng), 4000.0 * u(rng), 3000.0 * (u(rng) + 1.0));
    Vec3 d(u(rng), u(rng), u(rng));
    if (d.norm() < 1e-3) continue;
    d.normalize();
    if (!c.crossing(p, d, t0, t1)) continue;
    ++crossed;
    for (double t : {t0, t1}) {
      const Vec3 x = p + t * d;
      const Vec3 perp = x - x.dot(c.axis) * c.axis;
      BOOST_TEST(perp.norm() == 3000.0, boost::test_tools::tolerance(1e-7));
    }
    BOOST_TEST(c.contains(p + 0.5 * (t0 + t1) * d));
    BOOST_TEST(!c.contains(p + (t1 + 1.0) * d));
    BOOST_TEST(!c.contains(p + (t0 - 1.0) * d));
  }
  BOOST_TEST(crossed > 500);
  BOOST_TEST_REQUIRE(c.crossing(Vec3(0.0, 8000.0, R + 100.0), c.axis, t0, t1));
  BOOST_TEST(std::isinf(t0));
  BOOST_TEST(std::isinf(t1));
  BOOST_TEST(!c.crossing(o, Vec3(1.0, 0.0, 0.0), t0, t1));  // eastwards: 8 km from the axis
}

BOOST_AUTO_TEST_SUITE_END()  // test_geometry
