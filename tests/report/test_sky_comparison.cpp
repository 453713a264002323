#include <boost/test/unit_test.hpp>

#include <nlohmann/json.hpp>

#include <Eigen/LU>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "colour/chromatic_adaptation.hpp"
#include "report/comparison_report.hpp"
#include "scratch_folder.hpp"
#include "skyspec/colour.hpp"
#include "skyspec/error.hpp"
#include "skyspec/sky_comparison.hpp"

BOOST_AUTO_TEST_SUITE(test_sky_comparison)

using namespace skyspec;
using skyspec::test::ScratchFolder;
namespace fs = std::filesystem;

namespace {

Scene seed_scene(double sun_elevation_deg, int size = 32) {
  SceneLoader loader("seed");
  loader.apply_override("camera.width", std::to_string(size), "test");
  loader.apply_override("camera.height", std::to_string(size), "test");
  loader.apply_override("sun.elevation_deg", std::to_string(sun_elevation_deg), "test");
  return loader.finish();
}

/// The seed preset (RGB-fast) against its spectral twin at one sun elevation.
SkyComparison seed_against_twin(double sun_elevation_deg) {
  const Scene fast = seed_scene(sun_elevation_deg);
  const Scene spectral = spectral_twin(fast);
  return compare_skies(render_sky_image(spectral), render_sky_image(fast), pixel_geometry(fast));
}

double region_mean(const SkyComparison& c, SkyRegion r) { return c.regions[static_cast<size_t>(r)].delta_e.mean; }

}  // namespace

BOOST_AUTO_TEST_SUITE(rules)

// A render compared with itself: every statistic is exactly zero.
BOOST_AUTO_TEST_CASE(render_against_itself_is_zero) {
  const Scene s = seed_scene(10.0, 24);
  const SkyImage image = render_sky_image(s);
  const SkyComparison c = compare_skies(image, image, pixel_geometry(s));
  BOOST_TEST(c.all.delta_e.pixels > 0u);
  BOOST_TEST(c.all.delta_e.max == 0.0);
  BOOST_TEST(c.all.delta_e.share_above_1 == 0.0);
  BOOST_TEST(c.all.luminance.max_abs == 0.0);
  for (const auto& r : c.regions) BOOST_TEST(r.delta_e.max == 0.0);
}

// Rule 1: images are taken relative to their own sun, so scaling an image together with its sun
// changes nothing, while scaling the image alone is a luminance error of exactly that factor.
BOOST_AUTO_TEST_CASE(sun_relative_scale) {
  const Scene s = seed_scene(20.0, 24);
  const SkyImage image = render_sky_image(s);
  SkyImage brighter = image;
  for (float& v : brighter.rgb) v *= 4.0f;
  brighter.sun_rgb *= 4.0;
  const auto geometry = pixel_geometry(s);
  BOOST_TEST(compare_skies(image, brighter, geometry).all.delta_e.max < 1e-4);
  brighter.sun_rgb = image.sun_rgb;
  const SkyComparison c = compare_skies(image, brighter, geometry);
  BOOST_TEST(std::abs(c.all.luminance.mean - 3.0) < 1e-5);
  BOOST_TEST(c.all.delta_e.mean > 5.0);
}

// Rule 1's adaptation: a sun of another colour, with the whole sky tinted the same way (a von
// Kries scaling of the Bradford cone responses, which is what the adaptation undoes), is the same
// sky.
BOOST_AUTO_TEST_CASE(sun_colour_is_the_white) {
  const Scene s = seed_scene(20.0, 16);
  const SkyImage image = render_sky_image(s);
  const Eigen::Matrix3d bradford = bradford_matrix();
  const Eigen::Matrix3d tint = xyz_to_linear_rec709() * bradford.inverse() *
                               Eigen::Vector3d(1.2, 1.0, 0.7).asDiagonal() * bradford * linear_rec709_to_xyz();
  SkyImage tinted = image;
  for (size_t i = 0; i < tinted.rgb.size(); i += 3) {
    const Eigen::Vector3d v = tint * Eigen::Vector3d(image.rgb[i], image.rgb[i + 1], image.rgb[i + 2]);
    for (int c = 0; c < 3; ++c) tinted.rgb[i + size_t(c)] = static_cast<float>(v[c]);
  }
  tinted.sun_rgb = tint * image.sun_rgb;
  BOOST_TEST(compare_skies(image, tinted, pixel_geometry(s)).all.delta_e.max < 1e-3);
}

BOOST_AUTO_TEST_CASE(size_mismatch_is_an_input_error) {
  const Scene s = seed_scene(20.0, 8);
  const SkyImage a = render_sky_image(s);
  const SkyImage b = render_sky_image(seed_scene(20.0, 9));
  BOOST_CHECK_THROW(compare_skies(a, b, pixel_geometry(s)), InputError);
}

BOOST_AUTO_TEST_CASE(percentiles_interpolate_order_statistics) {
  std::vector<double> v;
  for (int i = 100; i >= 0; --i) v.push_back(i);
  const DeltaEStats s = delta_e_stats(v);
  BOOST_TEST(s.pixels == 101u);
  BOOST_TEST(s.median == 50.0);
  BOOST_TEST(s.p95 == 95.0);
  BOOST_TEST(s.max == 100.0);
  BOOST_TEST(s.mean == 50.0);
  BOOST_TEST(std::abs(s.share_above_5 - 95.0 / 101.0) < 1e-15);
  BOOST_TEST(delta_e_stats({}).pixels == 0u);
}

BOOST_AUTO_TEST_SUITE_END()

BOOST_AUTO_TEST_SUITE(geometry)

// The fisheye's centre looks at the zenith, its corners at nothing; the sun's direction is in
// the near-sun region; an equirectangular image compares only its upper half.
BOOST_AUTO_TEST_CASE(regions_of_the_fisheye_and_the_panorama) {
  const Scene s = seed_scene(45.0, 41);
  const PixelGeometry g = pixel_geometry(s);
  const auto at = [&](int x, int y) { return g.region[static_cast<size_t>(y) * 41 + static_cast<size_t>(x)]; };
  BOOST_TEST(int(at(20, 20)) == int(SkyRegion::Zenith));
  BOOST_TEST(std::abs(g.elevation_deg[20 * 41 + 20] - 90.0f) < 3.0f);
  BOOST_TEST(int(at(0, 0)) == int(kNotCompared));
  BOOST_TEST(int(at(20, 1)) == int(SkyRegion::Horizon));  // the top edge is the northern horizon
  size_t near_sun = 0;
  for (size_t i = 0; i < g.region.size(); ++i)
    if (g.region[i] == static_cast<uint8_t>(SkyRegion::NearSun)) {
      ++near_sun;
      BOOST_TEST(g.sun_angle_deg[i] < 10.0f);
    }
  BOOST_TEST(near_sun > 0u);

  SceneLoader loader("seed");
  loader.apply_override("camera.type", "\"equirectangular\"", "test");
  loader.apply_override("camera.width", "16", "test");
  loader.apply_override("camera.height", "8", "test");
  const PixelGeometry pano = pixel_geometry(loader.finish());
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 16; ++x) BOOST_TEST((pano.region[size_t(y * 16 + x)] == kNotCompared) == (y >= 4));
}

BOOST_AUTO_TEST_SUITE_END()

BOOST_AUTO_TEST_SUITE(twins)

// The seed's three typed-in Rayleigh coefficients follow one lambda^-4 law to 0.3 %; the spectral
// twin extends that law over 380-780 nm and keeps everything else.
BOOST_AUTO_TEST_CASE(spectral_twin_of_the_seed) {
  const Scene fast = seed_scene(30.0);
  std::string note;
  const Scene spectral = spectral_twin(fast, &note);
  BOOST_TEST((spectral.render.path == RenderSpec::Path::Spectral));
  const auto& ray = spectral.atmosphere.rayleigh;
  BOOST_TEST(ray.fixed_wavelengths_nm.size() == 41u);
  for (size_t i = 0; i < ray.fixed_wavelengths_nm.size(); ++i)
    for (const auto& [nm, beta] : {std::pair{440.0, 33.1e-6}, std::pair{550.0, 13.5e-6}, std::pair{680.0, 5.8e-6}})
      if (ray.fixed_wavelengths_nm[i] == nm) BOOST_TEST(std::abs(ray.fixed_beta_per_m[i] / beta - 1.0) < 3e-3);
  BOOST_TEST(note.find("lambda^-4") != std::string::npos);
  BOOST_TEST(spectral.sun.elevation_deg == fast.sun.elevation_deg);
  BOOST_TEST(spectral.atmosphere.mie.scattering_per_m == fast.atmosphere.mie.scattering_per_m);
  const Scene back = rgb_fast_twin(spectral);
  BOOST_TEST(back.atmosphere.rayleigh.fixed_wavelengths_nm.size() == 3u);
}

BOOST_AUTO_TEST_SUITE_END()

BOOST_AUTO_TEST_SUITE(physics)

// Where physics says the three-wavelength sky must fail: with the sun low, sunlight crosses up to
// ~40 air masses and its spectrum within each "channel" is far from flat, so three samples
// misrepresent it; with the sun high the sky spectrum is smooth and three samples do better. The
// seed preset against its spectral twin (same atmosphere): visible (> 1) mean Delta E at 2 degrees,
// clearly more than at 60 degrees, worst near the sun and along the horizon.
BOOST_AUTO_TEST_CASE(rgb_fast_fails_with_the_sun_low) {
  const SkyComparison low = seed_against_twin(2.0);
  const SkyComparison high = seed_against_twin(60.0);
  BOOST_TEST_MESSAGE("seed vs spectral twin, 32 x 32: mean Delta E 2000 at 2 deg "
                     << low.all.delta_e.mean << " (p95 " << low.all.delta_e.p95 << "), at 60 deg "
                     << high.all.delta_e.mean << " (p95 " << high.all.delta_e.p95 << ")");
  BOOST_TEST(low.all.delta_e.mean > 1.0);
  BOOST_TEST(low.all.delta_e.mean > 1.5 * high.all.delta_e.mean);
  BOOST_TEST(low.all.delta_e.p95 > high.all.delta_e.p95);
  BOOST_TEST(region_mean(low, SkyRegion::NearSun) > region_mean(low, SkyRegion::Zenith));
  BOOST_TEST(region_mean(low, SkyRegion::Horizon) > region_mean(low, SkyRegion::Zenith));
  BOOST_TEST(high.all.delta_e.mean > 0.0);  // never exactly the same
}

BOOST_AUTO_TEST_SUITE_END()

BOOST_AUTO_TEST_SUITE(reports)

BOOST_AUTO_TEST_CASE(markdown_json_and_pictures) {
  ScratchFolder dir("compare");
  ComparisonRun run;
  run.command = "skyspec compare --preset seed";
  run.scene_summary = "preset seed";
  run.reference_label = "spectral";
  run.test_label = "rgb-fast";
  run.comparison = seed_against_twin(5.0);
  run.sweep.push_back({5.0, run.comparison.all, run.comparison.regions});
  run.sweep.push_back({30.0, run.comparison.all, run.comparison.regions});
  run.delta_e_map_file = "map.png";
  const std::string md = comparison_markdown(run);
  BOOST_TEST(md.find("| **all** |") != std::string::npos);
  BOOST_TEST(md.find("| near the sun |") != std::string::npos);
  BOOST_TEST(md.find("## Sweep over sun elevation") != std::string::npos);
  BOOST_TEST(md.find("Common white and luminance scale: the extraterrestrial sun") != std::string::npos);
  const auto j = nlohmann::json::parse(comparison_json(run));
  BOOST_TEST(j["result"]["all"]["delta_e_2000"]["mean"].get<double>() == run.comparison.all.delta_e.mean);
  BOOST_TEST(j["result"]["regions"].size() == 4u);
  BOOST_TEST(j["sweep"].size() == 2u);
  BOOST_TEST(sweep_plot_svg(run.sweep).find("<svg") != std::string::npos);
  write_delta_e_map(dir.path / "map.png", run.comparison, 10.0);
  BOOST_TEST(fs::file_size(dir.path / "map.png") > 100u);
  BOOST_CHECK_THROW(write_delta_e_map(dir.path / "bad.png", run.comparison, 0.0), InputError);
  BOOST_TEST(!fs::exists(dir.path / "bad.png"));
}

BOOST_AUTO_TEST_SUITE_END()

BOOST_AUTO_TEST_SUITE_END()  // test_sky_comparison
