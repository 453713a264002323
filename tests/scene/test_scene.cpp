#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "check_helpers.hpp"
#include "scene_fixtures.hpp"
#include "skyspec/error.hpp"
#include "skyspec/render.hpp"
#include "skyspec/scene.hpp"

BOOST_AUTO_TEST_SUITE(test_scene)

using namespace skyspec;

namespace {
template <class F>
std::string error_of(F f) {
  return test::input_error_message(f);
}
using test::contains;

std::string load_error(const std::string& toml, const std::string& preset = "default") {
  return error_of([&] {
    SceneLoader l(preset);
    l.apply_toml(toml, "test.toml");
    (void)l.finish();
  });
}
}  // namespace

BOOST_AUTO_TEST_CASE(presets_load) {
  const Scene d = SceneLoader("default").finish();
  BOOST_TEST(make_wavelength_grid(d).size() == 41);
  BOOST_TEST((d.render.path == RenderSpec::Path::Spectral));
  BOOST_TEST(d.atmosphere.rayleigh.derivation.co2_ppv == 420e-6, boost::test_tools::tolerance(1e-12));
  const Scene s = SceneLoader("seed").finish();
  BOOST_TEST((s.render.path == RenderSpec::Path::RgbFast));
  BOOST_TEST(s.atmosphere.rayleigh.fixed_beta_per_m.size() == 3u);
  BOOST_TEST(s.sun.spectral_irradiance_W_m2_nm == 20.0);
}

BOOST_AUTO_TEST_CASE(unknown_preset_lists_the_known_ones) {
  const std::string e = error_of([] { SceneLoader l("sunset"); });
  BOOST_TEST(contains(e, "preset"));
  BOOST_TEST(contains(e, "default, hazy, high-altitude, mars, seed"));
}

BOOST_AUTO_TEST_CASE(unknown_key_suggests_the_nearest_and_names_the_line) {
  const std::string e = load_error("[atmosphere.rayleigh]\nscale_heigth_m = 8000\n");
  BOOST_TEST(contains(e, "test.toml:2:1"));
  BOOST_TEST(contains(e, "atmosphere.rayleigh.scale_heigth_m"));
  BOOST_TEST(contains(e, "did you mean \"atmosphere.rayleigh.scale_height_m\""));
  const std::string t = load_error("[camra]\nwidth = 5\n");
  BOOST_TEST(contains(t, "unknown key \"camra\""));
}

BOOST_AUTO_TEST_CASE(wrong_type_and_out_of_range_values) {
  const std::string type = load_error("[camera]\nwidth = \"wide\"\n");
  BOOST_TEST(contains(type, "test.toml:2:9"));
  BOOST_TEST(contains(type, "camera.width = \"wide\""));
  BOOST_TEST(contains(type, "a whole number from 1 to 65536"));
  const std::string radius = load_error("[planet]\nradius_m = -5\n");
  BOOST_TEST(contains(radius, "planet.radius_m = -5"));
  BOOST_TEST(contains(radius, ">= 1000"));
  BOOST_TEST(!load_error("[atmosphere]\ntop_altitude_m = 0\n").empty());
  BOOST_TEST(contains(load_error("[atmosphere.mie]\ng = 1.0\n"), "atmosphere.mie.g"));
  BOOST_TEST(contains(load_error("[atmosphere.mie]\nphase = \"rayleigh\"\n"), "cornette-shanks, henyey-greenstein"));
  BOOST_TEST(contains(load_error("[sun]\nelevation_deg = nan\n"), "sun.elevation_deg"));
  BOOST_TEST(contains(load_error("[output]\nname = \"../x\"\n"), "output.name"));
}

BOOST_AUTO_TEST_CASE(invalid_toml_reports_position) {
  const std::string e = load_error("[camera]\nwidth = = 3\n");
  BOOST_TEST(contains(e, "test.toml:2:"));
  BOOST_TEST(contains(e, "valid TOML"));
}

BOOST_AUTO_TEST_CASE(wavelength_grid_must_lie_where_the_tables_are) {
  // The ultraviolet and near infrared render (colour comes from the overlap with the CMFs); each
  // end is where a table the scene uses ends, named in the message.
  const auto grid_from = [](const std::string& toml) {
    SceneLoader l("default");
    l.apply_toml(toml, "test.toml");
    return make_wavelength_grid(l.finish());
  };
  BOOST_TEST(grid_from("[spectrum]\nmin_nm = 300\n").min_nm() == 300.0);
  BOOST_TEST(grid_from("[spectrum]\nmin_nm = 280\nmax_nm = 1060\nstep_nm = 20\n").max_nm() == 1060.0);
  BOOST_TEST(contains(load_error("[spectrum]\nmin_nm = 270\n"), "from 280 nm (the extraterrestrial solar spectrum"));
  BOOST_TEST(contains(load_error("[spectrum]\nmax_nm = 1100\nstep_nm = 10\n"), "to 1060 nm (the built-in ozone"));
  // Without ozone the solar spectrum and the refractive index (to 1690 nm) set the range; with a
  // flat sun too, the refractive index alone (from 230 nm).
  BOOST_TEST(grid_from("[atmosphere.ozone]\nenabled = false\n[spectrum]\nmin_nm = 400\nmax_nm = 1600\nstep_nm = 100\n")
                 .max_nm() == 1600.0);
  BOOST_TEST(contains(load_error("[atmosphere.ozone]\nenabled = false\n[spectrum]\nmax_nm = 1700\nstep_nm = 10\n"),
                      "to 1690 nm (the refractive index of air: the range of Peck & Reeder"));
  BOOST_TEST(contains(
      load_error("[atmosphere.ozone]\nenabled = false\n[sun]\nspectrum = \"flat\"\n[spectrum]\nmin_nm = 220\n"),
      "from 230 to 1690 nm when render.path = \"spectral\": the refractive index of air"));
  BOOST_TEST(contains(load_error("[spectrum]\nstep_nm = 0.5\n"),
                      "spectrum.step_nm = 0.5 is not allowed: a number in nm, >= 1"));
  BOOST_TEST(contains(load_error("[spectrum]\nstep_nm = 7\n"), "divides"));
  BOOST_TEST(contains(load_error("[spectrum]\ncount = 500\n"), "at least 1 nm apart"));
  SceneLoader counted;
  counted.apply_toml("[spectrum]\ncount = 48\nmin_nm = 360\nmax_nm = 830\n", "test.toml");
  BOOST_TEST(make_wavelength_grid(counted.finish()).size() == 48);
  // The seed's typed-in coefficients exist only at its three wavelengths.
  BOOST_TEST(
      contains(load_error("[spectrum]\nwavelengths_nm = [440, 550, 600]\n[render]\npath = \"spectral\"\n", "seed"),
               "atmosphere.rayleigh.wavelengths_nm"));
  BOOST_TEST(contains(load_error("[render]\npath = \"rgb-fast\"\n"), "exactly 440, 550 and 680 nm"));
}

BOOST_AUTO_TEST_CASE(camera_below_ground_is_rejected) {
  const std::string e = load_error("[camera]\nposition_m = [0, 0, -10]\n");
  BOOST_TEST(contains(e, "camera.position_m"));
  BOOST_TEST(contains(e, "below"));
}

BOOST_AUTO_TEST_CASE(overrides_name_their_flag) {
  const std::string e = error_of([] {
    SceneLoader l;
    l.apply_override("camera.width", "-5", "--width");
  });
  BOOST_TEST(contains(e, "--width: camera.width = -5 is not allowed: a whole number from 1 to 65536"));
  const std::string k = error_of([] {
    SceneLoader l;
    l.apply_override("camera.widht", "5", "--set camera.widht");
  });
  BOOST_TEST(contains(k, "did you mean \"camera.width\""));
  SceneLoader l;
  l.apply_override("camera.type", "equirectangular", "--camera");  // bare words are strings
  BOOST_TEST((l.finish().camera.type == CameraSpec::Type::Equirectangular));
}

// A flag or an override that the chosen camera does not read is refused, naming the flag, the key,
// the camera types that read it and the one chosen (issue 41: --panorama-convention blender
// rendered a fisheye); whichever order the flags come in, the camera type decides. A scene file
// may carry every key (recorded scenes do), so a file's fov_deg under a fisheye is no error.
BOOST_AUTO_TEST_CASE(keys_the_camera_does_not_read_are_refused) {
  const std::string e = error_of([] {
    SceneLoader l;  // the default camera is a fisheye
    l.apply_override("camera.panorama_convention", "blender", "--panorama-convention");
    (void)l.finish();
  });
  BOOST_TEST(e ==
             "--panorama-convention: camera.panorama_convention = \"blender\" is not allowed: only with camera.type = "
             "\"equirectangular\" (this camera is \"fisheye\" and does not read it)");
  for (const char* key : {"camera.fov_deg", "camera.look_at_m"}) {
    const std::string f = error_of([key] {
      SceneLoader l;
      l.apply_override("camera.type", "equirectangular", "--camera");
      l.apply_override(key, std::string(key) == "camera.fov_deg" ? "30" : "[0, 1, 0]", "--set");
      (void)l.finish();
    });
    BOOST_TEST(contains(f, std::string(key) + " = "));
    BOOST_TEST(contains(f, "only with camera.type = \"perspective\" (this camera is \"equirectangular\""));
  }
  SceneLoader later;  // the type after the key
  later.apply_override("camera.fov_deg", "30", "--fov");
  later.apply_override("camera.type", "perspective", "--camera");
  BOOST_TEST(later.finish().camera.fov_deg == 30.0);
  SceneLoader file;
  file.apply_toml("[camera]\ntype = \"fisheye\"\nfov_deg = 30\npanorama_convention = \"blender\"\n", "test.toml");
  BOOST_TEST((file.finish().camera.type == CameraSpec::Type::Fisheye));
  // The registry says which camera reads a key, and its help says so.
  for (const auto& [key, help] : scene_key_help())
    if (key == "camera.panorama_convention" || key == "camera.min_elevation_deg")
      BOOST_TEST(contains(help, ") equirectangular: "), key);
}

// The equirectangular camera's bottom edge: 0 is the upper hemisphere; the horizon cannot be
// the top edge, so 90 is refused with the range.
BOOST_AUTO_TEST_CASE(equirectangular_elevation_range) {
  SceneLoader l;
  l.apply_override("camera.type", "equirectangular", "--camera");
  l.apply_override("camera.min_elevation_deg", "0", "--set camera.min_elevation_deg");
  BOOST_TEST(l.finish().camera.min_elevation_deg == 0.0);
  const std::string e = error_of([] {
    SceneLoader bad;
    bad.apply_override("camera.min_elevation_deg", "90", "--set camera.min_elevation_deg");
  });
  BOOST_TEST(contains(e, "camera.min_elevation_deg = 90 is not allowed"));
  BOOST_TEST(contains(e, "<= 89"));
}

// A panorama that sees the ground gets kPanoramaGroundAlbedo unless a preset, file or flag sets
// a ground albedo (0 included); other cameras, and panoramas of the upper hemisphere, keep the
// scene's (0 by default). A recorded scene sets every key, so it keeps its albedo.
BOOST_AUTO_TEST_CASE(panoramas_get_a_grey_ground_unless_one_is_set) {
  const auto albedo = [](std::initializer_list<std::pair<std::string, std::string>> keys) {
    SceneLoader l;
    for (const auto& [key, value] : keys) l.apply_override(key, value, "test");
    return l.finish().atmosphere.ground.albedo;
  };
  BOOST_TEST(albedo({}) == 0.0);
  BOOST_TEST(albedo({{"camera.type", "equirectangular"}}) == kPanoramaGroundAlbedo);
  BOOST_TEST(albedo({{"camera.type", "equirectangular"}, {"camera.min_elevation_deg", "-10"}}) ==
             kPanoramaGroundAlbedo);
  BOOST_TEST(albedo({{"camera.type", "equirectangular"}, {"camera.min_elevation_deg", "0"}}) == 0.0);
  BOOST_TEST(albedo({{"camera.type", "equirectangular"}, {"ground.albedo", "0"}}) == 0.0);
  BOOST_TEST(albedo({{"camera.type", "equirectangular"}, {"ground.albedo", "0.6"}}) == 0.6);
  BOOST_TEST(albedo({{"camera.type", "perspective"}}) == 0.0);
  SceneLoader file;
  file.apply_toml("[camera]\ntype = \"equirectangular\"\n[ground]\nalbedo = 0.0\n", "scene.toml");
  BOOST_TEST(file.finish().atmosphere.ground.albedo == 0.0);
  SceneLoader spectral;
  spectral.apply_toml(
      "[camera]\ntype = \"equirectangular\"\n[ground]\nalbedo_wavelengths_nm = [400, 700]\n"
      "albedo_values = [0.1, 0.3]\n",
      "scene.toml");
  BOOST_TEST(spectral.finish().atmosphere.ground.albedo == 0.0);  // the spectral albedo is the choice
  // The effective scene of a panorama records the albedo it used; loading it gives the same.
  SceneLoader panorama;
  panorama.apply_override("camera.type", "equirectangular", "--camera");
  const std::string recorded = scene_to_toml(panorama.finish());
  SceneLoader again;
  again.apply_toml(recorded, "recorded");
  again.apply_override("camera.type", "fisheye", "--camera");  // a flag on top does not reset it
  BOOST_TEST(again.finish().atmosphere.ground.albedo == kPanoramaGroundAlbedo);
}

// sun.date_time takes a TOML offset date-time as written in a file or after --set, unquoted, as
// well as the quoted text; a local date-time (no offset) or a bare date is refused, saying why.
BOOST_AUTO_TEST_CASE(date_times_unquoted_as_toml_writes_them) {
  const auto sun_of = [](const Scene& s) {
    return std::to_string(s.sun.elevation_deg) + " " + std::to_string(s.sun.azimuth_deg);
  };
  SceneLoader quoted;
  quoted.apply_toml("[sun]\ndate_time = \"2026-06-21T12:00:00+02:00\"\n[location]\nlatitude_deg = 48\n", "a.toml");
  SceneLoader bare;
  bare.apply_toml("[sun]\ndate_time = 2026-06-21T12:00:00+02:00\n[location]\nlatitude_deg = 48\n", "b.toml");
  SceneLoader flag;
  flag.apply_override("location.latitude_deg", "48", "--set");
  flag.apply_override("sun.date_time", "2026-06-21T10:00:00Z", "--set sun.date_time");
  BOOST_TEST(bare.finish().sun.date_time == "2026-06-21T12:00:00+02:00");
  BOOST_TEST(sun_of(bare.finish()) == sun_of(quoted.finish()));
  BOOST_TEST(sun_of(flag.finish()) == sun_of(quoted.finish()));  // the same instant in UTC
  const std::string local = error_of([] {
    SceneLoader l;
    l.apply_toml("[sun]\ndate_time = 2026-06-21T12:00:00\n", "c.toml");
  });
  BOOST_TEST(contains(local, "sun.date_time"));
  BOOST_TEST(contains(local, "UTC offset"));
  BOOST_TEST(contains(local, "c.toml:2"));
  const std::string date_only = error_of([] {
    SceneLoader l;
    l.apply_override("sun.date_time", "2026-06-21", "--set sun.date_time");
  });
  BOOST_TEST(contains(date_only, "ISO 8601 date-time with UTC offset"));
}

BOOST_AUTO_TEST_CASE(blender_and_openexr_conventions_need_the_whole_sphere) {
  for (const char* convention : {"blender", "openexr"}) {
    const std::string e = error_of([convention] {
      SceneLoader l;
      l.apply_override("camera.type", "equirectangular", "--camera");
      l.apply_override("camera.panorama_convention", convention, "--panorama-convention");
      l.apply_override("camera.min_elevation_deg", "0", "--set camera.min_elevation_deg");
      l.finish();
    });
    BOOST_TEST_CONTEXT(convention) {
      BOOST_TEST(contains(e, "camera.min_elevation_deg = 0"));
      BOOST_TEST(contains(e, "-90 with camera.panorama_convention = \"" + std::string(convention) + "\""));
    }
  }
  const std::string e = error_of([] {
    SceneLoader l;
    l.apply_override("camera.panorama_convention", "cycles", "--panorama-convention");
  });
  BOOST_TEST(contains(e, "one of: skyspec, blender, openexr"));
}

BOOST_AUTO_TEST_CASE(effective_scene_round_trips_through_toml) {
  SceneLoader a("default");
  a.apply_override("sun.elevation_deg", "7.25", "test");
  a.apply_override("atmosphere.rayleigh.co2_ppm", "360", "test");
  const std::string dumped = scene_to_toml(a.finish());
  SceneLoader b("seed");  // a different start: the dump must hold every key
  b.apply_toml(dumped, "dump");
  BOOST_TEST(scene_to_toml(b.finish()) == dumped);
  BOOST_TEST(b.finish().atmosphere.rayleigh.derivation.co2_ppv == 360e-6, boost::test_tools::tolerance(1e-12));
}

// Every shipped preset loads, validates and builds its atmosphere on its grid.
BOOST_AUTO_TEST_CASE(every_preset_is_valid) {
  for (const auto& name : preset_names()) {
    BOOST_TEST_CONTEXT("preset " << name) {
      const Scene s = SceneLoader(name).finish();
      const AtmosphereModel atm(s.atmosphere, make_wavelength_grid(s));
      BOOST_TEST(atm.medium("air")->scattering_per_m.minCoeff() > 0.0);
      BOOST_TEST(atm.top_radius_m() > atm.planet_radius_m());
    }
  }
  // Mars: CO2 scatters more per molecule than air, the gas is thin, the dust absorbs blue.
  const Scene mars = SceneLoader("mars").finish();
  const AtmosphereModel m(mars.atmosphere, make_wavelength_grid(mars));
  BOOST_TEST(m.rayleigh_derivation().front().king_factor > 1.1);
  BOOST_TEST(m.rayleigh_number_density_per_m3() < 1e24);
  const int blue = 2, red = m.grid().size() - 3;  // 400 and 760 nm on the default grid
  BOOST_TEST(m.medium("aerosol")->scattering_per_m[blue] / m.medium("aerosol")->extinction_per_m[blue] <
             m.medium("aerosol")->scattering_per_m[red] / m.medium("aerosol")->extinction_per_m[red]);
}

// Quality levels: "default" is the default scene's sample counts (the two files must agree), the
// levels grow monotonically (no count falls from one level to the next, and at least one rises;
// "lean" keeps the default's march and coarsens only the tables), keys applied afterwards win, and
// an unknown level is an error that names the flag and the allowed values.
BOOST_AUTO_TEST_CASE(quality_levels) {
  const RenderSpec base = SceneLoader().finish().render;
  auto at = [](const std::string& q) {
    SceneLoader l;
    l.apply_quality(q);
    return l.finish().render;
  };
  const RenderSpec d = at("default");
  BOOST_TEST(scene_to_toml(SceneLoader().finish()) == [] {
    SceneLoader l;
    l.apply_quality("default");
    return scene_to_toml(l.finish());
  }());
  BOOST_TEST(d.view_segments == base.view_segments);
  const auto names = quality_names();
  for (size_t i = 1; i < names.size(); ++i) {
    const RenderSpec lo = at(names[i - 1]), hi = at(names[i]);
    BOOST_TEST_CONTEXT(names[i - 1] << " -> " << names[i]) {
      const std::vector<std::pair<int, int>> counts = {{lo.view_segments, hi.view_segments},
                                                       {lo.table_altitude_samples, hi.table_altitude_samples},
                                                       {lo.table_zenith_samples, hi.table_zenith_samples},
                                                       {lo.ms_altitude_samples, hi.ms_altitude_samples},
                                                       {lo.ms_sun_samples, hi.ms_sun_samples},
                                                       {lo.ms_view_segments, hi.ms_view_segments},
                                                       {lo.ms_higher_order_segments, hi.ms_higher_order_segments},
                                                       {lo.scattering_orders, hi.scattering_orders}};
      bool rises = false;
      for (const auto& [a, b] : counts) {
        BOOST_TEST(a <= b);
        rises = rises || a < b;
      }
      // The sky-view table's size where both levels have one ("reference" marches every pixel).
      if (lo.sky_view_table && hi.sky_view_table) {
        BOOST_TEST(lo.sky_view_zenith_samples <= hi.sky_view_zenith_samples);
        BOOST_TEST(lo.sky_view_azimuth_samples <= hi.sky_view_azimuth_samples);
        BOOST_TEST(lo.sky_view_higher_zenith_samples <= hi.sky_view_higher_zenith_samples);
        BOOST_TEST(lo.sky_view_higher_azimuth_samples <= hi.sky_view_higher_azimuth_samples);
        rises = rises || lo.sky_view_zenith_samples < hi.sky_view_zenith_samples;
      }
      BOOST_TEST(rises);
    }
  }
  BOOST_TEST(!at("reference").sky_view_table);
  // A preset of single scattering keeps it: the level sets how many orders, not whether.
  for (const auto& q : names) {
    SceneLoader seed("seed");
    seed.apply_quality(q);
    BOOST_TEST(seed.finish().render.scattering_orders == 1, q);
  }
  SceneLoader l;
  l.apply_quality("draft");
  l.apply_override("render.view_segments", "100", "--view-segments");
  BOOST_TEST(l.finish().render.view_segments == 100);
  const std::string e = error_of([] { SceneLoader().apply_quality("ultra"); });
  BOOST_TEST(contains(e, "render.quality = \"ultra\""));
  BOOST_TEST(contains(e, "one of: draft, lean, default, high, reference"));
}

// One schema: the built-in defaults (Scene{}) and data/scenes/default.toml are the same scene, key
// by key, so that a library user who starts from Scene{} renders what the CLI renders.
BOOST_AUTO_TEST_CASE(built_in_defaults_are_the_default_scene_file) {
  auto lines = [](const std::string& toml) {
    std::vector<std::string> out;
    std::istringstream in(toml);
    std::string line, table;
    while (std::getline(in, line)) {
      if (line.empty()) continue;
      if (line.front() == '[')
        table = line.substr(1, line.size() - 2);
      else
        out.push_back(table + "." + line);
    }
    return out;
  };
  const std::vector<std::string> built_in = lines(scene_to_toml(Scene{}));
  const std::vector<std::string> file = lines(scene_to_toml(SceneLoader("default").finish()));
  BOOST_TEST(built_in.size() == file.size());
  for (size_t i = 0; i < std::min(built_in.size(), file.size()); ++i) BOOST_TEST(built_in[i] == file[i]);
  BOOST_TEST(default_scene().atmosphere.mie.angstrom_exponent == Scene{}.atmosphere.mie.angstrom_exponent);
}

// docs/scene-keys.md is generated from the key registry (`skyspec render --help-keys=markdown`):
// every key appears once, with the default scene's value.
BOOST_AUTO_TEST_CASE(key_reference_lists_every_key_with_its_default) {
  const std::string md = scene_keys_markdown();
  for (const auto& [key, doc] : scene_key_help()) {
    BOOST_TEST_CONTEXT(key) {
      const std::string cell = "| `" + key + "` |";
      BOOST_TEST(md.find(cell) != std::string::npos);
      BOOST_TEST(md.find(cell) == md.rfind(cell));
    }
  }
  BOOST_TEST(md.find("| `camera.width` | 512 |") != std::string::npos);
}

// Camera types and panorama conventions are named in one table each (camera_spec.hpp): the scene
// key accepts exactly those names, writes them back, and every type has a camera (make_camera).
BOOST_AUTO_TEST_CASE(every_named_camera_type_and_convention_round_trips_through_the_scene_key) {
  BOOST_TEST(camera_types().size() == 3u);
  for (const auto& row : camera_types()) {
    SceneLoader l;
    l.apply_override("camera.type", std::string("\"") + row.name + "\"", "test");
    const Scene s = l.finish();
    BOOST_TEST((s.camera.type == row.value));
    BOOST_TEST(std::string(camera_type_name(s.camera.type)) == row.name);
    BOOST_TEST(scene_to_toml(s, SceneTomlKeys::All).find(std::string("type = \"") + row.name + "\"") !=
               std::string::npos);
    BOOST_TEST(static_cast<bool>(make_camera(s)));
  }
  for (const auto& row : panorama_conventions()) {
    BOOST_TEST((value_named(panorama_conventions(), row.name, "x") == row.value));
    BOOST_TEST(std::string(panorama_convention_name(row.value)) == row.name);
  }
  try {
    value_named(camera_types(), "orthographic", "camera.type");
    BOOST_FAIL("no error");
  } catch (const InputError& e) {
    BOOST_TEST(std::string(e.what()) ==
               "camera.type = orthographic is not allowed: one of fisheye perspective equirectangular");
  }
}

// A list key's bounds read "each in <unit>, ..." (they read "each n nm" when the text was cut from
// a single number's by a fixed offset).
BOOST_AUTO_TEST_CASE(list_keys_state_the_unit_and_bounds_of_each_value) {
  std::map<std::string, std::string> help;
  for (const auto& [key, doc] : scene_key_help()) help[key] = doc;
  BOOST_TEST(contains(help.at("atmosphere.rayleigh.wavelengths_nm"), "numbers, each in nm, >= 1 and <= 100000"));
  BOOST_TEST(contains(help.at("ground.albedo_values"), "numbers, each >= 0 and <= 1"));
}

// A table where a key wants a value is that key's wrong value (issue 42, item 18: it suggested
// the key itself as "did you mean").
BOOST_AUTO_TEST_CASE(a_table_for_a_value_is_that_keys_error) {
  const std::string e = error_of([] {
    SceneLoader l;
    l.apply_toml("[sun]\nelevation_deg = {a = 1}\n", "t.toml");
  });
  BOOST_TEST(contains(e, "sun.elevation_deg = "));
  BOOST_TEST(contains(e, "is not allowed: a number in degrees"));
  BOOST_TEST(!contains(e, "did you mean"));
}

// No sample's band reaches 0 nm (issue 42, item 20: 1000 nm around 380 nm was accepted).
BOOST_AUTO_TEST_CASE(a_band_below_zero_nm_is_refused) {
  const std::string e = error_of([] {
    SceneLoader l;
    l.apply_override("spectrum.bandwidth_nm", "1000", "--set spectrum.bandwidth_nm");
    l.finish();
  });
  BOOST_TEST(
      contains(e, "spectrum.bandwidth_nm = 1000 is not allowed: less than twice the shortest wavelength (380 nm)"));
  SceneLoader ok;
  ok.apply_override("spectrum.bandwidth_nm", "700", "--set spectrum.bandwidth_nm");
  BOOST_TEST(ok.finish().spectrum.bandwidth_nm == 700.0);
}

// Typed overrides for C++ callers (issue 41): each type reaches its key; text is quoted, not parsed.
BOOST_AUTO_TEST_CASE(typed_overrides) {
  SceneLoader loader("default");
  loader.set("camera.width", 320);
  loader.set("sun.elevation_deg", 12.5);
  loader.set("output.png", false);
  loader.set("camera.type", "equirectangular");
  loader.set("output.name", std::string("2026"));  // text, not the TOML integer
  loader.set("camera.position_m", std::vector<double>{0.0, 0.0, 1500.0});
  const Scene scene = loader.finish();
  BOOST_TEST(scene.camera.width == 320);
  BOOST_TEST(scene.sun.elevation_deg == 12.5);
  BOOST_TEST(!scene.output.png);
  BOOST_TEST((scene.camera.type == CameraSpec::Type::Equirectangular));
  BOOST_TEST(scene.output.name == "2026");
  BOOST_TEST(scene.camera.position_m.z() == 1500.0);
  // The same checks as every other way in: the key and what is allowed; a given origin named.
  BOOST_CHECK_EXCEPTION(loader.set("camera.width", 8.5), InputError, [](const InputError& e) {
    return test::contains(e.what(), "camera.width = 8.5 is not allowed");
  });
  BOOST_CHECK_EXCEPTION(loader.set("sun.elevation_deg", 95.0, "my_elevation"), InputError,
                        [](const InputError& e) { return test::contains(e.what(), "my_elevation"); });
}

BOOST_AUTO_TEST_SUITE_END()  // test_scene
