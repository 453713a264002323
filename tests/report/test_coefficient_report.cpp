#include <boost/test/unit_test.hpp>

// The coefficient derivation report: its comparisons with published tables (Bodhaine et al. 1999,
// Bucholtz 1995) hold to the stated accuracy, its per-level numbers follow closed forms, and its
// writers produce complete, parseable files.

#include <algorithm>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "check_helpers.hpp"
#include "report/published_references.hpp"
#include "skyspec/coefficient_report.hpp"
#include "skyspec/error.hpp"
#include "skyspec/rayleigh.hpp"
#include "skyspec/scene.hpp"
#include "skyspec/standard_atmosphere.hpp"
#include "skyspec/units.hpp"

BOOST_AUTO_TEST_SUITE(test_coefficient_report)

using namespace skyspec;

namespace {

/// physics.md: a derivation within 0.1 % of the published tables is right.
constexpr double kPublishedTolerancePercent = 0.1;

const ReferenceComparison& comparison(const std::vector<ReferenceComparison>& all, const std::string& id) {
  for (const auto& c : all)
    if (c.id == id) return c;
  BOOST_FAIL("no comparison " << id);
  return all.front();
}

CoefficientReportRequest default_request(std::vector<double> wavelengths_nm) {
  CoefficientReportRequest req;
  req.atmosphere = SceneLoader("default").finish().atmosphere;
  req.wavelengths_nm = std::move(wavelengths_nm);
  return req;
}

std::vector<double> visible_grid() {
  std::vector<double> nm;
  for (double l = 380.0; l <= 780.0; l += 10.0) nm.push_back(l);
  return nm;
}

double relative_error(double value, double reference) { return std::abs(value / reference - 1.0); }

}  // namespace

BOOST_AUTO_TEST_SUITE(published_tables)

// The validation of the issue: sea-level optical depths of Bodhaine Table 3 (350-850 nm) to 0.1 %.
BOOST_AUTO_TEST_CASE(bodhaine_table3_optical_depths) {
  const auto all = published_comparisons();
  const auto& c = comparison(all, "bodhaine1999_table3");
  BOOST_TEST(c.rows.size() == 11u);
  BOOST_TEST(c.rows.front().wavelength_nm == 350.0);
  BOOST_TEST(c.rows.back().wavelength_nm == 850.0);
  for (const auto& r : c.rows) {
    BOOST_TEST_MESSAGE(r.wavelength_nm << " nm: published " << r.published << ", skyspec " << r.skyspec << " ("
                                       << r.difference_percent << " %)");
    BOOST_TEST(std::abs(r.difference_percent) < kPublishedTolerancePercent, r.wavelength_nm << " nm");
  }
  BOOST_TEST_MESSAGE("largest |difference| " << c.max_abs_difference_percent << " %");
}

// Bodhaine's sigma(550 nm) = 4.51e-27 cm^2 and F(air, 550 nm) = 1.0488.
BOOST_AUTO_TEST_CASE(bodhaine_single_values) {
  const auto all = published_comparisons();
  const auto& s = comparison(all, "bodhaine1999_cross_section_550nm");
  BOOST_REQUIRE(s.rows.size() == 1u);
  BOOST_TEST(s.rows[0].published == 4.51e-31, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(std::abs(s.rows[0].difference_percent) < kPublishedTolerancePercent);
  const auto& f = comparison(all, "bodhaine1999_king_factor_550nm");
  BOOST_TEST(std::abs(f.rows[0].skyspec - f.rows[0].published) <= 1e-4);
}

// Bucholtz 1995's King factors (his rho_n table, 4 digits, a staircase in wavelength): within
// 0.11 % over 350-850 nm and 0.05 % over 400-700 nm.
BOOST_AUTO_TEST_CASE(bucholtz_king_factors) {
  const auto all = published_comparisons();
  const auto& c = comparison(all, "bucholtz1995_king_factor");
  BOOST_TEST(c.rows.size() == 15u);
  for (const auto& r : c.rows) {
    BOOST_TEST(std::abs(r.difference_percent) < 0.11, r.wavelength_nm << " nm: " << r.difference_percent << " %");
    if (r.wavelength_nm >= 400.0 && r.wavelength_nm <= 700.0)
      BOOST_TEST(std::abs(r.difference_percent) < 0.05, r.wavelength_nm << " nm: " << r.difference_percent << " %");
  }
}

// Bucholtz 1995's analytic fit to his cross-sections: its two branches disagree by 0.11 % where they
// meet, so agreement is asked to 0.3 % over 250-500 nm (the fit's short-wave branch and its junction)
// and 0.1 % from 550 nm to 1650 nm (docs/validation.md has the figures).
BOOST_AUTO_TEST_CASE(bucholtz_cross_section_fit) {
  const double junction_nm = bucholtz1995_fit_branch_nm();
  BOOST_TEST(junction_nm == 500.0);
  const double jump = relative_error(bucholtz1995_cross_section_fit_m2(junction_nm + 1e-9),
                                     bucholtz1995_cross_section_fit_m2(junction_nm));
  BOOST_TEST(jump > 1e-3);
  BOOST_TEST(jump < 1.5e-3);
  const auto all = published_comparisons();
  const auto& c = comparison(all, "bucholtz1995_cross_section_fit");
  BOOST_TEST(c.rows.size() == 29u);
  BOOST_TEST(c.rows.front().wavelength_nm == 250.0);
  BOOST_TEST(c.rows.back().wavelength_nm == 1650.0);
  bool saw_1500 = false;
  for (const auto& r : c.rows) {
    BOOST_TEST(std::abs(r.difference_percent) < 0.3, r.wavelength_nm << " nm: " << r.difference_percent << " %");
    if (r.wavelength_nm >= 550.0) BOOST_TEST(std::abs(r.difference_percent) < kPublishedTolerancePercent);
    if (r.wavelength_nm == 1500.0) saw_1500 = true;
  }
  BOOST_TEST(saw_1500);
  BOOST_CHECK_THROW(bucholtz1995_cross_section_fit_m2(150.0), InputError);
  BOOST_CHECK_THROW(bucholtz1995_cross_section_fit_m2(1700.0), InputError);
}

// Bodhaine et al.'s own fit to their optical depths (eq. 30): the same calculation, so within
// 0.01 % from 250 to 850 nm and 0.05 % up to 1000 nm, where the fit drifts from the calculation it
// summarises.
BOOST_AUTO_TEST_CASE(bodhaine_fit_from_the_ultraviolet_to_1_um) {
  const auto all = published_comparisons();
  const auto& c = comparison(all, "bodhaine1999_fit");
  BOOST_TEST(c.rows.size() == 16u);
  BOOST_TEST(c.rows[1].wavelength_nm == 300.0);
  BOOST_TEST(c.rows[1].published == 1.21641, boost::test_tools::tolerance(1e-5));  // eq. (30) at 0.3 um
  for (const auto& r : c.rows) {
    BOOST_TEST(std::abs(r.difference_percent) < 0.05, r.wavelength_nm << " nm: " << r.difference_percent << " %");
    if (r.wavelength_nm <= 850.0)
      BOOST_TEST(std::abs(r.difference_percent) < 0.01, r.wavelength_nm << " nm: " << r.difference_percent << " %");
  }
}

// The report's embedded copy of Table 3 is the test data file, figure for figure.
BOOST_AUTO_TEST_CASE(embedded_table_matches_test_data) {
  std::ifstream file(std::string(SKYSPEC_TEST_DATA_DIR) + "/bodhaine1999_table3.csv");
  BOOST_REQUIRE(file.good());
  std::vector<PublishedValue> test_rows;
  std::string line;
  bool header = false;
  while (std::getline(file, line)) {
    if (line.empty() || line[0] == '#') continue;
    if (!header) {
      header = true;
      continue;
    }
    std::replace(line.begin(), line.end(), ',', ' ');
    std::istringstream in(line);
    PublishedValue v{};
    in >> v.wavelength_nm >> v.value;
    test_rows.push_back(v);
  }
  const auto& embedded = bodhaine1999_table3_optical_depth();
  BOOST_REQUIRE(embedded.size() == test_rows.size());
  for (size_t i = 0; i < embedded.size(); ++i) {
    BOOST_TEST(embedded[i].wavelength_nm == test_rows[i].wavelength_nm);
    BOOST_TEST(embedded[i].value == test_rows[i].value);
  }
}

// The seed's constants (5.8 / 13.5 / 33.1 e-6 m^-1) against standard air: physics.md quotes the
// derivation as about 4.85, 11.49, 28.71 e-6 m^-1; the seed's are 15-20 % larger.
BOOST_AUTO_TEST_CASE(seed_constants) {
  const auto all = published_comparisons();
  const auto& c = comparison(all, "seed_constants");
  BOOST_REQUIRE(c.rows.size() == 3u);
  const double physics_md[] = {28.71e-6, 11.49e-6, 4.85e-6};  // 440, 550, 680 nm
  const double seed[] = {33.1e-6, 13.5e-6, 5.8e-6};
  for (size_t i = 0; i < 3; ++i) {
    BOOST_TEST(c.rows[i].published == seed[i], boost::test_tools::tolerance(1e-12));
    BOOST_TEST(relative_error(c.rows[i].skyspec, physics_md[i]) < 1e-3);
    BOOST_TEST(c.rows[i].published / c.rows[i].skyspec > 1.15);
    BOOST_TEST(c.rows[i].published / c.rows[i].skyspec < 1.20);
  }
  BOOST_TEST(c.explanation.find("no single pressure and temperature") != std::string::npos);
}

BOOST_AUTO_TEST_SUITE_END()

BOOST_AUTO_TEST_SUITE(report_numbers)

// 220 K and 250 hPa: N = P / (k T); sigma is that of standard air; beta = sigma N; (n - 1) scales
// with N; the hydrostatic column above 250 hPa holds P / (m_a g) of air.
BOOST_AUTO_TEST_CASE(arbitrary_pressure_and_temperature) {
  auto req = default_request({440.0, 550.0, 680.0});
  req.conditions = AirConditions{25000.0, 220.0};
  const CoefficientReport r = make_coefficient_report(req);
  BOOST_REQUIRE(r.conditions.has_value());
  const auto& c = *r.conditions;
  const double n_per_m3 = 25000.0 / (1.380649e-23 * 220.0);
  BOOST_TEST(c.number_density_per_m3 == n_per_m3, boost::test_tools::tolerance(1e-14));
  BOOST_TEST(c.density_ratio == n_per_m3 / 2.546899e25, boost::test_tools::tolerance(1e-14));
  for (size_t i = 0; i < 3; ++i) {
    const double sigma = r.derivation[i].cross_section_m2;
    BOOST_TEST(sigma == rayleigh_cross_section_m2(r.wavelengths_nm[i], req.atmosphere.rayleigh.derivation));
    BOOST_TEST(c.rayleigh_scattering_per_m[i] == sigma * n_per_m3, boost::test_tools::tolerance(1e-14));
    BOOST_TEST(c.refractivity[i] == r.derivation[i].refractivity * c.density_ratio,
               boost::test_tools::tolerance(1e-14));
    BOOST_TEST(c.rayleigh_optical_depth_above[i] == sigma * c.column_molecules_per_m2,
               boost::test_tools::tolerance(1e-14));
  }
  // 250 hPa lies near 10.36 km in the U.S. Standard Atmosphere 1976; the bisection finds it.
  BOOST_TEST(c.pressure_altitude_m > 10300.0);
  BOOST_TEST(c.pressure_altitude_m < 10450.0);
  BOOST_TEST(us_standard_atmosphere_1976(c.pressure_altitude_m).pressure_Pa == 25000.0,
             boost::test_tools::tolerance(1e-6));
  BOOST_TEST(c.column_gravity_m_per_s2 > 9.75);
  BOOST_TEST(c.column_gravity_m_per_s2 < 9.81);
}

// An exponential atmosphere: beta(z) = beta(0) exp(-z/H) and tau(z) = beta(0) H (exp(-z/H) -
// exp(-top/H)) exactly; N(0) = P / (k T).
BOOST_AUTO_TEST_CASE(exponential_levels_follow_closed_forms) {
  auto req = default_request({400.0, 550.0, 700.0});
  auto& ray = req.atmosphere.rayleigh;
  ray.profile = ProfileKind::Exponential;
  ray.scale_height_m = 8000.0;
  ray.surface_pressure_Pa = 100000.0;
  ray.surface_temperature_K = 280.0;
  req.atmosphere.mie.enabled = false;
  req.atmosphere.ozone.enabled = false;
  req.altitudes_m = {0.0, 1500.0, 12000.0};
  const CoefficientReport r = make_coefficient_report(req);
  const double top_m = req.atmosphere.top_altitude_m, h_m = 8000.0;
  const double n0_per_m3 = 100000.0 / (constants::kBoltzmann_J_per_K * 280.0);
  BOOST_REQUIRE(r.levels.size() == 3u);
  for (const auto& l : r.levels) {
    const double decay = std::exp(-l.altitude_m / h_m);
    BOOST_TEST(l.rayleigh_number_density_per_m3 == n0_per_m3 * decay, boost::test_tools::tolerance(1e-12));
    for (size_t i = 0; i < r.wavelengths_nm.size(); ++i) {
      const double beta0 = r.derivation[i].cross_section_m2 * n0_per_m3;
      BOOST_TEST(l.rayleigh_scattering_per_m[i] == beta0 * decay, boost::test_tools::tolerance(1e-12));
      BOOST_TEST(l.rayleigh_optical_depth[i] == beta0 * h_m * (decay - std::exp(-top_m / h_m)),
                 boost::test_tools::tolerance(1e-8));
      BOOST_TEST(l.mie_optical_depth[i] == 0.0);
      BOOST_TEST(l.total_optical_depth[i] == l.rayleigh_optical_depth[i]);
    }
  }
}

// The U.S. Standard Atmosphere levels carry the standard's own T, P and N = P / kT.
BOOST_AUTO_TEST_CASE(standard_atmosphere_levels) {
  auto req = default_request({550.0});
  req.altitudes_m = {0.0, 5000.0, 11000.0};
  const CoefficientReport r = make_coefficient_report(req);
  for (const auto& l : r.levels) {
    const AtmosphereState s = us_standard_atmosphere_1976(l.altitude_m);
    BOOST_REQUIRE(l.temperature_K.has_value());
    BOOST_TEST(*l.temperature_K == s.temperature_K);
    BOOST_TEST(*l.pressure_Pa == s.pressure_Pa);
    BOOST_TEST(relative_error(l.rayleigh_number_density_per_m3, s.number_density_per_m3) < 1e-5);
  }
  // Sea-level column through the profile vs the hydrostatic column of Bodhaine eq. (9) (420 ppm,
  // 45 deg): the two ways to weigh the atmosphere agree to 0.2 % (the 60 km top, the profile).
  const double hydrostatic = rayleigh_optical_depth_hydrostatic(r.derivation[0].cross_section_m2, 101325.0, 45.0, 0.0,
                                                                req.atmosphere.rayleigh.derivation.co2_ppv);
  BOOST_TEST(relative_error(r.levels[0].rayleigh_optical_depth[0], hydrostatic) < 2e-3);
}

// Aerosols follow the Angstrom law exactly; extinction = ratio x scattering.
BOOST_AUTO_TEST_CASE(angstrom_law) {
  const CoefficientReport r = make_coefficient_report(default_request({400.0, 550.0, 700.0}));
  BOOST_REQUIRE(r.mie_enabled);
  for (size_t i = 0; i < 3; ++i) {
    const double expected = r.mie_scattering_at_reference_per_m *
                            std::pow(r.wavelengths_nm[i] / r.mie_reference_wavelength_nm, -r.mie_angstrom_exponent);
    BOOST_TEST(r.levels[0].mie_scattering_per_m[i] == expected, boost::test_tools::tolerance(1e-12));
    BOOST_TEST(r.levels[0].mie_extinction_per_m[i] == expected * r.mie_extinction_to_scattering,
               boost::test_tools::tolerance(1e-12));
  }
}

// With an ozone layer the report gains its absorption and optical depth: the vertical optical depth
// from the ground is sigma x the column (300 DU = 300 x 2.6867e20 molecules m^-2).
BOOST_AUTO_TEST_CASE(ozone_rows_when_present) {
  auto req = default_request({500.0, 600.0});
  auto& o = req.atmosphere.ozone;
  o.enabled = true;
  o.column_DU = 300.0;
  o.cross_section_wavelengths_nm = {500.0, 600.0};
  o.cross_section_m2 = {3.0e-25, 5.0e-25};
  const CoefficientReport r = make_coefficient_report(req);
  BOOST_REQUIRE(r.ozone_enabled);
  const double column_per_m2 = 300.0 * constants::kDobsonUnit_per_m2;
  BOOST_TEST(r.ozone_cross_section_m2[1] == 5.0e-25, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(r.levels[0].ozone_optical_depth[1] == 5.0e-25 * column_per_m2, boost::test_tools::tolerance(1e-4));
  BOOST_TEST(report_to_markdown(r).find("tau_O3") != std::string::npos);
  BOOST_TEST(report_to_csv(r).find("ozone_optical_depth_from_0m") != std::string::npos);
  // Without ozone: a plain note, no ozone columns.
  auto plain_req = default_request({500.0});
  plain_req.atmosphere.ozone.enabled = false;
  const CoefficientReport plain = make_coefficient_report(plain_req);
  BOOST_TEST(!plain.ozone_enabled);
  BOOST_TEST(report_to_markdown(plain).find("tau_O3") == std::string::npos);
}

// Water and ice in the atmosphere are in the report and its total (fog here): at the ground its
// extinction at 550 nm is ln 20 / visibility (how the medium is defined), its vertical optical
// depth the closed form of an exponential profile, beta H (exp(-z / H) - exp(-top / H)); every
// writer carries its columns.
BOOST_AUTO_TEST_CASE(water_and_ice_rows_when_present) {
  auto req = default_request({450.0, 550.0});
  req.atmosphere.fog.enabled = true;
  req.atmosphere.fog.visibility_m = 2000.0;
  req.atmosphere.fog.scale_height_m = 100.0;
  req.altitudes_m = {0.0, 50.0};
  const CoefficientReport r = make_coefficient_report(req);
  BOOST_REQUIRE(r.media.size() == 1u);
  BOOST_TEST(r.media[0].name == "fog");
  const double h_m = 100.0, top_m = req.atmosphere.top_altitude_m;
  const ReportMediumLevel& ground = r.levels[0].media.at(0);
  BOOST_TEST(ground.extinction_per_m[1] == std::log(20.0) / 2000.0, boost::test_tools::tolerance(1e-9));
  for (const ReportLevel& l : r.levels) {
    BOOST_REQUIRE(l.media.size() == 1u);
    const double decay = std::exp(-l.altitude_m / h_m);
    for (size_t i = 0; i < 2; ++i) {
      BOOST_TEST(l.media[0].extinction_per_m[i] == ground.extinction_per_m[i] * decay,
                 boost::test_tools::tolerance(1e-12));
      BOOST_TEST(l.media[0].scattering_per_m[i] <= l.media[0].extinction_per_m[i]);
      BOOST_TEST(l.media[0].optical_depth[i] == ground.extinction_per_m[i] * h_m * (decay - std::exp(-top_m / h_m)),
                 boost::test_tools::tolerance(1e-8));
      BOOST_TEST(l.total_optical_depth[i] == l.rayleigh_optical_depth[i] + l.mie_optical_depth[i] +
                                                 l.ozone_optical_depth[i] + l.media[0].optical_depth[i],
                 boost::test_tools::tolerance(1e-12));
    }
  }
  BOOST_TEST(report_to_markdown(r).find("tau_fog") != std::string::npos);
  BOOST_TEST(report_to_csv(r).find("fog_optical_depth_from_50m") != std::string::npos);
  const auto j = nlohmann::json::parse(report_to_json(r));
  BOOST_TEST(j["media"][0]["name"] == "fog");
  BOOST_TEST(j["levels"][1]["media"]["fog"]["optical_depth"].size() == 2u);
  // Without them, no such columns.
  BOOST_TEST(make_coefficient_report(default_request({550.0})).media.empty());
  // Rain in a shower: the report says where it stands (its levels are those inside it).
  auto shower = default_request({550.0, 650.0});
  shower.atmosphere.rain.enabled = true;
  shower.atmosphere.rain.extent = RainSpec::Extent::Shower;
  shower.atmosphere.rain.shower_distance_m = 6000.0;
  shower.atmosphere.rain.shower_azimuth_deg = 90.0;
  shower.atmosphere.rain.shower_radius_m = 2500.0;
  const CoefficientReport rs = make_coefficient_report(shower);
  BOOST_REQUIRE(rs.media.size() == 1u);
  BOOST_TEST(rs.media[0].region_description.find("2500 m in radius") != std::string::npos);
  BOOST_TEST(rs.media[0].region_description.find("6000 m from the reference point at azimuth 90 degrees") !=
             std::string::npos);
  BOOST_TEST(nlohmann::json::parse(report_to_json(rs))["media"][0]["region"].is_string());
  BOOST_TEST(r.media[0].region_description.empty());
}

// The report works across the refractive index's range (230-1690 nm): ozone where its table has
// data (230-1060 nm), n/a beyond, and tau total then of air and aerosols; beyond the range, a clear
// error naming it and why.
BOOST_AUTO_TEST_CASE(ultraviolet_to_near_infrared) {
  const CoefficientReport r = make_coefficient_report(default_request({300.0, 350.0, 1500.0}));
  BOOST_REQUIRE(r.ozone_enabled);
  BOOST_TEST(r.ozone_cross_section_m2[0] > 1e-23);  // the Huggins band at 300 nm
  BOOST_TEST(std::isnan(r.ozone_cross_section_m2[2]));
  const ReportLevel& l = r.levels[0];
  BOOST_TEST(std::isnan(l.ozone_optical_depth[2]));
  BOOST_TEST(l.total_optical_depth[2] == l.rayleigh_optical_depth[2] + l.mie_optical_depth[2],
             boost::test_tools::tolerance(1e-12));
  BOOST_TEST(
      l.total_optical_depth[0] == l.rayleigh_optical_depth[0] + l.mie_optical_depth[0] + l.ozone_optical_depth[0],
      boost::test_tools::tolerance(1e-12));
  // Rayleigh: (1500/300)^4 = 625, and more since n - 1 and F rise towards the ultraviolet.
  BOOST_TEST(r.derivation[0].cross_section_m2 / r.derivation[2].cross_section_m2 > 700.0);
  const std::string md = report_to_markdown(r);
  BOOST_TEST(md.find("n/a") != std::string::npos);
  BOOST_TEST(md.find("230-1060 nm") != std::string::npos);
  BOOST_TEST(report_to_json(r).find("null") != std::string::npos);
  BOOST_TEST(report_to_csv(r).find("nan") == std::string::npos);
  for (double nm : {225.0, 1700.0}) {
    const std::string message = test::input_error_message([&] { make_coefficient_report(default_request({nm})); });
    BOOST_TEST(message.find("230 to 1690 nm") != std::string::npos, message);
  }
}

// The seed preset types its coefficients in: the report shows them as the renderer uses them.
BOOST_AUTO_TEST_CASE(fixed_coefficients) {
  CoefficientReportRequest req;
  const Scene seed = SceneLoader("seed").finish();
  req.atmosphere = seed.atmosphere;
  req.wavelengths_nm = make_wavelength_grid(seed).nanometres();
  const CoefficientReport r = make_coefficient_report(req);
  BOOST_TEST(!r.rayleigh_derived);
  BOOST_REQUIRE(r.wavelengths_nm.size() == 3u);
  BOOST_TEST(r.levels[0].rayleigh_scattering_per_m[0] == 33.1e-6, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(r.levels[0].rayleigh_scattering_per_m[2] == 5.8e-6, boost::test_tools::tolerance(1e-12));
}

BOOST_AUTO_TEST_CASE(bad_requests_name_the_setting) {
  auto req = default_request({550.0});
  req.altitudes_m = {70000.0};
  try {
    make_coefficient_report(req);
    BOOST_FAIL("an altitude above the top was accepted");
  } catch (const InputError& e) {
    BOOST_TEST(e.setting() == "altitudes_m");
  }
  req.altitudes_m = {0.0};
  req.conditions = AirConditions{-5.0, 220.0};
  try {
    make_coefficient_report(req);
    BOOST_FAIL("a negative pressure was accepted");
  } catch (const InputError& e) {
    BOOST_TEST(e.setting() == "conditions.pressure_Pa");
  }
  BOOST_CHECK_THROW(parse_report_format("xml"), InputError);
}

BOOST_AUTO_TEST_SUITE_END()

BOOST_AUTO_TEST_SUITE(writers)

BOOST_AUTO_TEST_CASE(every_format_is_complete) {
  auto req = default_request(visible_grid());
  req.altitudes_m = {0.0, 2000.0};
  req.conditions = AirConditions{25000.0, 220.0};
  const CoefficientReport r = make_coefficient_report(req);
  const size_t n = r.wavelengths_nm.size();

  const std::string md = report_to_markdown(r);
  for (const char* must : {"## Formulas", "Bodhaine et al. 1999 eq. (2)", "Bates 1984", "U.S. Standard Atmosphere 1976",
                           "Checked against published values", "Bucholtz", "seed", "Air at 250 hPa and 220 K"})
    BOOST_TEST(md.find(must) != std::string::npos, must);

  // CSV: comment lines, a header, one row per wavelength, every row as wide as the header.
  std::istringstream csv(report_to_csv(r));
  std::string line;
  size_t header_fields = 0, rows = 0;
  while (std::getline(csv, line)) {
    if (line.empty() || line[0] == '#') continue;
    const size_t fields = static_cast<size_t>(std::count(line.begin(), line.end(), ',')) + 1;
    if (header_fields == 0) {
      header_fields = fields;
      BOOST_TEST(line.rfind("wavelength_nm,", 0) == 0u);
      continue;
    }
    BOOST_TEST(fields == header_fields);
    ++rows;
  }
  BOOST_TEST(rows == n);

  // JSON: parses, arrays as long as the grid, numbers identical to the report's.
  const auto j = nlohmann::json::parse(report_to_json(r));
  BOOST_TEST(j["wavelength_nm"].size() == n);
  BOOST_TEST(j["rayleigh"]["cross_section_m2"].size() == n);
  BOOST_TEST(j["levels"].size() == 2u);
  BOOST_TEST(j["levels"][1]["rayleigh_optical_depth"][5].get<double>() == r.levels[1].rayleigh_optical_depth[5]);
  BOOST_TEST(j["conditions"]["number_density_per_m3"].get<double>() == r.conditions->number_density_per_m3);
  BOOST_TEST(j["references"].size() == r.references.size());
  const std::string text = report_to_json(r);
  BOOST_TEST(text.find("nan") == std::string::npos);
  BOOST_TEST(text.find("inf") == std::string::npos);

  // HTML: one page, three labelled SVG plots, the tables.
  const std::string html = report_to_html(r);
  size_t svgs = 0;
  for (size_t pos = html.find("<svg"); pos != std::string::npos; pos = html.find("<svg", pos + 1)) ++svgs;
  BOOST_TEST(svgs == 3u);
  for (const char* must : {"</html>", "wavelength (nm)", "beta (m^-1)", "optical depth", "King", "<table>"})
    BOOST_TEST(html.find(must) != std::string::npos, must);
}

BOOST_AUTO_TEST_SUITE_END()

BOOST_AUTO_TEST_SUITE_END()  // test_coefficient_report
