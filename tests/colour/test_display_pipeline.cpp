#include <boost/test/unit_test.hpp>

#include <ImfChromaticities.h>

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <vector>

#include "colour/chromatic_adaptation.hpp"
#include "colour/display_pipeline.hpp"
#include "colour/tone_mapping.hpp"
#include "io/png_image.hpp"
#include "io/rgb_exr.hpp"
#include "scratch_folder.hpp"
#include "skyspec/colour.hpp"
#include "skyspec/error.hpp"

BOOST_AUTO_TEST_SUITE(test_display_pipeline)

using namespace skyspec;
using skyspec::test::ScratchFolder;
namespace fs = std::filesystem;

namespace {

const std::string kConfigFile = std::string(SKYSPEC_TEST_DATA_DIR) + "/../../data/ocio/config.ocio";

DisplayPipeline pipeline(const std::string& display = "", const std::string& view = "", const std::string& look = "") {
  DisplaySettings s;
  s.display = display;
  s.view = view;
  s.look = look;
  return DisplayPipeline(s);
}

/// Linear Rec.709 values of the engine for XYZ (the inverse of the pipeline's first step).
std::vector<float> rgb_of_xyz(const Eigen::Vector3d& xyz) {
  const Eigen::Vector3d rgb = xyz_to_linear_rec709() * xyz;
  return {static_cast<float>(rgb[0]), static_cast<float>(rgb[1]), static_cast<float>(rgb[2])};
}

/// A spread of in-gamut linear Rec.709 colours in [0, 1], as triples.
std::vector<float> random_colours(int n, unsigned seed = 7) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<float> v(static_cast<size_t>(n) * 3);
  for (float& x : v) x = u(random) * u(random);  // more values near black, where the curves bend
  return v;
}

/// The normalised primary matrix (RGB -> XYZ) of a set of chromaticities (SMPTE RP 177).
Eigen::Matrix3d rgb_to_xyz(const Chromaticities& c) {
  Eigen::Matrix3d p;
  const double* xy[3] = {c.red, c.green, c.blue};
  for (int i = 0; i < 3; ++i) p.col(i) = xyz_from_xy(xy[i][0], xy[i][1]);
  const Eigen::Vector3d s = p.inverse() * xyz_from_xy(c.white[0], c.white[1]);
  return p * s.asDiagonal();
}

/// The PQ (SMPTE ST 2084) encoding of a luminance in cd/m^2.
double pq_encode(double nits) {
  const double m1 = 2610.0 / 16384.0, m2 = 2523.0 / 4096.0 * 128.0;
  const double c1 = 3424.0 / 4096.0, c2 = 2413.0 / 4096.0 * 32.0, c3 = 2392.0 / 4096.0 * 32.0;
  const double y = std::pow(nits / 10000.0, m1);
  return std::pow((c1 + c2 * y) / (1.0 + c3 * y), m2);
}

/// The chunks of a PNG file: (type, data).
std::vector<std::pair<std::string, std::vector<uint8_t>>> png_chunks(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::vector<std::pair<std::string, std::vector<uint8_t>>> chunks;
  size_t at = 8;
  while (at + 12 <= bytes.size()) {
    const uint32_t length =
        uint32_t(bytes[at]) << 24 | uint32_t(bytes[at + 1]) << 16 | uint32_t(bytes[at + 2]) << 8 | bytes[at + 3];
    const std::string type(bytes.begin() + static_cast<long>(at + 4), bytes.begin() + static_cast<long>(at + 8));
    chunks.emplace_back(type, std::vector<uint8_t>(bytes.begin() + static_cast<long>(at + 8),
                                                   bytes.begin() + static_cast<long>(at + 8 + length)));
    at += 12 + length;
  }
  return chunks;
}

bool message_has(const std::exception& e, const std::string& text) {
  return std::string(e.what()).find(text) != std::string::npos;
}

}  // namespace

// ------------------------------------------------------------------------------------------------
BOOST_AUTO_TEST_SUITE(config)

// ociocheck (OpenColorIO's own validator) accepts the shipped file.
BOOST_AUTO_TEST_CASE(ociocheck_accepts_the_shipped_config) {
  const std::string command = "ociocheck --iconfig '" + kConfigFile + "' > /dev/null 2>&1";
  BOOST_TEST(std::system(command.c_str()) == 0, "ociocheck failed (is opencolorio-tools installed?)");
}

// The built-in (embedded) config loads and has what issue 3 asks for.
BOOST_AUTO_TEST_CASE(builtin_config_has_the_spaces_displays_views_and_looks) {
  const OcioConfig c;
  BOOST_TEST(c.is_builtin());
  for (const char* space : {"CIE-XYZ-D65", "Linear Rec.709", "ACEScg", "ACES2065-1"}) {
    const auto names = c.colour_spaces();
    BOOST_TEST((std::find(names.begin(), names.end(), space) != names.end()), space);
  }
  const std::vector<std::string> displays = {"sRGB", "Display P3", "Rec.1886 Rec.709", "Rec.2100-PQ"};
  BOOST_TEST(c.displays() == displays, boost::test_tools::per_element());
  BOOST_TEST(c.default_display() == "sRGB");
  for (const auto& d : displays) BOOST_TEST(c.default_view(d) == "Un-tone-mapped");
  const auto srgb_views = c.views("sRGB");
  BOOST_TEST((std::find(srgb_views.begin(), srgb_views.end(), "ACES 1.0 - SDR Video") != srgb_views.end()));
  const auto pq_views = c.views("Rec.2100-PQ");
  BOOST_TEST((std::find(pq_views.begin(), pq_views.end(), "ACES 1.1 - HDR Video (1000 nits & Rec.2020 lim)") !=
              pq_views.end()));
  BOOST_TEST(c.looks() == std::vector<std::string>{"reinhard"}, boost::test_tools::per_element());
}

// The same file loaded from disk behaves like the embedded copy.
BOOST_AUTO_TEST_CASE(config_file_equals_builtin) {
  DisplaySettings s;
  s.config = {kConfigFile, "--ocio"};
  s.view = "ACES 1.0 - SDR Video";
  const DisplayPipeline from_file(s);
  const auto colours = random_colours(200);
  const auto a = from_file.encode(colours, 3.0);
  const auto b = pipeline("", "ACES 1.0 - SDR Video").encode(colours, 3.0);
  BOOST_TEST(a == b, boost::test_tools::per_element());
}

// A user config without "CIE-XYZ-D65" is entered through its aces_interchange role: the same
// config with that space renamed gives the same code values (to float rounding).
BOOST_AUTO_TEST_CASE(config_without_xyz_space_is_entered_through_aces_interchange) {
  ScratchFolder dir("ocio");
  std::ifstream in(kConfigFile);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string from = "    name: CIE-XYZ-D65\n    family: Scene-linear";
  BOOST_REQUIRE(text.find(from) != std::string::npos);
  text.replace(text.find(from), from.size(), "    name: Scene XYZ\n    family: Scene-linear");
  const fs::path path = dir.path / "user.ocio";
  std::ofstream(path) << text;
  DisplaySettings s;
  s.config = {path.string(), "$OCIO"};
  const DisplayPipeline user(s);
  BOOST_TEST(user.config().input_description().find("aces_interchange") != std::string::npos);
  const auto colours = random_colours(200);
  const auto a = user.encode(colours, 1.0);
  const auto b = pipeline().encode(colours, 1.0);
  double worst = 0;
  for (size_t i = 0; i < a.size(); ++i) worst = std::max(worst, double(std::abs(a[i] - b[i])));
  BOOST_TEST(worst < 2e-6);
  BOOST_TEST((user.png_tag() == PngColourTag::None));  // a user's display encoding is not guessed
}

BOOST_AUTO_TEST_CASE(broken_config_is_an_input_error_naming_its_origin) {
  ScratchFolder dir("ocio");
  const fs::path path = dir.path / "broken.ocio";
  std::ofstream(path) << "ocio_profile_version: 2.1\nroles: [\n";
  try {
    OcioConfig c({path.string(), "--ocio"});
    BOOST_FAIL("no error");
  } catch (const InputError& e) {
    BOOST_TEST(message_has(e, "--ocio"));
    BOOST_TEST(message_has(e, "broken.ocio"));
  }
  BOOST_CHECK_THROW(OcioConfig({(dir.path / "missing.ocio").string(), "--ocio"}), InputError);
}

BOOST_AUTO_TEST_SUITE_END()

// ------------------------------------------------------------------------------------------------
BOOST_AUTO_TEST_SUITE(names)

BOOST_AUTO_TEST_CASE(unknown_names_list_the_valid_ones) {
  try {
    pipeline("P3");
    BOOST_FAIL("no error");
  } catch (const InputError& e) {
    BOOST_TEST(message_has(e, "display.display = \"P3\" is not allowed"));
    BOOST_TEST(e.setting() == display_setting::kDisplay);
    BOOST_TEST(message_has(e, "\"sRGB\", \"Display P3\", \"Rec.1886 Rec.709\", \"Rec.2100-PQ\""));
  }
  try {
    pipeline("sRGB", "ACES 1.1 - HDR Video (1000 nits & Rec.2020 lim)");
    BOOST_FAIL("no error");
  } catch (const InputError& e) {
    BOOST_TEST(e.setting() == display_setting::kView);
    BOOST_TEST(message_has(e, "\"Un-tone-mapped\", \"ACES 1.0 - SDR Video\", \"Raw\""));
  }
  try {
    pipeline("", "", "filmic");
    BOOST_FAIL("no error");
  } catch (const InputError& e) {
    BOOST_TEST(e.setting() == display_setting::kLook);
    BOOST_TEST(message_has(e, "\"reinhard\""));
    BOOST_TEST(message_has(e, "\"uncharted2-filmic\""));
  }
}

// Names match exactly, or case-insensitively when that is unambiguous.
BOOST_AUTO_TEST_CASE(names_match_case_insensitively) {
  const auto p = pipeline("display p3", "aces 1.0 - sdr video", "ACES-APPROX");
  BOOST_TEST(p.display() == "Display P3");
  BOOST_TEST(p.view() == "ACES 1.0 - SDR Video");
  BOOST_TEST(p.look() == "aces-approx");
  BOOST_TEST(p.look_kind() == "skyspec look (C++)");
  BOOST_TEST(pipeline("", "", "reinhard").look_kind() == "OCIO look");
}

BOOST_AUTO_TEST_SUITE_END()

// ------------------------------------------------------------------------------------------------
BOOST_AUTO_TEST_SUITE(colour)

// D65 white in XYZ maps to equal RGB in linear Rec.709 and in ACEScg (Bradford takes D65 to the
// ACES white, which is RGB (1, 1, 1) in every ACES space).
BOOST_AUTO_TEST_CASE(d65_white_is_equal_rgb_in_every_working_space) {
  const Eigen::Vector3d d65 = xyz_from_xy(0.3127, 0.3290, 2.0);
  const OcioConfig c;
  for (const auto& space : working_spaces()) {
    const auto rgb = to_working_space(c, rgb_of_xyz(d65), space);
    BOOST_TEST_MESSAGE(
        "D65 (Y = 2) in " << space.name << ": largest deviation from (2, 2, 2) "
                          << std::max({std::abs(rgb[0] - 2.0f), std::abs(rgb[1] - 2.0f), std::abs(rgb[2] - 2.0f)}));
    BOOST_TEST_CONTEXT(space.name) {
      BOOST_TEST(std::abs(rgb[0] - 2.0) < 2e-4);
      BOOST_TEST(std::abs(rgb[1] - 2.0) < 2e-4);
      BOOST_TEST(std::abs(rgb[2] - 2.0) < 2e-4);
    }
  }
}

// At exposure 1, scene white of luminance 1 is display white: code values (1, 1, 1) on the SDR
// displays with the un-tone-mapped view; and 100 cd/m^2 (display-reference 1.0) on the PQ display.
BOOST_AUTO_TEST_CASE(white_at_the_right_exposure_is_code_value_one) {
  const auto white = rgb_of_xyz(xyz_from_xy(0.3127, 0.3290, 1.0));
  for (const char* display : {"sRGB", "Display P3", "Rec.1886 Rec.709"}) {
    const auto code = pipeline(display).encode(white, 1.0);
    BOOST_TEST_MESSAGE("white at exposure 1 on "
                       << display << ": largest deviation from code value 1 "
                       << std::max({std::abs(code[0] - 1.0f), std::abs(code[1] - 1.0f), std::abs(code[2] - 1.0f)}));
    BOOST_TEST_CONTEXT(display) {
      for (float v : code) BOOST_TEST(std::abs(v - 1.0f) < 1e-4f);
    }
    // Half the exposure: 0.5 through the display's curve, the same in all three channels.
    const auto half = pipeline(display).encode(white, 0.5);
    BOOST_TEST(std::abs(half[0] - half[1]) < 1e-5f);
    BOOST_TEST(std::abs(half[2] - half[1]) < 1e-5f);
  }
  const auto pq = pipeline("Rec.2100-PQ").encode(white, 1.0);
  for (float v : pq) BOOST_TEST(std::abs(v - pq_encode(100.0)) < 1e-4);
  BOOST_TEST(std::abs(pq_encode(100.0) - 0.5081) < 1e-4);  // the familiar PQ code of 100 nits
}

// The default pipeline (sRGB, Un-tone-mapped) equals skyspec's own sRGB encoding (IEC 61966-2-1),
// i.e. the foundation's preview, for in-gamut colours.
BOOST_AUTO_TEST_CASE(default_pipeline_is_the_srgb_encoding) {
  const auto colours = random_colours(1000);
  const auto code = pipeline().encode(colours, 1.0);
  double worst = 0;
  for (size_t i = 0; i < colours.size(); ++i) worst = std::max(worst, std::abs(code[i] - srgb_encode(colours[i])));
  BOOST_TEST_MESSAGE("OCIO sRGB vs srgb_encode, largest difference: " << worst);
  BOOST_TEST(worst < 1e-4);
}

// Display P3 is built from a matrix and the sRGB curve (OCIO 2.1 has no built-in for it): check
// against the P3-D65 primary matrix derived here from the chromaticities and the sRGB curve.
BOOST_AUTO_TEST_CASE(display_p3_is_p3_primaries_with_the_srgb_curve) {
  const Chromaticities p3{{0.680, 0.320}, {0.265, 0.690}, {0.150, 0.060}, {0.3127, 0.3290}};
  const Eigen::Matrix3d rec709_to_p3 = rgb_to_xyz(p3).inverse() * linear_rec709_to_xyz();
  const auto colours = random_colours(1000, 11);
  const auto code = pipeline("Display P3").encode(colours, 1.0);
  double worst = 0;
  for (size_t i = 0; i < colours.size(); i += 3) {
    const Eigen::Vector3d p = rec709_to_p3 * Eigen::Vector3d(colours[i], colours[i + 1], colours[i + 2]);
    for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(code[i + size_t(c)] - srgb_encode(p[c])));
  }
  BOOST_TEST_MESSAGE("Display P3 vs matrix + sRGB curve, largest difference: " << worst);
  BOOST_TEST(worst < 1e-4);
}

// The ACES SDR output transform is a tone curve: mid-grey 0.18 lands near 10 % of display white
// (the RRT + ODT put it at about 0.1 display-linear: sRGB code about 0.35-0.40), and 16x mid-grey
// is not clipped.
BOOST_AUTO_TEST_CASE(aces_sdr_view_compresses_highlights) {
  const auto grey = rgb_of_xyz(xyz_from_xy(0.3127, 0.3290, 0.18));
  const auto code = pipeline("sRGB", "ACES 1.0 - SDR Video").encode(grey, 1.0);
  BOOST_TEST_MESSAGE("ACES 1.0 SDR: mid-grey -> sRGB code " << code[1]);
  BOOST_TEST(code[1] > 0.3f);
  BOOST_TEST(code[1] < 0.45f);
  const auto bright = pipeline("sRGB", "ACES 1.0 - SDR Video").encode(grey, 16.0);
  BOOST_TEST(bright[1] < 0.99f);
  BOOST_TEST(bright[1] > code[1]);
}

// The OCIO look "reinhard" (log-affine, inverse log, matrix) is exactly c / (1 + c).
BOOST_AUTO_TEST_CASE(ocio_reinhard_look_equals_the_formula) {
  std::vector<float> values;
  for (double c = 0.0; c <= 64.0; c = c * 1.25 + 0.01)
    for (int k = 0; k < 3; ++k) values.push_back(static_cast<float>(c));
  const auto code = pipeline("sRGB", "Un-tone-mapped", "reinhard").encode(values, 1.0);
  double worst = 0;
  for (size_t i = 0; i < values.size(); ++i)
    worst = std::max(worst, std::abs(code[i] - srgb_encode(reinhard(values[i]))));
  BOOST_TEST_MESSAGE("OCIO reinhard look vs c / (1 + c), largest sRGB code difference: " << worst);
  BOOST_TEST(worst < 1e-4);
}

BOOST_AUTO_TEST_SUITE_END()

// ------------------------------------------------------------------------------------------------
BOOST_AUTO_TEST_SUITE(files)

// The chromaticities attribute round-trips, and it describes the data: R, G, B through
// Imf::RGBtoXYZ of the attribute, adapted from the file's white to D65 (Bradford, as the ACES
// configs do), give back the engine's XYZ.
BOOST_AUTO_TEST_CASE(working_space_exr_chromaticities_round_trip) {
  ScratchFolder dir("rgbexr");
  const OcioConfig c;
  const auto colours = random_colours(64, 3);
  const Eigen::Vector3d d65 = xyz_from_xy(0.3127, 0.3290);
  for (const auto& space : working_spaces()) {
    const auto rgb = to_working_space(c, colours, space);
    const fs::path path = dir.path / (space.name + ".exr");
    write_rgb_exr(path, 8, 8, rgb, space.chromaticities, {{"skyspec:workingSpace", space.name}});
    const RgbExrImage back = read_rgb_exr(path);
    BOOST_TEST_CONTEXT(space.name) {
      BOOST_TEST(back.has_chromaticities);
      for (int k = 0; k < 2; ++k) {
        BOOST_TEST(back.chromaticities.red[k] == double(float(space.chromaticities.red[k])));
        BOOST_TEST(back.chromaticities.green[k] == double(float(space.chromaticities.green[k])));
        BOOST_TEST(back.chromaticities.blue[k] == double(float(space.chromaticities.blue[k])));
        BOOST_TEST(back.chromaticities.white[k] == double(float(space.chromaticities.white[k])));
      }
      BOOST_TEST(back.rgb == rgb, boost::test_tools::per_element());
      BOOST_TEST(back.strings.at("skyspec:workingSpace") == space.name);
      const auto v2 = [](const double xy[2]) { return IMATH_NAMESPACE::V2f(float(xy[0]), float(xy[1])); };
      const Imf::Chromaticities chroma(v2(back.chromaticities.red), v2(back.chromaticities.green),
                                       v2(back.chromaticities.blue), v2(back.chromaticities.white));
      const IMATH_NAMESPACE::M44f m = Imf::RGBtoXYZ(chroma, 1.0f);  // row vectors: xyz = rgb * m
      const Eigen::Matrix3d adapt =
          bradford_adaptation(xyz_from_xy(back.chromaticities.white[0], back.chromaticities.white[1]), d65);
      double worst = 0;
      for (size_t i = 0; i < rgb.size(); i += 3) {
        Eigen::Vector3d xyz;
        for (int col = 0; col < 3; ++col)
          xyz[col] = rgb[i] * m[0][col] + rgb[i + 1] * m[1][col] + rgb[i + 2] * m[2][col];
        const Eigen::Vector3d expected =
            linear_rec709_to_xyz() * Eigen::Vector3d(colours[i], colours[i + 1], colours[i + 2]);
        worst = std::max(worst, (adapt * xyz - expected).norm());
      }
      BOOST_TEST_MESSAGE(space.name << ": XYZ from the chromaticities attribute vs the engine, largest error "
                                    << worst);
      BOOST_TEST(worst < 2e-4);
    }
  }
}

// 8- and 16-bit PNGs carry the chunks of their display.
BOOST_AUTO_TEST_CASE(png_bit_depth_and_colour_chunks) {
  ScratchFolder dir("png");
  const std::vector<float> code = {0.0f, 0.5f, 1.0f, 0.25f, 0.75f, 0.125f};
  struct Case {
    PngColourTag tag;
    int bits;
    std::string chunk;
  };
  for (const Case& k : {Case{PngColourTag::Srgb, 8, "sRGB"}, Case{PngColourTag::DisplayP3, 16, "cICP"},
                        Case{PngColourTag::Rec2100Pq, 16, "cICP"}, Case{PngColourTag::Rec709, 8, "cICP"}}) {
    const fs::path path = dir.path / "x.png";
    write_png_display(path, 2, 1, code, k.bits, k.tag, {{"skyspec:display", "test"}});
    const auto chunks = png_chunks(path);
    BOOST_REQUIRE(!chunks.empty());
    BOOST_TEST(chunks.front().first == "IHDR");
    BOOST_TEST(int(chunks.front().second[8]) == k.bits);
    bool found = false, text = false;
    size_t cicp_at = 0, idat_at = 0;
    for (size_t i = 0; i < chunks.size(); ++i) {
      if (chunks[i].first == k.chunk) found = true;
      if (chunks[i].first == "tEXt") text = true;
      if (chunks[i].first == "cICP" && !cicp_at) cicp_at = i;
      if (chunks[i].first == "IDAT" && !idat_at) idat_at = i;
    }
    BOOST_TEST(found, k.chunk);
    BOOST_TEST(text);
    if (k.chunk == "cICP") {
      BOOST_TEST(cicp_at < idat_at);
      const auto& data = chunks[cicp_at].second;
      BOOST_TEST(data.size() == 4u);
      if (k.tag == PngColourTag::Rec2100Pq) BOOST_TEST((data[0] == 9 && data[1] == 16 && data[2] == 0 && data[3] == 1));
      if (k.tag == PngColourTag::DisplayP3) BOOST_TEST((data[0] == 12 && data[1] == 13));
    }
  }
  BOOST_CHECK_THROW(write_png_display(dir.path / "y.png", 2, 1, code, 12, PngColourTag::None), IoError);
  BOOST_TEST(!fs::exists(dir.path / "y.png"));
}

BOOST_AUTO_TEST_SUITE_END()

BOOST_AUTO_TEST_SUITE_END()  // test_display_pipeline
