// The Lee diagram: a row of large drops shows the primary bow just inside Descartes' angle at each
// wavelength, the secondary just outside its own, Alexander's dark band between them and the
// primary's strong perpendicular polarisation; a row's phase function integrates to 1 over the
// sphere; the files hold what was computed; bad settings are refused naming the setting.

#include <boost/test/unit_test.hpp>

#include <cmath>

#include "io/spectral_exr.hpp"
#include "physics/solar_spectrum.hpp"
#include "scratch_folder.hpp"
#include "skyspec/error.hpp"
#include "skyspec/lee_diagram.hpp"
#include "skyspec/refractive_index.hpp"
#include "skyspec/water.hpp"

BOOST_AUTO_TEST_SUITE(test_lee_diagram)

using namespace skyspec;

namespace {
// Descartes' angle of the k-th bow (k internal reflections), degrees of scattering angle.
double descartes_deg(double n, int k) {
  const double i = std::acos(std::sqrt((n * n - 1.0) / (k * (k + 2.0)))), r = std::asin(std::sin(i) / n);
  const double deviation = 180.0 * k + (2.0 * i - 2.0 * (k + 1.0) * r) * 180.0 / M_PI;
  return k % 2 == 1 ? deviation : 360.0 - deviation;
}

double relative_index(double nm) {
  return water_refractive_index(283.15, liquid_water_density_kg_per_m3(283.15), nm) /
         (1.0 + refractivity_standard_air(RefractiveIndexFormula::PeckReeder1972, nm));
}

LeeDiagramSettings one_large_drop() {
  LeeDiagramSettings s;
  s.radius_min_um = s.radius_max_um = 500.0;
  s.height = 1;
  s.width = 400;
  s.angle_min_deg = 125.0;
  s.angle_max_deg = 145.0;
  s.lambda_min_nm = 450.0;
  s.lambda_max_nm = 650.0;
  s.lambda_step_nm = 100.0;
  s.angle_subsamples = 8;
  s.polarisation = true;
  return s;
}
}  // namespace

// Drops of 0.5 mm (x = 4800-7000): the brightest column between 135 and 145 degrees lies within
// 0.5 degree inside Descartes' primary angle (Airy's offset at these sizes is 0.25-0.35 degree),
// the brightest between 125 and 132 degrees within 0.8 degree outside the secondary's; the mean
// radiance between the bows (Alexander's band, 131-136 degrees) is below a third of either bow's
// region's; the primary's light is more than 90 % polarised perpendicular to the scattering plane.
BOOST_AUTO_TEST_CASE(bows_and_dark_band_of_large_drops) {
  const LeeDiagram d = compute_lee_diagram(one_large_drop());
  const int n = static_cast<int>(d.wavelengths_nm.size());
  for (int i = 0; i < n; ++i) {
    const double m = relative_index(d.wavelengths_nm[static_cast<size_t>(i)]);
    const double primary = descartes_deg(m, 1), secondary = descartes_deg(m, 2);
    const auto value = [&](int x) { return d.spectral[static_cast<size_t>(x) * n + i]; };
    const auto brightest = [&](double from, double to) {
      int best = -1;
      for (int x = 0; x < d.width; ++x) {
        const double a = d.angles_deg[static_cast<size_t>(x)];
        if (a >= from && a <= to && (best < 0 || value(x) > value(best))) best = x;
      }
      return best;
    };
    const auto mean = [&](double from, double to) {
      double sum = 0.0;
      int count = 0;
      for (int x = 0; x < d.width; ++x)
        if (d.angles_deg[static_cast<size_t>(x)] >= from && d.angles_deg[static_cast<size_t>(x)] <= to)
          sum += value(x), ++count;
      return sum / count;
    };
    const int p = brightest(135.0, 145.0), s = brightest(125.0, 132.0);
    const double p_angle = d.angles_deg[static_cast<size_t>(p)], s_angle = d.angles_deg[static_cast<size_t>(s)];
    BOOST_TEST_MESSAGE(d.wavelengths_nm[static_cast<size_t>(i)] << " nm: primary " << p_angle << " deg (Descartes "
                                                                << primary << "), secondary " << s_angle << " ("
                                                                << secondary << ")");
    BOOST_TEST_CONTEXT(d.wavelengths_nm[static_cast<size_t>(i)] << " nm") {
      BOOST_TEST(p_angle - primary > 0.0);
      BOOST_TEST(p_angle - primary < 0.5);
      BOOST_TEST(secondary - s_angle > 0.0);
      BOOST_TEST(secondary - s_angle < 0.8);
      const double band = mean(131.0, 136.0);
      BOOST_TEST(band < mean(137.0, 142.0) / 3.0);
      BOOST_TEST(band < mean(126.0, 130.0) / 3.0);
      const float q = d.stokes[(static_cast<size_t>(p) * 3) * n + i];
      BOOST_TEST(q / value(p) > 0.9);
    }
  }
}

// P_11 integrates to 1 over the sphere: a row of 1 um drops over 0-180 degrees (720 columns, each
// the average of 16 angles), sin-weighted, over the sun's irradiance at 550 nm, within 1e-3; the
// same settings give the same values (threads notwithstanding).
BOOST_AUTO_TEST_CASE(rows_integrate_to_one) {
  LeeDiagramSettings s;
  s.radius_min_um = s.radius_max_um = 1.0;
  s.height = 1;
  s.width = 720;
  s.angle_min_deg = 0.0;
  s.angle_max_deg = 180.0;
  s.lambda_min_nm = s.lambda_max_nm = 550.0;
  s.angle_subsamples = 16;
  const LeeDiagram d = compute_lee_diagram(s);
  const double sun = solar_irradiance_on_grid(WavelengthGrid::uniform(550.0, 550.0, 10.0))[0];
  double integral = 0.0;
  const double dtheta = M_PI / s.width;
  for (int x = 0; x < s.width; ++x)
    integral += 2.0 * M_PI * d.spectral[static_cast<size_t>(x)] *
                std::sin(d.angles_deg[static_cast<size_t>(x)] * M_PI / 180.0) * dtheta;
  BOOST_TEST_MESSAGE("integral of P_11 over the sphere: " << integral / sun);
  BOOST_TEST(std::abs(integral / sun - 1.0) < 1e-3);
  BOOST_TEST(compute_lee_diagram(s).spectral == d.spectral);
}

BOOST_AUTO_TEST_CASE(files_hold_the_diagram) {
  test::ScratchFolder dir;
  LeeDiagramSettings s = one_large_drop();
  s.width = 40;
  const LeeDiagram d = compute_lee_diagram(s);
  const LeeDiagramFiles files = write_lee_diagram(d, dir.path, "lee", DisplaySettings{}, true);
  BOOST_TEST(std::filesystem::is_regular_file(files.png));
  const SpectralImage back = read_spectral_exr(files.exr);
  BOOST_TEST(back.width == 40);
  BOOST_TEST(back.wavelengths_nm == d.wavelengths_nm);
  BOOST_TEST(back.spectral == d.spectral);
  BOOST_TEST(back.stokes == d.stokes);
  BOOST_TEST(back.string_attributes.at("skyspec:content").find("Lee diagram") == 0);
}

BOOST_AUTO_TEST_CASE(bad_settings_are_refused) {
  const auto setting_of = [](LeeDiagramSettings s) {
    try {
      check_lee_diagram_settings(s);
    } catch (const InputError& e) {
      return e.setting();
    }
    return std::string("accepted");
  };
  LeeDiagramSettings s;
  BOOST_TEST(setting_of(s) == "accepted");
  s.radius_max_um = 2000.0;  // x = 2.3e4 at 380 nm
  BOOST_TEST(setting_of(s) == lee_setting::kRadiusMax);
  s = {};
  s.angle_max_deg = s.angle_min_deg;
  BOOST_TEST(setting_of(s) == lee_setting::kAngleMax);
  s = {};
  s.lambda_min_nm = 250.0;
  BOOST_TEST(setting_of(s) == lee_setting::kLambdaMin);
  s = {};
  s.water_temperature_C = -20.0;
  BOOST_TEST(setting_of(s) == lee_setting::kTemperature);
  s = {};
  s.width = 0;
  BOOST_TEST(setting_of(s) == lee_setting::kWidth);
  test::ScratchFolder dir;
  BOOST_CHECK_THROW(write_lee_diagram(compute_lee_diagram(one_large_drop()), dir.path, "a/b", DisplaySettings{}, false),
                    InputError);
}

BOOST_AUTO_TEST_SUITE_END()
