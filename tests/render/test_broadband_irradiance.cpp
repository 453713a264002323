#include <boost/test/unit_test.hpp>

// The broadband irradiance (broadband_irradiance.hpp): the light transport's runs, one per term of
// the gases' exponential sums, give the direct beam that Bird & Riordan's band models give for the
// same absorber amounts (closed form), leave the wavelengths without gas bands as an ordinary
// render has them, and refuse what they cannot compute.

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "check_helpers.hpp"
#include "physics/gas_bands.hpp"
#include "release_stage.hpp"
#include "render/broadband_irradiance.hpp"
#include "render/irradiance.hpp"
#include "scene_fixtures.hpp"
#include "skyspec/error.hpp"
#include "skyspec/render.hpp"

BOOST_AUTO_TEST_SUITE(test_broadband_irradiance)

using namespace skyspec;

namespace {
// Single scattering and no table cache: the direct beam is what is compared; the diffuse is
// computed as in any irradiance.
Scene scene_at(double sun_elevation_deg) {
  return test::scene_with("[sun]\nelevation_deg = " + std::to_string(sun_elevation_deg) +
                          "\n[render]\nscattering_orders = 1\ncache_tables = false\n[irradiance]\nbroadband = "
                          "true\n[atmosphere.water_vapour]\ncolumn_cm = 2.5\n");
}
}  // namespace

// The gases' transmittance along the sun's path: the broadband run's direct normal irradiance over
// an ordinary render's (no gas bands; the same air, aerosol and ozone) at Bird & Riordan's
// wavelengths to 1060 nm (the ozone table's end), against eqs. 2-8 and 2-11 with the path's absorber
// amounts: the vertical column (sun at the zenith) and twice it (30 degrees: the spherical shell's
// air mass differs from 2 by 0.2 % for air, less for water vapour). Release stage only (its runs are
// ordinary renders; the_runs_add_up runs the broadband irradiance under the sanitizers).
BOOST_AUTO_TEST_CASE(gases_absorb_the_direct_beam_as_the_band_models_say,
                     *boost::unit_test::precondition(test::not_in_sanitizer_stage)) {
  for (const auto& [elevation, air_masses] : {std::pair{90.0, 1.0}, std::pair{30.0, 2.0}}) {
    const Scene scene = scene_at(elevation);
    const BroadbandIrradiance bb = broadband_irradiance(scene, 8, 16);  // the direct beam is compared
    BOOST_TEST(bb.runs == exponential_term_count());
    std::vector<double> nodes;
    for (double nm : bb.wavelengths_nm)
      if (nm <= 1060.0) nodes.push_back(nm);
    Scene plain = scene;
    plain.spectrum.wavelengths_nm = nodes;
    plain.camera.width = plain.camera.height = 1;
    const IrradianceReport ref = irradiance_at_camera(SkyRenderer(plain));
    double largest = 0.0;
    for (size_t k = 0; k < nodes.size(); ++k) {
      const double nm = nodes[k];
      const double a_w = band_coefficient(GasBand::WaterVapour, nm), a_u = band_coefficient(GasBand::MixedGases, nm);
      const double expected = band_transmittance(GasBand::WaterVapour, a_w * 2.5 * air_masses) *
                              band_transmittance(GasBand::MixedGases, a_u * air_masses);
      const double got =
          bb.direct_normal[static_cast<Eigen::Index>(k)] / ref.direct_normal[static_cast<Eigen::Index>(k)];
      const bool both = a_w > 0.0 && a_u > 0.0;
      BOOST_TEST_CONTEXT(nm << " nm, sun at " << elevation << " degrees") {
        BOOST_TEST(std::abs(got - expected) < (both ? 0.01 : 0.003), got << " vs " << expected);
        if (a_w == 0.0 && a_u == 0.0) BOOST_TEST(got == 1.0, boost::test_tools::tolerance(1e-6));
      }
      largest = std::max(largest, std::abs(got - expected));
    }
    std::printf("sun at %g degrees: largest |T - band models| %.4f to 1060 nm\n", elevation, largest);
    // Watts: the broadband holds the render's band and more; diffuse light is there.
    BOOST_TEST(bb.direct_horizontal_W_m2 == bb.direct_normal_W_m2 * std::sin(elevation * 3.14159265358979 / 180.0),
               boost::test_tools::tolerance(1e-6));
    BOOST_TEST(bb.diffuse_horizontal_W_m2 > 0.0);
    BOOST_TEST(std::isfinite(bb.global_horizontal_W_m2()));
  }
}

// The runs' sum (a coarse hemisphere: this case runs under the sanitizers too): five runs, every
// wavelength's irradiance finite and not negative, global = direct + diffuse, the sun's cosine.
BOOST_AUTO_TEST_CASE(the_runs_add_up) {
  const BroadbandIrradiance bb = broadband_irradiance(scene_at(45.0), 4, 8);
  BOOST_TEST(bb.runs == exponential_term_count());
  BOOST_TEST(bb.wavelengths_nm.size() == band_model_wavelengths_nm().size());
  BOOST_TEST((bb.direct_normal.array() >= 0.0).all());
  BOOST_TEST((bb.diffuse_horizontal.array() >= 0.0).all());
  BOOST_TEST(bb.diffuse_horizontal_W_m2 > 0.0);
  BOOST_TEST(bb.direct_normal.allFinite());
  BOOST_TEST(bb.global_horizontal_W_m2() == bb.direct_horizontal_W_m2 + bb.diffuse_horizontal_W_m2);
  BOOST_TEST(bb.cos_sun == std::sqrt(0.5), boost::test_tools::tolerance(1e-3));
}

// What it cannot compute is refused naming the key: a medium not defined to 4000 nm (water's
// refractive index ends at 1100 nm), the RGB-fast path.
BOOST_AUTO_TEST_CASE(refuses_what_it_cannot_compute) {
  Scene fog = scene_at(30.0);
  fog.atmosphere.fog.enabled = true;
  BOOST_CHECK_EXCEPTION(broadband_irradiance(fog), InputError, [](const InputError& e) {
    return e.setting() == "irradiance.broadband" && std::string(e.what()).find("1100") != std::string::npos;
  });
  Scene rgb = scene_at(30.0);
  rgb.render.path = RenderSpec::Path::RgbFast;
  BOOST_CHECK_EXCEPTION(broadband_irradiance(rgb), InputError,
                        [](const InputError& e) { return e.setting() == "irradiance.broadband"; });
}

BOOST_AUTO_TEST_SUITE_END()
