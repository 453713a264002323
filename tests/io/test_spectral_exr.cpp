#include <boost/test/unit_test.hpp>

#include <ImfChannelList.h>
#include <ImfFloatAttribute.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfStandardAttributes.h>
#include <ImfStringAttribute.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "io/png_image.hpp"
#include "io/spectral_exr.hpp"
#include "scratch_folder.hpp"
#include "skyspec/colour.hpp"
#include "skyspec/error.hpp"

BOOST_AUTO_TEST_SUITE(test_spectral_exr)

using namespace skyspec;
using skyspec::test::ScratchFolder;
namespace fs = std::filesystem;

namespace {

/// A small test image: 41 wavelengths 380-780 nm, random finite values of varied magnitude.
struct TestImage {
  int width = 7, height = 11;
  std::vector<double> wavelengths_nm;
  std::vector<float> spectral, rgb;
  TestImage() {
    for (int i = 0; i <= 40; ++i) wavelengths_nm.push_back(380.0 + 10.0 * i);
    std::mt19937 random(12345);
    std::uniform_real_distribution<float> mantissa(-1.0f, 1.0f);
    std::uniform_int_distribution<int> exponent(-20, 20);
    const auto value = [&] { return std::ldexp(mantissa(random), exponent(random)); };
    spectral.resize(static_cast<size_t>(width * height) * wavelengths_nm.size());
    rgb.resize(static_cast<size_t>(width * height) * 3);
    for (float& v : spectral) v = value();
    for (float& v : rgb) v = value();
  }
  size_t n() const { return wavelengths_nm.size(); }
  /// Writes in bands of `band_rows` rows (the last may be shorter).
  void write(const fs::path& path, int band_rows, const SpectralExrMetadata& meta) const {
    SpectralExrWriter writer(path, width, height, wavelengths_nm, meta);
    for (int y = 0; y < height; y += band_rows) {
      const int rows = std::min(band_rows, height - y);
      writer.write_rows(rows, spectral.data() + static_cast<size_t>(y * width) * n(),
                        rgb.data() + static_cast<size_t>(y * width) * 3);
    }
    writer.finish();
  }
};

SpectralExrMetadata test_metadata() {
  SpectralExrMetadata meta;
  meta.strings["skyspec:scene"] = "default";
  meta.ev = 2.5f;
  return meta;
}

bool same_bits(const std::vector<float>& a, const std::vector<float>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

std::string read_all(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

}  // namespace

// ------------------------------------------------------------------------------------------------
BOOST_AUTO_TEST_SUITE(channel_names)

BOOST_AUTO_TEST_CASE(names_use_six_decimals_and_a_comma) {
  BOOST_TEST(spectral_channel_name(550.0) == "S0.550,000000nm");
  BOOST_TEST(spectral_channel_name(412.5) == "S0.412,500000nm");
  BOOST_TEST(spectral_channel_name(1000.0 / 3.0) == "S0.333,333333nm");
}

BOOST_AUTO_TEST_CASE(parse_accepts_the_layouts_forms) {
  const auto near = [](std::optional<double> v, double expected) {
    return v.has_value() && std::abs(*v - expected) < 1e-9;
  };
  BOOST_TEST(near(parse_spectral_channel_name("S0.550,000000nm"), 550.0));
  BOOST_TEST(near(parse_spectral_channel_name("S0.412,5nm"), 412.5));
  BOOST_TEST(near(parse_spectral_channel_name("S0.550nm"), 550.0));
  BOOST_TEST(near(parse_spectral_channel_name("S0.0,55um"), 550.0));
  BOOST_TEST(near(parse_spectral_channel_name("S0.550,nm"), 550.0));
  BOOST_TEST(near(parse_spectral_channel_name("S0.0,00055mm"), 550.0));
  BOOST_TEST(near(parse_spectral_channel_name("S0.5,5e-7m"), 550.0));
  BOOST_TEST(near(parse_spectral_channel_name("S0.0,55\xC2\xB5m"), 550.0));  // U+00B5 micro sign
  // Frequency: lambda = c / f; 545.077196 THz is 550.0000004 nm.
  BOOST_TEST(std::abs(parse_spectral_channel_name("S0.545,077196THz").value_or(0.0) - 550.0) < 1e-5);
  // Our own names read back to within their 1e-6 nm rounding.
  for (double lambda_nm : {360.0, 412.5, 555.123456, 1000.0 / 3.0, 830.0, 2500.25})
    BOOST_TEST(std::abs(parse_spectral_channel_name(spectral_channel_name(lambda_nm)).value_or(0.0) - lambda_nm) <
               1e-6);
}

// Stokes components 1 to 3: the same names with S1-S3 (polarised files), read by
// parse_stokes_channel_name and never taken for S0.
BOOST_AUTO_TEST_CASE(stokes_components_have_their_own_names) {
  BOOST_TEST(spectral_channel_name(550.0, 2) == "S2.550,000000nm");
  const auto s3 = parse_stokes_channel_name("S3.0,55um");
  BOOST_TEST((s3.has_value() && s3->first == 3 && std::abs(s3->second - 550.0) < 1e-9));
  BOOST_TEST(!parse_stokes_channel_name("S4.550nm").has_value());
  BOOST_TEST(!parse_stokes_channel_name("S1550nm").has_value());
  BOOST_CHECK_THROW(spectral_channel_name(550.0, 4), Error);
}

BOOST_AUTO_TEST_CASE(parse_rejects_other_channels) {
  for (const char* name : {"S0.400.5nm", "R", "G", "B", "A", "T.550nm", "S1.550nm", "S3.550,0nm", "S0.nm", "S0.,nm",
                           "S0.550", "S0.550 nm", "S0.-550nm", "S0.0nm", "s0.550nm", "S0.550Nm", "S0.550nmx", "S0550nm",
                           "S0.5500\xC3\x85m" /* angstrom: not an SI prefix */})
    BOOST_TEST(!parse_spectral_channel_name(name).has_value(), name);
}

BOOST_AUTO_TEST_SUITE_END()

// ------------------------------------------------------------------------------------------------
BOOST_AUTO_TEST_SUITE(write_and_read)

// Every compression the writer offers is lossless: the values read back are the same bits.
BOOST_AUTO_TEST_CASE(every_compression_is_lossless) {
  ScratchFolder dir("exr-compression");
  const TestImage img;
  for (const char* compression : {"piz", "zip", "zips", "rle", "none"}) {
    SpectralExrMetadata meta = test_metadata();
    meta.compression = compression;
    const fs::path path = dir.path / (std::string(compression) + ".exr");
    img.write(path, 4, meta);
    const SpectralImage back = read_spectral_exr(path);
    BOOST_TEST_CONTEXT(compression) {
      BOOST_TEST(same_bits(back.spectral, img.spectral));
      BOOST_TEST(same_bits(back.rgb, img.rgb));
    }
  }
  SpectralExrMetadata lossy = test_metadata();
  lossy.compression = "dwaa";
  BOOST_CHECK_THROW(img.write(dir.path / "dwaa.exr", 4, lossy), IoError);
  BOOST_TEST(!fs::exists(dir.path / "dwaa.exr"));
}

// Half spectral channels (opt-in): S0 stored as 16-bit half, R, G, B still float; every value read
// back within half's rounding (2^-11 relative from 2^-14 up, 2^-25 absolute below), and a value
// beyond half's 65504 refused, naming the setting, with no file left.
BOOST_AUTO_TEST_CASE(half_spectral_channels_round_to_half) {
  ScratchFolder dir("exr-half");
  TestImage img;
  for (float& v : img.spectral) v = std::min(std::abs(v), 65504.0f);  // radiances: >= 0, within range
  SpectralExrMetadata meta = test_metadata();
  meta.half_spectral = true;
  const fs::path path = dir.path / "half.exr";
  img.write(path, 4, meta);
  {
    Imf::InputFile in(path.c_str());
    BOOST_TEST(in.header().channels().findChannel("S0.550,000000nm")->type == Imf::HALF);
    BOOST_TEST(in.header().channels().findChannel("R")->type == Imf::FLOAT);
  }
  const SpectralImage back = read_spectral_exr(path);
  BOOST_TEST(same_bits(back.rgb, img.rgb));
  double worst_relative = 0.0, worst_absolute = 0.0;
  for (size_t i = 0; i < img.spectral.size(); ++i) {
    const double v = img.spectral[i], d = std::abs(back.spectral[i] - v);
    if (v >= std::ldexp(1.0, -14))
      worst_relative = std::max(worst_relative, d / v);
    else
      worst_absolute = std::max(worst_absolute, d);
  }
  BOOST_TEST_MESSAGE("half: largest relative error " << worst_relative << ", absolute below 2^-14 " << worst_absolute);
  BOOST_TEST(worst_relative <= std::ldexp(1.0, -11));
  BOOST_TEST(worst_absolute <= std::ldexp(1.0, -25));
  img.spectral[5] = 70000.0f;
  try {
    img.write(dir.path / "over.exr", 4, meta);
    BOOST_FAIL("a value beyond 65504 was written as half");
  } catch (const IoError& e) {
    BOOST_TEST(std::string(e.what()).find("output.exr_spectral_type") != std::string::npos);
  }
  BOOST_TEST(!fs::exists(dir.path / "over.exr"));
}

// The render-time estimate encodes a sample band into memory (SpectralExrWriter::Discarding): the same
// bytes as the writer puts in a file, so the same work.
BOOST_AUTO_TEST_CASE(encoding_into_memory_makes_the_file_s_bytes) {
  ScratchFolder dir("exr-encode");
  const TestImage img;
  TestImage in_half_range = img;  // what a half file can hold
  for (float& v : in_half_range.spectral) v = std::min(std::abs(v), 65504.0f);
  for (const char* compression : {"piz", "zip", "none", "piz-half"}) {
    SpectralExrMetadata meta = test_metadata();
    meta.half_spectral = std::string(compression) == "piz-half";
    meta.compression = meta.half_spectral ? "piz" : compression;
    const TestImage& data = meta.half_spectral ? in_half_range : img;
    const fs::path path = dir.path / (std::string(compression) + ".exr");
    data.write(path, data.height, meta);
    SpectralExrWriter discarding(SpectralExrWriter::Discarding{}, data.width, data.height, data.wavelengths_nm, meta);
    discarding.write_rows(data.height, data.spectral.data(), data.rgb.data());
    discarding.finish();
    BOOST_TEST_CONTEXT(compression) { BOOST_TEST(discarding.bytes_written() == fs::file_size(path)); }
  }
}

BOOST_AUTO_TEST_CASE(round_trip_through_read_spectral_exr) {
  ScratchFolder dir;
  const TestImage image;
  const fs::path path = dir.path / "sky.exr";
  image.write(path, 4, test_metadata());                             // bands of 4, 4 and 3 rows
  BOOST_TEST(dir.entries() == std::vector<std::string>{"sky.exr"});  // no temporary left

  const SpectralImage back = read_spectral_exr(path);
  BOOST_TEST(back.width == image.width);
  BOOST_TEST(back.height == image.height);
  BOOST_TEST(back.wavelengths_nm == image.wavelengths_nm);
  BOOST_TEST(same_bits(back.spectral, image.spectral));
  BOOST_TEST(same_bits(back.rgb, image.rgb));
  BOOST_TEST(back.string_attributes.at("spectralLayoutVersion") == "1.0");
  BOOST_TEST(back.string_attributes.at("emissiveUnits") == "W.m^-2.sr^-1");
  BOOST_TEST(back.string_attributes.at("skyspec:scene") == "default");
  BOOST_TEST(back.ev.has_value());
  BOOST_TEST(back.ev.value_or(0.0f) == 2.5f);
}

// A polarised file: S0-S3 at every wavelength, the layout's polarisationHandedness, and the
// reader's S1-S3 the values written (a pixel's values: S0 at all wavelengths, then S1, S2, S3).
BOOST_AUTO_TEST_CASE(polarised_round_trip) {
  ScratchFolder dir;
  const TestImage image;
  const size_t n = image.n(), pixels = static_cast<size_t>(image.width * image.height);
  std::vector<float> all(pixels * 4 * n), stokes(pixels * 3 * n);
  for (size_t p = 0; p < pixels; ++p)
    for (size_t c = 0; c < 4; ++c)
      for (size_t i = 0; i < n; ++i) {
        const float v =
            c == 0 ? image.spectral[p * n + i] : image.spectral[p * n + i] * (0.1f * static_cast<float>(c)) - 0.05f;
        all[(p * 4 + c) * n + i] = v;
        if (c > 0) stokes[(p * 3 + c - 1) * n + i] = v;
      }
  SpectralExrMetadata meta = test_metadata();
  meta.polarised = true;
  const fs::path path = dir.path / "polarised.exr";
  {
    SpectralExrWriter writer(path, image.width, image.height, image.wavelengths_nm, meta);
    writer.write_rows(image.height, all.data(), image.rgb.data());
    writer.finish();
  }
  const SpectralImage back = read_spectral_exr(path);
  BOOST_TEST(same_bits(back.spectral, image.spectral));
  BOOST_TEST(same_bits(back.stokes, stokes));
  BOOST_TEST(back.string_attributes.at("polarisationHandedness") == "right");
  Imf::InputFile raw(path.c_str());
  int count[4] = {0, 0, 0, 0};
  for (auto it = raw.header().channels().begin(); it != raw.header().channels().end(); ++it)
    if (const auto s = parse_stokes_channel_name(it.name())) ++count[s->first];
  for (int c = 0; c < 4; ++c) BOOST_TEST(count[c] == static_cast<int>(n));
  // An unpolarised file has neither.
  const fs::path plain = dir.path / "plain.exr";
  image.write(plain, 4, test_metadata());
  const SpectralImage back_plain = read_spectral_exr(plain);
  BOOST_TEST(back_plain.stokes.empty());
  BOOST_TEST(back_plain.string_attributes.count("polarisationHandedness") == 0u);
}

BOOST_AUTO_TEST_CASE(one_band_and_row_by_row_give_the_same_pixels) {
  ScratchFolder dir;
  const TestImage image;
  image.write(dir.path / "one.exr", image.height, SpectralExrMetadata{});
  image.write(dir.path / "rows.exr", 1, SpectralExrMetadata{});
  const SpectralImage one = read_spectral_exr(dir.path / "one.exr");
  const SpectralImage rows = read_spectral_exr(dir.path / "rows.exr");
  BOOST_TEST(same_bits(one.spectral, image.spectral));
  BOOST_TEST(same_bits(rows.spectral, image.spectral));
  BOOST_TEST(!one.ev.has_value());
}

// Line blocks compressed on several threads, out of order (encode_rows), then written in order
// (write_encoded), make the file that write_rows makes, byte for byte, whether write_rows gets the
// image at once or row by row (rows that do not fill a block wait for the next): for every
// compression, half spectral channels, and a tile whose data window starts inside a block.
BOOST_AUTO_TEST_CASE(blocks_encoded_on_threads_make_the_bytes_of_write_rows) {
  ScratchFolder dir("exr-blocks");
  TestImage img;
  img.height = 75;  // PIZ: blocks of 32, 32 and 11 rows
  img.spectral.resize(static_cast<size_t>(img.width * img.height) * img.n());
  img.rgb.resize(static_cast<size_t>(img.width * img.height) * 3);
  for (size_t i = 0; i < img.spectral.size(); ++i) img.spectral[i] = std::sin(0.001f * static_cast<float>(i)) + 1.5f;
  for (size_t i = 0; i < img.rgb.size(); ++i) img.rgb[i] = std::cos(0.01f * static_cast<float>(i));
  for (const char* compression : {"piz", "zip", "zips", "rle", "none"})
    for (const bool half : {false, true})
      for (const bool tile : {false, true}) {
        BOOST_TEST_CONTEXT(compression << (half ? " half" : "") << (tile ? " tile" : "")) {
          SpectralExrMetadata meta = test_metadata();
          meta.compression = compression;
          meta.half_spectral = half;
          const int image_height = tile ? img.height + 40 : img.height;
          if (tile) meta.data_window = std::array<int, 4>{0, img.width, 7, 7 + img.height};  // rows 7..81
          const fs::path whole = dir.path / "whole.exr", rows = dir.path / "rows.exr", blocks = dir.path / "blocks.exr";
          const auto rows_at = [&](int y) {
            return img.spectral.data() + static_cast<size_t>(y * img.width) * img.n();
          };
          const auto rgb_at = [&](int y) { return img.rgb.data() + static_cast<size_t>(y * img.width) * 3; };
          {
            SpectralExrWriter w(whole, img.width, image_height, img.wavelengths_nm, meta);
            w.write_rows(img.height, img.spectral.data(), img.rgb.data());
            w.finish();
          }
          {
            SpectralExrWriter w(rows, img.width, image_height, img.wavelengths_nm, meta);
            for (int y = 0; y < img.height; ++y) w.write_rows(1, rows_at(y), rgb_at(y));
            w.finish();
          }
          {
            SpectralExrWriter w(blocks, img.width, image_height, img.wavelengths_nm, meta);
            BOOST_TEST(w.rows_per_block() == spectral_exr_block_rows(compression));
            const int block = w.rows_per_block();
            std::vector<SpectralExrWriter::EncodedRows> encoded(static_cast<size_t>((img.height + block - 1) / block));
            std::vector<std::thread> threads;
            for (int t = 0; t < 3; ++t)  // three threads, each taking every third block from the last
              threads.emplace_back([&, t] {
                for (int b = static_cast<int>(encoded.size()) - 1 - t; b >= 0; b -= 3) {
                  const int y = b * block;
                  encoded[static_cast<size_t>(b)] =
                      w.encode_rows(y, std::min(block, img.height - y), rows_at(y), rgb_at(y));
                }
              });
            for (std::thread& t : threads) t.join();
            for (auto& e : encoded) w.write_encoded(std::move(e));
            w.finish();
          }
          BOOST_TEST((read_all(rows) == read_all(whole)));
          BOOST_TEST((read_all(blocks) == read_all(whole)));
          const SpectralImage back = read_spectral_exr(blocks);
          BOOST_TEST(back.height == img.height);
          if (!half) BOOST_TEST(same_bits(back.spectral, img.spectral));
          BOOST_TEST(same_bits(back.rgb, img.rgb));
        }
      }
}

// Bands that would make a wrong file are refused by name: one that does not start on a line block,
// one written out of order, one written while write_rows holds rows back; nothing is left.
BOOST_AUTO_TEST_CASE(encoded_bands_in_the_wrong_place_are_refused) {
  ScratchFolder dir("exr-bad-blocks");
  TestImage img;
  img.height = 70;
  img.spectral.assign(static_cast<size_t>(img.width * img.height) * img.n(), 1.0f);
  img.rgb.assign(static_cast<size_t>(img.width * img.height) * 3, 1.0f);
  const fs::path path = dir.path / "bad.exr";
  const auto message = [](const auto& call) {
    try {
      call();
    } catch (const IoError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  {
    SpectralExrWriter w(path, img.width, img.height, img.wavelengths_nm, SpectralExrMetadata{});  // PIZ
    const float* s = img.spectral.data();
    const float* c = img.rgb.data();
    BOOST_TEST(message([&] { w.encode_rows(1, 32, s, c); }).find("starts on a line block (32 rows)") !=
               std::string::npos);
    BOOST_TEST(message([&] { w.encode_rows(0, 20, s, c); }).find("ends on one or at the last row") !=
               std::string::npos);
    auto second = w.encode_rows(32, 32, s, c);
    BOOST_TEST(message([&] { w.write_encoded(std::move(second)); }).find("out of order: the next row to write is 0") !=
               std::string::npos);
    w.write_rows(5, s, c);  // held back: 5 rows do not fill a block
    auto first = w.encode_rows(0, 32, s, c);
    BOOST_TEST(message([&] { w.write_encoded(std::move(first)); }).find("the next row to write is 5") !=
               std::string::npos);
    img.spectral[img.n() * static_cast<size_t>(img.width + 2) + 3] = std::nanf("");  // x = 2, y = 1
    BOOST_TEST(message([&] {
                 w.encode_rows(0, 32, img.spectral.data(), c);
               }).find("non-finite spectral value at x = 2, y = 1, channel S0.410") != std::string::npos);
  }
  BOOST_TEST(fs::is_empty(dir.path));
}

// The file as any OpenEXR reader sees it, through the library's own API.
BOOST_AUTO_TEST_CASE(raw_openexr_view_of_the_file) {
  ScratchFolder dir;
  const TestImage image;
  const fs::path path = dir.path / "raw.exr";
  image.write(path, 5, test_metadata());

  Imf::InputFile in(path.c_str());
  const Imf::Header& header = in.header();
  BOOST_TEST(header.compression() == Imf::PIZ_COMPRESSION);  // the default, lossless
  BOOST_TEST(header.lineOrder() == Imf::INCREASING_Y);

  std::set<std::string> expected_channels{"R", "G", "B"};
  for (double lambda_nm : image.wavelengths_nm) {
    char name[64];
    std::snprintf(name, sizeof name, "S0.%d,000000nm", static_cast<int>(lambda_nm));
    expected_channels.insert(name);
  }
  std::set<std::string> channels;
  for (auto it = header.channels().begin(); it != header.channels().end(); ++it) {
    channels.insert(it.name());
    BOOST_TEST(it.channel().type == Imf::FLOAT);
  }
  BOOST_TEST(channels == expected_channels);
  BOOST_TEST(channels.count("S0.550,000000nm") == 1u);

  BOOST_TEST(header.typedAttribute<Imf::StringAttribute>("spectralLayoutVersion").value() == "1.0");
  BOOST_TEST(header.typedAttribute<Imf::StringAttribute>("emissiveUnits").value() == "W.m^-2.sr^-1");
  BOOST_TEST(header.typedAttribute<Imf::FloatAttribute>("EV").value() == 2.5f);
  BOOST_REQUIRE(Imf::hasChromaticities(header));
  const Imf::Chromaticities& c = Imf::chromaticities(header);
  BOOST_TEST(c.red.x == 0.64f);
  BOOST_TEST(c.red.y == 0.33f);
  BOOST_TEST(c.green.x == 0.30f);
  BOOST_TEST(c.green.y == 0.60f);
  BOOST_TEST(c.blue.x == 0.15f);
  BOOST_TEST(c.blue.y == 0.06f);
  BOOST_TEST(c.white.x == 0.3127f);
  BOOST_TEST(c.white.y == 0.3290f);

  // Pixels of S0.550nm and G, read planar, equal the writer's interleaved input bit for bit.
  const size_t pixels = static_cast<size_t>(image.width * image.height);
  std::vector<float> s550(pixels), green(pixels);
  Imf::FrameBuffer frame;
  const IMATH_NAMESPACE::Box2i window = header.dataWindow();
  frame.insert("S0.550,000000nm", Imf::Slice::Make(Imf::FLOAT, s550.data(), window));
  frame.insert("G", Imf::Slice::Make(Imf::FLOAT, green.data(), window));
  in.setFrameBuffer(frame);
  in.readPixels(window.min.y, window.max.y);
  const size_t k550 = 17;  // 380 + 17 * 10
  bool all_equal = true;
  for (size_t p = 0; p < pixels; ++p) {
    all_equal = all_equal && std::memcmp(&s550[p], &image.spectral[p * image.n() + k550], sizeof(float)) == 0;
    all_equal = all_equal && std::memcmp(&green[p], &image.rgb[p * 3 + 1], sizeof(float)) == 0;
  }
  BOOST_TEST(all_equal);
}

BOOST_AUTO_TEST_CASE(reader_sorts_wavelengths_and_handles_other_units) {
  ScratchFolder dir;
  const TestImage image;
  // Written in descending order: the reader returns ascending wavelengths with matching values.
  std::vector<double> descending(image.wavelengths_nm.rbegin(), image.wavelengths_nm.rend());
  std::vector<float> reordered(image.spectral.size());
  const size_t n = image.n();
  for (size_t p = 0; p < reordered.size() / n; ++p)
    for (size_t k = 0; k < n; ++k) reordered[p * n + k] = image.spectral[p * n + (n - 1 - k)];
  const fs::path path = dir.path / "descending.exr";
  {
    SpectralExrWriter writer(path, image.width, image.height, descending, SpectralExrMetadata{});
    writer.write_rows(image.height, reordered.data(), image.rgb.data());
    writer.finish();
  }
  const SpectralImage back = read_spectral_exr(path);
  BOOST_TEST(back.wavelengths_nm == image.wavelengths_nm);
  BOOST_TEST(same_bits(back.spectral, image.spectral));
}

BOOST_AUTO_TEST_CASE(writer_destroyed_before_finish_leaves_nothing) {
  ScratchFolder dir;
  const TestImage image;
  {
    SpectralExrWriter writer(dir.path / "never.exr", image.width, image.height, image.wavelengths_nm,
                             SpectralExrMetadata{});
    writer.write_rows(3, image.spectral.data(), image.rgb.data());
  }
  BOOST_TEST(dir.entries().empty());
  {
    SpectralExrWriter writer(dir.path / "short.exr", image.width, image.height, image.wavelengths_nm,
                             SpectralExrMetadata{});
    writer.write_rows(3, image.spectral.data(), image.rgb.data());
    BOOST_CHECK_THROW(writer.finish(), IoError);  // rows missing
    BOOST_CHECK_THROW(writer.write_rows(image.height, image.spectral.data(), image.rgb.data()), IoError);
  }
  BOOST_TEST(dir.entries().empty());
}

BOOST_AUTO_TEST_CASE(non_finite_values_are_rejected_and_leave_no_file) {
  ScratchFolder dir;
  for (float bad : {std::nanf(""), INFINITY, -INFINITY})
    for (bool in_rgb : {false, true}) {
      TestImage image;
      (in_rgb ? image.rgb[7] : image.spectral[200]) = bad;
      const fs::path path = dir.path / "bad.exr";
      BOOST_CHECK_THROW(image.write(path, 4, SpectralExrMetadata{}), IoError);
      BOOST_TEST(dir.entries().empty());
    }
  // The message says where.
  TestImage image;
  image.spectral[image.n() * (2 * image.width + 3) + 17] = std::nanf("");
  try {
    image.write(dir.path / "bad.exr", image.height, SpectralExrMetadata{});
    BOOST_FAIL("expected IoError");
  } catch (const IoError& e) {
    const std::string what = e.what();
    BOOST_TEST(what.find("bad.exr") != std::string::npos);
    BOOST_TEST(what.find("x = 3, y = 2") != std::string::npos);
    BOOST_TEST(what.find("S0.550,000000nm") != std::string::npos);
  }
}

BOOST_AUTO_TEST_CASE(bad_arguments_are_io_errors) {
  ScratchFolder dir;
  const std::vector<double> wl{500.0, 600.0};
  BOOST_CHECK_THROW(SpectralExrWriter(dir.path / "a.exr", 0, 5, wl, {}), IoError);
  BOOST_CHECK_THROW(SpectralExrWriter(dir.path / "a.exr", 5, 5, {}, {}), IoError);
  BOOST_CHECK_THROW(SpectralExrWriter(dir.path / "a.exr", 5, 5, {500.0, 500.0000001}, {}), IoError);
  BOOST_CHECK_THROW(SpectralExrWriter(dir.path / "no/such/a.exr", 5, 5, wl, {}), IoError);
  BOOST_TEST(dir.entries().empty());
  BOOST_CHECK_THROW(read_spectral_exr(dir.path / "missing.exr"), IoError);
  std::ofstream(dir.path / "not.exr") << "not an EXR file";
  BOOST_CHECK_THROW(read_spectral_exr(dir.path / "not.exr"), IoError);
}

BOOST_AUTO_TEST_SUITE_END()

// ------------------------------------------------------------------------------------------------
// Other tools open our files: exrheader (OpenEXR) lists the spectral channels, oiiotool
// (OpenImageIO) reads the EXR and the PNG preview. Both are installed by the project's setup, so
// their absence is a failure, not a skip.
BOOST_AUTO_TEST_SUITE(external_tools)

/// Runs a shell command, stdout + stderr to a file; returns (exit status, output).
std::pair<int, std::string> run(const std::string& command, const fs::path& output) {
  const int status = std::system((command + " > '" + output.string() + "' 2>&1").c_str());
  return {status, read_all(output)};
}

BOOST_AUTO_TEST_CASE(exrheader_and_oiiotool_read_the_files) {
  ScratchFolder dir;
  const TestImage image;
  const fs::path exr = dir.path / "tools.exr";
  image.write(exr, 4, test_metadata());
  const fs::path log = dir.path / "log.txt";

  BOOST_REQUIRE_MESSAGE(run("command -v exrheader", log).first == 0, "exrheader is not installed");
  BOOST_REQUIRE_MESSAGE(run("command -v oiiotool", log).first == 0, "oiiotool is not installed");

  const auto [header_status, header_text] = run("exrheader '" + exr.string() + "'", log);
  BOOST_TEST(header_status == 0);
  BOOST_TEST(header_text.find("S0.380,000000nm, 32-bit floating-point") != std::string::npos);
  BOOST_TEST(header_text.find("S0.550,000000nm, 32-bit floating-point") != std::string::npos);
  BOOST_TEST(header_text.find("S0.780,000000nm, 32-bit floating-point") != std::string::npos);
  BOOST_TEST(header_text.find("spectralLayoutVersion") != std::string::npos);

  const auto [info_status, info_text] = run("oiiotool --info -v '" + exr.string() + "'", log);
  BOOST_TEST(info_status == 0);
  BOOST_TEST(info_text.find("44 channel") != std::string::npos, info_text);  // 41 + R, G, B
  BOOST_TEST(info_text.find("S0.550,000000nm") != std::string::npos);

  const fs::path png = dir.path / "tools.png";
  write_png_srgb8(png, image.width, image.height, image.rgb, 1.0);
  const auto [png_status, png_text] = run("oiiotool --info -v '" + png.string() + "'", log);
  BOOST_TEST(png_status == 0);
  BOOST_TEST(png_text.find("3 channel, uint8 png") != std::string::npos, png_text);
  BOOST_TEST(png_text.find("oiio:ColorSpace: \"sRGB\"") != std::string::npos, png_text);
}

BOOST_AUTO_TEST_SUITE_END()

BOOST_AUTO_TEST_SUITE_END()  // test_spectral_exr
