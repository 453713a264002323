// The viewer's requests without HTTP (src/viewer/view_requests.hpp): a query's names are scene keys
// or the viewer's words, checked with the name and the allowed values in the error; the keys the
// viewer owns are refused; a frame is the PNG `skyspec render` writes; a spectrum is the renderer's
// radiance along the pixel's ray; an export never replaces a file and renders what its TOML says.
#include <png.h>

#include <boost/test/unit_test.hpp>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "render/table_family.hpp"
#include "scratch_folder.hpp"
#include "skyspec/error.hpp"
#include "skyspec/render.hpp"
#include "viewer/view_requests.hpp"

BOOST_AUTO_TEST_SUITE(test_view_requests)

using namespace skyspec;
using viewer::Query;

namespace {
// A small, quick scene: single scattering, 24 x 12 panorama.
viewer::ViewerBase small_base() {
  SceneLoader l("default");
  l.apply_toml("[camera]\ntype = \"equirectangular\"\nwidth = 24\nheight = 12\n[render]\nscattering_orders = 1\n",
               "test");
  viewer::ViewerBase base;
  base.scene_toml = scene_to_toml(l.finish());
  base.threads = 2;
  return base;
}

// A PNG's pixels as 8-bit RGB, by libpng's simplified API (a decoder that is not ours).
std::vector<unsigned char> png_pixels(const std::string& bytes) {
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  BOOST_REQUIRE(png_image_begin_read_from_memory(&image, bytes.data(), bytes.size()));
  image.format = PNG_FORMAT_RGB;
  std::vector<unsigned char> pixels(PNG_IMAGE_SIZE(image));
  BOOST_REQUIRE(png_image_finish_read(&image, nullptr, pixels.data(), 0, nullptr));
  return pixels;
}

std::string setting_of(const viewer::ViewerBase& base, const Query& q) {
  try {
    viewer::parse_view_request(base, q);
  } catch (const InputError& e) {
    return e.setting() + " | " + e.what();
  }
  return "";
}
}  // namespace

BOOST_AUTO_TEST_CASE(queries_set_scene_keys_and_bad_ones_are_named) {
  const auto base = small_base();
  const viewer::ViewRequest r = viewer::parse_view_request(base, {{"sun.elevation_deg", "12.5"},
                                                                  {"camera.type", "\"fisheye\""},
                                                                  {"camera.width", "16"},
                                                                  {"camera.height", "16"},
                                                                  {"view", "Raw"}});
  BOOST_TEST(r.scene.sun.elevation_deg == 12.5);
  BOOST_TEST(r.scene.camera.width == 16);
  BOOST_TEST(r.display.view == "Raw");
  BOOST_TEST(r.scene.render.threads == 2);  // the command line's, never the page's
  BOOST_TEST((r.mode == viewer::ViewRequest::Mode::Colour));

  std::string e = setting_of(base, {{"sun.elevation_deg", "abc"}});
  BOOST_TEST(e.rfind("sun.elevation_deg |", 0) == 0, e);
  BOOST_TEST(e.find("a number in degrees") != std::string::npos, e);
  e = setting_of(base, {{"sun.elevation_deg", "91"}});
  BOOST_TEST(e.rfind("sun.elevation_deg |", 0) == 0, e);
  e = setting_of(base, {{"colour", "1"}});
  BOOST_TEST(e.rfind("colour |", 0) == 0, e);
  BOOST_TEST(e.find("a scene key") != std::string::npos, e);
  e = setting_of(base, {{"mode", "infrared"}});
  BOOST_TEST(e.find("colour or polarisation") != std::string::npos, e);
  e = setting_of(base, {{"view", "Nope"}});
  BOOST_TEST(e.rfind("display.view |", 0) == 0, e);  // the server respells it "view"
  e = setting_of(base, {{"preset", "venus"}});
  BOOST_TEST(e.rfind("preset |", 0) == 0, e);
  for (const std::string& owned : viewer::kViewerOwnedKeys) {
    e = setting_of(base, {{owned, "\"x\""}});
    BOOST_TEST(e.rfind(owned + " |", 0) == 0, e);
  }
}

BOOST_AUTO_TEST_CASE(a_preset_replaces_the_viewers_scene_and_polarisation_mode_polarises) {
  const auto base = small_base();
  const auto r = viewer::parse_view_request(base, {{"preset", "hazy"}, {"mode", "polarisation"}});
  SceneLoader hazy("hazy");
  hazy.set("output.polarisation", true);
  Scene expected = hazy.finish();
  expected.render.threads = 2;
  BOOST_TEST(scene_to_toml(r.scene) == scene_to_toml(expected));
  BOOST_TEST((r.mode == viewer::ViewRequest::Mode::Polarisation));
}

BOOST_AUTO_TEST_CASE(frames_are_the_display_png_and_too_large_ones_are_refused) {
  const auto base = small_base();
  const auto request = viewer::parse_view_request(base, {{"sun.elevation_deg", "20"}});
  const viewer::Frame frame = viewer::render_frame(request);
  BOOST_TEST(frame.width == 24);
  BOOST_TEST(frame.height == 12);
  // The frame is compressed for speed: other bytes than the exported PNG, the same pixels.
  const SpectralImageBuffer image = render_to_memory(request.scene);
  BOOST_TEST(frame.png == display_png_bytes(image, {}, PngCompression::Fastest));
  BOOST_TEST(frame.png != display_png_bytes(image));
  BOOST_TEST(png_pixels(frame.png) == png_pixels(display_png_bytes(image)));
  BOOST_TEST(frame.png.substr(1, 3) == "PNG");

  const auto polarised = viewer::parse_view_request(base, {{"mode", "polarisation"}});
  const viewer::Frame p = viewer::render_frame(polarised);
  BOOST_TEST(p.png.substr(1, 3) == "PNG");
  BOOST_TEST(p.png != frame.png);

  BOOST_TEST(frame.preview == "");
  // A preview: the coarse sky-view table (this scene marches no table rows beyond it: single
  // scattering); without the tables: single scattering.
  const auto asked = viewer::parse_view_request(base, {{"sun.elevation_deg", "20"}, {"preview", "1"}});
  BOOST_TEST(asked.preview);
  const viewer::Frame preview = viewer::render_frame(asked);
  BOOST_TEST(preview.preview == "coarse sky-view table");
  Scene coarse = asked.scene;  // what the preview leaves out, set by hand
  coarse.render.sky_view_zenith_samples = viewer::kPreviewZenithSamples;
  coarse.render.sky_view_azimuth_samples = viewer::kPreviewAzimuthSamples;
  coarse.render.view_segments = viewer::kPreviewViewSegments;
  BOOST_TEST(preview.png == display_png_bytes(render_to_memory(coarse), {}, PngCompression::Fastest));
  BOOST_TEST(preview.png != viewer::render_frame(viewer::parse_view_request(base, {{"sun.elevation_deg", "20"}})).png);
  BOOST_TEST(viewer::render_frame(request, viewer::TablesAtHand::none).preview.rfind("single scattering", 0) == 0);
  BOOST_TEST(viewer::scattering_tables_ready(request.scene));  // single scattering needs none
  BOOST_CHECK_EXCEPTION(viewer::parse_view_request(base, {{"preview", "yes"}}), InputError,
                        [](const InputError& e) { return e.setting() == "preview"; });

  const auto huge = viewer::parse_view_request(base, {{"camera.width", "4096"}, {"camera.height", "2048"}});
  BOOST_CHECK_EXCEPTION(viewer::render_frame(huge), InputError,
                        [](const InputError& e) { return e.setting() == "camera.width"; });
}

BOOST_AUTO_TEST_CASE(a_spectrum_is_the_radiance_along_the_pixels_ray) {
  const auto base = small_base();
  const auto request = viewer::parse_view_request(base, {{"sun.elevation_deg", "20"}});
  const auto s = viewer::spectrum_at(request, {{"x", "6"}, {"y", "3"}});
  const auto& wl = s.at("wavelengths_nm");
  BOOST_TEST(wl.size() == 41u);
  // Single scattering alone (the scene's single order): both the same.
  for (size_t i = 0; i < wl.size(); ++i) {
    const double all = s.at("radiance")[i], first = s.at("single_scattering")[i];
    BOOST_TEST(std::isfinite(all));
    BOOST_TEST(all > 0.0);
    BOOST_TEST(first == all);
  }
  // Pixel (6, 3) of a 24 x 12 skyspec panorama: azimuth (6.5 / 24) 360, elevation 90 - (3.5 / 12) 180.
  BOOST_TEST(double(s.at("azimuth_deg")) == 97.5, boost::test_tools::tolerance(1e-9));
  BOOST_TEST(double(s.at("elevation_deg")) == 37.5, boost::test_tools::tolerance(1e-9));
  const SkyRenderer r(request.scene);
  Vec3 dir;
  BOOST_TEST(make_camera(request.scene)->direction(6.5, 3.5, dir));
  const Spectrum direct = r.radiance(dir);
  BOOST_TEST(double(s.at("radiance")[20]) == direct[20], boost::test_tools::tolerance(1e-5));

  for (const Query& q : {Query{{"x", "24"}, {"y", "0"}}, Query{{"x", "-1"}, {"y", "0"}},
                         Query{{"x", "1e3"}, {"y", "0"}}, Query{{"y", "0"}}})
    BOOST_CHECK_EXCEPTION(viewer::spectrum_at(request, q), InputError,
                          [](const InputError& e) { return e.setting() == "x"; });
  BOOST_CHECK_EXCEPTION(viewer::spectrum_at(request, {{"x", "0"}, {"y", "12"}}), InputError,
                        [](const InputError& e) { return e.setting() == "y"; });
}

BOOST_AUTO_TEST_CASE(the_background_build_makes_the_tables_of_the_scene_asked_for_polarised_or_not) {
  // Small tables kept in memory only (render.cache_tables = false), of an aerosol load no other test
  // uses: not at hand before the build, at hand after it, for the polarised scene (vector tables)
  // and then for the same scene without polarisation (its own, scalar, tables).
  SceneLoader l("default");
  l.apply_toml(
      "[camera]\nwidth = 8\nheight = 8\n[render]\nscattering_orders = 2\nms_altitude_samples = 8\n"
      "ms_sun_samples = 24\nms_angular_degree = 4\ncache_tables = false\n[atmosphere.mie]\n"
      "scattering_per_m = 1.7341e-05\n[output]\npolarisation = true\n",
      "test");
  Scene polarised = l.finish();
  Scene scalar = polarised;
  scalar.output.polarisation = false;
  BOOST_TEST(!viewer::scattering_tables_ready(polarised));
  BOOST_TEST(!viewer::scattering_tables_ready(scalar));
  BOOST_TEST((viewer::tables_at_hand(polarised) == viewer::TablesAtHand::none));
  // Tables no larger than the preview's are their own preview: one build.
  BOOST_TEST(scene_to_toml(viewer::with_preview_tables(polarised)) == scene_to_toml(polarised));
  viewer::build_scattering_tables(polarised);
  BOOST_TEST(viewer::scattering_tables_ready(polarised));
  BOOST_TEST((viewer::tables_at_hand(polarised) == viewer::TablesAtHand::exact));
  BOOST_TEST(!viewer::scattering_tables_ready(scalar));
  viewer::build_scattering_tables(scalar);
  BOOST_TEST(viewer::scattering_tables_ready(scalar));
}

BOOST_AUTO_TEST_CASE(the_preview_tables_come_first_and_frames_show_them_until_the_scenes_are_built) {
  // The default scene's tables are larger than the preview's in every dimension.
  const Scene preview_of_default = viewer::with_preview_tables(SceneLoader("default").finish());
  BOOST_TEST(preview_of_default.render.ms_altitude_samples == viewer::kPreviewTableAltitudes);
  BOOST_TEST(preview_of_default.render.ms_sun_samples == viewer::kPreviewTableSuns);
  BOOST_TEST(preview_of_default.render.ms_angular_degree == viewer::kPreviewTableDegree);
  BOOST_TEST(preview_of_default.render.scattering_orders == viewer::kPreviewTableOrders);
  // Small tables (quick under the sanitizers too) one altitude larger than the preview's, of an
  // aerosol load no other test uses, in memory only.
  SceneLoader l("default");
  l.apply_toml(
      "[camera]\ntype = \"equirectangular\"\nwidth = 16\nheight = 8\n[render]\nscattering_orders = 2\n"
      "ms_altitude_samples = " +
          std::to_string(viewer::kPreviewTableAltitudes + 1) +
          "\nms_sun_samples = 24\nms_angular_degree = 2\ncache_tables = false\n"
          "[atmosphere.mie]\nscattering_per_m = 1.8341e-05\n",
      "test");
  const Scene scene = l.finish();
  const Scene preview = viewer::with_preview_tables(scene);
  BOOST_TEST(preview.render.ms_altitude_samples == viewer::kPreviewTableAltitudes);
  BOOST_TEST((viewer::tables_at_hand(scene) == viewer::TablesAtHand::none));
  // The preview's tables alone (as the server has them while the scene's are built): frames are
  // the scene rendered with them and the coarse sky-view table, and say so.
  {
    Scene only_preview = preview;
    only_preview.camera.width = only_preview.camera.height = 1;
    const SkyRenderer build(only_preview);
  }
  BOOST_TEST((viewer::tables_at_hand(scene) == viewer::TablesAtHand::preview));
  viewer::ViewRequest request;
  request.scene = scene;
  const viewer::Frame frame = viewer::render_frame(request, viewer::tables_at_hand(scene));
  BOOST_TEST(frame.preview.rfind("small scattering tables", 0) == 0);
  Scene expected = preview;
  expected.render.sky_view_zenith_samples = viewer::kPreviewZenithSamples;
  expected.render.sky_view_azimuth_samples = viewer::kPreviewAzimuthSamples;
  expected.render.view_segments = viewer::kPreviewViewSegments;
  BOOST_TEST(frame.png == display_png_bytes(render_to_memory(expected), {}, PngCompression::Fastest));
  // A spectrum then: all orders from the preview's tables, marched along the pixel's ray, and says so.
  const viewer::Query pixel = {{"x", "3"}, {"y", "2"}};
  const auto s = viewer::spectrum_at(request, pixel, viewer::TablesAtHand::preview);
  BOOST_TEST(s.at("preview").get<std::string>().rfind("small scattering tables", 0) == 0);
  BOOST_TEST(int(s.at("orders")) == preview.render.scattering_orders);
  Scene marched = preview;
  marched.render.sky_view_table = false;
  Vec3 dir;
  BOOST_TEST(make_camera(scene)->direction(3.5, 2.5, dir));
  BOOST_TEST(double(s.at("radiance")[20]) == SkyRenderer(marched).radiance(dir)[20],
             boost::test_tools::tolerance(1e-6));
  BOOST_CHECK_THROW(viewer::spectrum_at(request, pixel, viewer::TablesAtHand::none), Error);
  // The background build then makes the scene's own; frames and spectra are exact.
  viewer::build_scattering_tables(scene);
  BOOST_TEST((viewer::tables_at_hand(scene) == viewer::TablesAtHand::exact));
  BOOST_TEST(viewer::render_frame(request, viewer::tables_at_hand(scene)).preview == "");
  BOOST_TEST(viewer::spectrum_at(request, pixel).at("preview").get<std::string>() == "");
}

// Interpolated tables (render.ms_tables) are blended in the background like a build: not at hand
// before it although the grid's tables are, then at hand, and the preview's small tables are not
// built first (reading and blending the grid's is quicker).
BOOST_AUTO_TEST_CASE(interpolated_tables_are_blended_in_the_background) {
  SceneLoader l("default");
  l.apply_toml(
      "[camera]\nwidth = 8\nheight = 8\n[render]\nscattering_orders = 2\nms_altitude_samples = 8\n"
      "ms_sun_samples = 24\nms_angular_degree = 4\ncache_tables = false\nms_tables = \"interpolated\"\n"
      "[atmosphere.mie]\nscattering_per_m = 1.9341e-05\n",
      "test");
  const Scene scene = l.finish();
  BOOST_TEST_REQUIRE(table_family(scene).has_value());
  for (const Scene& member : scenes_of_tables(scene)) scene_scattering_orders(member);  // the grid's, in memory
  BOOST_TEST(scene_tables_cached(scene));
  BOOST_TEST(!viewer::scattering_tables_ready(scene));
  BOOST_TEST((viewer::tables_at_hand(scene) == viewer::TablesAtHand::none));
  viewer::build_scattering_tables(scene);
  BOOST_TEST((viewer::tables_at_hand(scene) == viewer::TablesAtHand::exact));
  BOOST_TEST(!viewer::scattering_tables_ready(viewer::with_preview_tables(scene)));
  viewer::ViewRequest request;
  request.scene = scene;
  BOOST_TEST(viewer::render_frame(request, viewer::tables_at_hand(scene)).preview == "");
}

// A shower's preview leaves its own multiple scattering out (its passes take seconds per camera
// position and sun), says so, and is the scene rendered so; the exact frame has it.
BOOST_AUTO_TEST_CASE(a_showers_preview_leaves_its_passes_out) {
  SceneLoader l("default");
  l.apply_toml(
      "[camera]\ntype = \"perspective\"\nwidth = 8\nheight = 4\nlook_at_m = [0, 1000, 200]\n"
      "[spectrum]\nwavelengths_nm = [450, 650]\n[render]\nscattering_orders = 2\nms_altitude_samples = 8\n"
      "ms_sun_samples = 16\nms_angular_degree = 2\ncache_tables = false\nshower_passes = 1\n"
      "[atmosphere.rain]\nenabled = true\nextent = \"shower\"\n",
      "test");
  const Scene scene = l.finish();
  viewer::ViewRequest request;
  request.scene = scene;
  request.preview = true;
  const viewer::Frame preview = viewer::render_frame(request, viewer::TablesAtHand::exact);
  BOOST_TEST(preview.preview == std::string("coarse sky-view table") + viewer::kShowerPreview);
  Scene expected = scene;
  expected.render.sky_view_zenith_samples = viewer::kPreviewZenithSamples;
  expected.render.sky_view_azimuth_samples = viewer::kPreviewAzimuthSamples;
  expected.render.view_segments = viewer::kPreviewViewSegments;
  expected.render.shower_passes = 0;
  BOOST_TEST(preview.png == display_png_bytes(render_to_memory(expected), {}, PngCompression::Fastest));
  // Without the shower's passes the rain is darker (its light scattered more than once missing).
  expected.render.shower_passes = 1;
  BOOST_TEST(preview.png != display_png_bytes(render_to_memory(expected), {}, PngCompression::Fastest));
  // Without tables there is nothing to leave out.
  BOOST_TEST(viewer::render_frame(request, viewer::TablesAtHand::none).preview.find(viewer::kShowerPreview) ==
             std::string::npos);
}

BOOST_AUTO_TEST_CASE(an_export_never_replaces_a_file_and_its_toml_renders_the_same_files) {
  const auto base = small_base();
  test::ScratchFolder folder("viewer-export");
  // Files of another run (and a link) with the first names: left as they are.
  test::write_text(folder.path / "view-0001.png", "not ours");
  std::filesystem::create_symlink("/nonexistent", folder.path / "view-0002.toml");
  const auto request = viewer::parse_view_request(base, {{"sun.elevation_deg", "7"}});
  const auto e = viewer::export_view(request, folder.path);
  BOOST_TEST(std::string(e.at("scene")) == (folder.path / "view-0003.toml").string());
  BOOST_TEST(test::read_all(folder.path / "view-0001.png") == "not ours");
  BOOST_TEST(std::filesystem::is_symlink(folder.path / "view-0002.toml"));
  BOOST_TEST(e.at("files").size() == 2u);

  SceneLoader again("default");
  again.apply_file((folder.path / "view-0003.toml").string());
  Scene s = again.finish();
  s.output.directory = (folder.path / "again").string();
  std::filesystem::create_directories(s.output.directory);
  render_scene_to_files(s);
  for (const char* ext : {".exr", ".png"})
    BOOST_TEST(test::read_all(folder.path / (std::string("view-0003") + ext)) ==
               test::read_all(folder.path / "again" / (std::string("view-0003") + ext)));
}

BOOST_AUTO_TEST_SUITE_END()
