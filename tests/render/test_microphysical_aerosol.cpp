// A sky whose aerosol comes from its microphysics (atmosphere.mie.model = "opac": OPAC's
// continental average by Lorenz-Mie theory, polarising) against the vector Monte Carlo reference,
// which uses the same tabulated scattering matrix: intensity within 2 % + 3 standard errors and
// the degree of linear polarisation within 0.02 (the water-and-aerosols issue's criteria), at the
// standard probes and two wavelengths, 10 000 paths each, for a sun 10 degrees up (the sun at 30 degrees is in
// bench/opac_aerosol.sh, with more paths, and docs/validation.md has its table).
//
// Except on the horizon across from and away from the sun: there the renderer's degree of
// polarisation is known to fall short of the reference by up to 0.076 (here) because the
// scattering-order tables carry the polarised field only to its quadrupole (the polarisation
// issue's item 2; the default scene with its non-polarising aerosol misses by 0.056 there). Those
// two probes are held to 0.08, which fails if that gap grows.

#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>

#include "release_stage.hpp"
#include "scene_fixtures.hpp"
#include "skyspec/camera.hpp"
#include "skyspec/monte_carlo_reference.hpp"
#include "skyspec/render.hpp"

BOOST_AUTO_TEST_SUITE(test_microphysical_aerosol)

using namespace skyspec;

namespace {
Scene opac_scene(double sun_elevation) {
  char toml[400];
  std::snprintf(toml, sizeof toml,
                "[sun]\nelevation_deg = %g\n[spectrum]\nwavelengths_nm = [450, 650]\n[camera]\nwidth = 1\nheight = 1\n"
                "[atmosphere.mie]\nmodel = \"opac\"\n[render]\ncache_tables = false\n[output]\npolarisation = true\n",
                sun_elevation);
  return test::scene_with(toml, "default");
}

struct Largest {
  double intensity = 0.0, intensity_sigmas = 0.0, dolp = 0.0, dolp_quadrupole_limited = 0.0;
};

// The comparison at one sun; prints every probe and returns the largest differences.
Largest compare(double sun, std::int64_t paths) {
  Largest largest;
  {
    const Scene scene = opac_scene(sun);
    const std::vector<ReferenceProbe> probes = standard_reference_probes(scene);
    ReferenceSettings settings;
    settings.paths = paths;
    settings.seed = 2028;
    settings.stokes = true;
    const ReferenceResult mc = monte_carlo_reference(scene, probes, settings);
    const SkyRenderer renderer(scene);
    for (size_t k = 0; k < probes.size(); ++k) {
      const Vec3 dir = direction_from_angles(probes[k].azimuth_deg, probes[k].elevation_deg);
      Spectrum i, q, u;
      renderer.stokes(dir, stokes_frame_axis(dir), i, q, u);
      for (size_t w = 0; w < mc.wavelengths_nm.size(); ++w) {
        const auto& v = mc.stokes[k][w];
        const auto& e = mc.stokes_standard_error[k][w];
        const Eigen::Index j = static_cast<Eigen::Index>(w);
        const double dolp = std::hypot(q[j], u[j]) / i[j], dolp_mc = std::hypot(v[1], v[2]) / v[0];
        std::printf("sun %g, %s, %g nm: I %.5g / %.5g +- %.2g (%+.2f %%), DoLP %.4f / %.4f (%+.4f)\n", sun,
                    probes[k].label.c_str(), mc.wavelengths_nm[w], i[j], v[0], e[0], 100.0 * (i[j] / v[0] - 1.0), dolp,
                    dolp_mc, dolp - dolp_mc);
        BOOST_TEST(std::abs(i[j] - v[0]) <= 0.02 * v[0] + 3.0 * e[0]);
        // The DoLP's standard error, from Q's and U's, propagated to first order.
        const double dolp_se = std::hypot(e[1], e[2]) / v[0] + dolp_mc * e[0] / v[0];
        const bool quadrupole_limited =
            probes[k].label == "horizon across sun" || probes[k].label == "horizon away from sun";
        BOOST_TEST(std::abs(dolp - dolp_mc) <= (quadrupole_limited ? 0.08 : 0.02) + 3.0 * dolp_se,
                   probes[k].label << " " << mc.wavelengths_nm[w] << " nm: DoLP " << dolp << " vs " << dolp_mc);
        largest.intensity = std::max(largest.intensity, std::abs(i[j] / v[0] - 1.0));
        largest.intensity_sigmas = std::max(largest.intensity_sigmas, std::abs(i[j] - v[0]) / e[0]);
        double& d = quadrupole_limited ? largest.dolp_quadrupole_limited : largest.dolp;
        d = std::max(d, std::abs(dolp - dolp_mc));
      }
    }
  }
  return largest;
}

}  // namespace

BOOST_AUTO_TEST_CASE(renderer_matches_the_vector_reference,
                     *boost::unit_test::precondition(test::not_in_sanitizer_stage)) {
  compare(10.0, 10000);
}

// The benchmark's table: three suns, five times the paths.
BOOST_AUTO_TEST_CASE(benchmark_table, *boost::unit_test::disabled() *
                                          boost::unit_test::precondition(test::asked_for_by("SKYSPEC_BENCH_OPAC",
                                                                                            "bench/opac_aerosol.sh"))) {
  for (double sun : {30.0, 10.0, 2.0}) {
    const Largest l = compare(sun, 100000);
    std::printf("| %g | %.2f %% | %.1f | %.4f | %.4f |\n", sun, 100.0 * l.intensity, l.intensity_sigmas, l.dolp,
                l.dolp_quadrupole_limited);
  }
}

BOOST_AUTO_TEST_SUITE_END()
