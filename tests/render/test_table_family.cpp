// Tables interpolated between the atmospheres of a grid (render.ms_tables = "interpolated",
// render/table_family.hpp): which atmospheres a scene's blend reads and with what weights, that a
// scene on the grid gets exactly its own tables, that a scene between the grid's atmospheres gets
// tables close to its own exact ones, and what is refused.
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <string>
#include <vector>

#include "render/scene_tables.hpp"
#include "render/table_family.hpp"
#include "scene_fixtures.hpp"
#include "transport/optical_depth.hpp"
#include "transport/single_scattering.hpp"

BOOST_AUTO_TEST_SUITE(test_table_family)

using namespace skyspec;

namespace {

// Small tables, built in a fraction of a second each and not cached on disk.
const std::string kSmall =
    "render.cache_tables = false\nrender.scattering_orders = 3\nrender.ms_altitude_samples = 6\n"
    "render.ms_sun_samples = 12\nrender.ms_angular_degree = 4\nrender.table_altitude_samples = 32\n"
    "render.table_zenith_samples = 64\nspectrum.wavelengths_nm = [400.0, 550.0, 700.0]\n";

Scene small_scene(const std::string& toml) {
  return test::scene_with(kSmall + "render.ms_tables = \"interpolated\"\n" + toml);
}

// The scene's own tables, built for its atmosphere.
std::shared_ptr<const ScatteringOrders> exact_tables(const Scene& s) {
  const AtmosphereModel atmosphere(s.atmosphere, make_wavelength_grid(s), false);
  const auto table = SunColumnTable::shared(atmosphere, sun_table_resolution(s), SunColumnTable::MuBand{});
  const TableSunColumns columns(*table);
  const SingleScattering integrator(atmosphere, columns, IntegratorSettings{s.render.view_segments});
  return std::make_shared<const ScatteringOrders>(integrator, multiple_scattering_settings(s));
}

std::shared_ptr<const ScatteringOrders> interpolated(const Scene& s) {
  const AtmosphereModel atmosphere(s.atmosphere, make_wavelength_grid(s), false);
  std::string why;
  auto t = interpolated_scattering_orders(s, atmosphere, &why);
  BOOST_TEST_REQUIRE(t != nullptr, why);
  return t;
}

// The largest relative differences of the two tables' sources (the sum of the orders, every
// medium) over altitudes and view directions, in daylight (the sun 17 and 64 degrees up) and near
// the terminator (1 degree up, 3 down), and of their ground irradiance.
struct Differences {
  double day = 0.0, terminator = 0.0;
};
Differences largest_differences(const ScatteringOrders& a, const ScatteringOrders& b, int wavelengths) {
  const double R = 6360e3;
  std::vector<float> sa(static_cast<size_t>(wavelengths) * 4 + 64), sb(sa.size());
  float* out_a[2] = {sa.data(), sa.data() + wavelengths + 16};
  float* out_b[2] = {sb.data(), sb.data() + wavelengths + 16};
  Differences d;
  const auto compare = [&](size_t count, double& worst) {
    for (size_t i = 0; i < count; ++i)
      if (std::abs(sb[i]) > 1e-12) worst = std::max(worst, std::abs(sa[i] / sb[i] - 1.0));
  };
  for (double mu_s : {0.9, 0.3, 0.02, -0.05}) {
    double& worst = mu_s > 0.1 ? d.day : d.terminator;
    for (double h : {10.0, 1500.0, 12000.0})
      for (double mu_v : {0.8, 0.1, -0.4}) {
        a.source(R + h, mu_s, mu_v, mu_s * mu_v, out_a);  // the sun 90 degrees off in azimuth
        b.source(R + h, mu_s, mu_v, mu_s * mu_v, out_b);
        compare(sa.size(), worst);
      }
    a.ground_irradiance(mu_s, sa.data());
    b.ground_irradiance(mu_s, sb.data());
    compare(static_cast<size_t>(wavelengths), worst);
  }
  return d;
}

}  // namespace

BOOST_AUTO_TEST_CASE(a_scene_on_the_grid_reads_only_its_own_atmosphere) {
  const Scene s = small_scene(
      "atmosphere.mie.scattering_per_m = 2e-5\natmosphere.mie.angstrom_exponent = 0\natmosphere.ozone.column_DU = 300");
  const auto family = table_family(s);
  BOOST_TEST_REQUIRE(family.has_value());
  BOOST_TEST_REQUIRE(family->lower.members.size() == 1u);
  BOOST_TEST(family->upper.members.empty());
  for (float w : family->lower.weights[0]) BOOST_TEST(w == 1.0f);
  const AtmosphereSpec& m = family->lower.members[0].atmosphere;
  BOOST_TEST(m.mie.scattering_per_m == 2e-5);
  BOOST_TEST(m.mie.angstrom_exponent == 0.0);
  BOOST_TEST(m.ozone.column_DU == 300.0);
  // Its blend is the member's tables, bit for bit.
  const auto blended = interpolated(s);
  Scene own = s;
  own.render.ms_tables = RenderSpec::Tables::Exact;
  const Differences d = largest_differences(*blended, *exact_tables(own), 3);
  BOOST_TEST(d.day == 0.0);
  BOOST_TEST(d.terminator == 0.0);
}

BOOST_AUTO_TEST_CASE(the_weights_of_a_scene_between_the_grids_atmospheres) {
  // beta(lambda) = 3e-5 (lambda / 550)^-1.3: 4.5e-5 at 400 nm, 1.9e-5 at 700 nm; ozone 250 DU.
  const Scene s = small_scene(
      "atmosphere.mie.scattering_per_m = 3e-5\natmosphere.mie.angstrom_exponent = 1.3\natmosphere.ozone.column_DU = "
      "250");
  const auto family = table_family(s);
  BOOST_TEST_REQUIRE(family.has_value());
  BOOST_TEST(family->ozone_t == 0.5f);
  for (const TableFamily::Group* g : {&family->lower, &family->upper}) {
    BOOST_TEST(g->members.size() == g->weights.size());
    for (const Scene& m : g->members) BOOST_TEST(m.atmosphere.mie.angstrom_exponent == 0.0);
    for (int i = 0; i < 3; ++i) {  // a partition of unity at every wavelength, from four amounts each
      double sum = 0.0;
      int used = 0;
      for (const auto& w : g->weights) {
        sum += w[static_cast<size_t>(i)];
        used += w[static_cast<size_t>(i)] != 0.0f;
      }
      BOOST_TEST(sum == 1.0, boost::test_tools::tolerance(1e-6));
      BOOST_TEST(used == 4);
    }
  }
  BOOST_TEST(family->lower.members.front().atmosphere.ozone.column_DU == 200.0);
  BOOST_TEST(family->upper.members.front().atmosphere.ozone.column_DU == 300.0);
  // 400 nm's four amounts (2e-5 .. 1.6e-4) and 550 and 700 nm's (1e-5 .. 8e-5): five in all.
  BOOST_TEST(family->lower.members.size() == 5u);
  BOOST_TEST(scenes_of_tables(s).size() == 10u);
}

BOOST_AUTO_TEST_CASE(a_scene_between_the_grids_atmospheres_gets_tables_close_to_its_own) {
  for (const std::string& toml :
       {std::string("atmosphere.mie.scattering_per_m = 3e-5\natmosphere.mie.angstrom_exponent = 1.3\n"
                    "atmosphere.ozone.column_DU = 250"),
        std::string("atmosphere.mie.scattering_per_m = 1.2e-4\natmosphere.mie.angstrom_exponent = 0.6\n"
                    "atmosphere.ozone.column_DU = 380")}) {
    BOOST_TEST_CONTEXT(toml) {
      const Scene s = small_scene(toml);
      Scene own = s;
      own.render.ms_tables = RenderSpec::Tables::Exact;
      // The entries err most near the terminator at the ground in hazy air, where the sun's light
      // crosses tens of air masses (the message below prints both; a render's radiance errs far
      // less: bench/table_family.py, docs/jobs.md).
      const Differences d = largest_differences(*interpolated(s), *exact_tables(own), 3);
      BOOST_TEST_MESSAGE("largest relative difference of the interpolated tables' sources: daylight "
                         << d.day << ", near the terminator " << d.terminator);
      BOOST_TEST(d.day < 0.015);
      BOOST_TEST(d.terminator < 0.1);
      BOOST_TEST(d.day > 0.0);  // not the exact tables under another name
    }
  }
}

BOOST_AUTO_TEST_CASE(what_is_not_on_the_grid_is_refused_with_the_key_named) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"atmosphere.mie.model = \"opac\"", "atmosphere.mie.model"},
      {"atmosphere.mie.scattering_per_m = 9e-4", "atmosphere.mie.scattering_per_m"},
      {"atmosphere.mie.scattering_per_m = 5e-4\natmosphere.mie.angstrom_exponent = 2", "380 nm"},
      {"atmosphere.ozone.column_DU = 1200", "atmosphere.ozone.column_DU = 1200"},
      {"atmosphere.mie.enabled = false\natmosphere.ozone.enabled = false", "nothing to interpolate"},
      {"render.scattering_orders = 1", "single scattering"},
  };
  for (const auto& [toml, named] : cases) {
    BOOST_TEST_CONTEXT(toml) {
      std::string why;
      BOOST_TEST(!table_family(test::scene_with("render.ms_tables = \"interpolated\"\n" + toml), &why).has_value());
      BOOST_TEST(test::contains(why, named), why);
    }
  }
  // Such a scene's tables are its own: scenes_of_tables names the scene itself.
  const Scene off = test::scene_with("render.ms_tables = \"interpolated\"\natmosphere.ozone.column_DU = 1200");
  BOOST_TEST_REQUIRE(scenes_of_tables(off).size() == 1u);
  BOOST_TEST(scenes_of_tables(off)[0].atmosphere.ozone.column_DU == 1200.0);
}

BOOST_AUTO_TEST_SUITE_END()
