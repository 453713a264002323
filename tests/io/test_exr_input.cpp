#include <boost/test/unit_test.hpp>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "io/exr_channels.hpp"
#include "io/exr_input.hpp"
#include "io/png_image.hpp"
#include "scratch_folder.hpp"
#include "skyspec/error.hpp"

BOOST_AUTO_TEST_SUITE(test_exr_input)

using namespace skyspec;
using skyspec::test::read_all;
using skyspec::test::ScratchFolder;
using skyspec::test::write_text;
namespace fs = std::filesystem;

namespace {

// A 16 x 8 ZIP EXR with channels R, G, B and a short string attribute.
fs::path good_exr(const ScratchFolder& dir) {
  const fs::path path = dir.path / "good.exr";
  std::vector<float> v(16 * 8, 0.25f);
  write_exr_channels(path, 16, 8, {{"R", &v}, {"G", &v}, {"B", &v}}, {{"note", "hello"}});
  return path;
}

// Where the value of attribute `name` of `type` starts (after its 4-byte size).
std::size_t value_of(const std::string& file, const std::string& name, const std::string& type) {
  const std::string key = name + std::string(1, '\0') + type + std::string(1, '\0');
  const std::size_t at = file.find(key);
  BOOST_REQUIRE(at != std::string::npos);
  return at + key.size() + 4;
}

void put_int(std::string& file, std::size_t at, std::int32_t v) { std::memcpy(&file[at], &v, 4); }

std::string error_of(const fs::path& path) {
  try {
    check_exr_declared_sizes(path);
  } catch (const IoError& e) {
    return e.what();
  }
  return {};
}

}  // namespace

BOOST_AUTO_TEST_CASE(a_good_file_passes_and_reads) {
  ScratchFolder dir;
  const fs::path path = good_exr(dir);
  BOOST_TEST(error_of(path).empty());
  BOOST_TEST(read_exr_channels(path, {"R"}).width == 16);
}

BOOST_AUTO_TEST_CASE(an_attribute_larger_than_the_file_is_refused_before_reading) {
  ScratchFolder dir;
  std::string bytes = read_all(good_exr(dir));
  put_int(bytes, value_of(bytes, "note", "string") - 4, 2000000000);
  write_text(dir.path / "bad.exr", bytes);
  BOOST_TEST(
      error_of(dir.path / "bad.exr").find("attribute \"note\" declares 2000000000 bytes, more than the file holds") !=
      std::string::npos);
  BOOST_CHECK_THROW(read_exr_channels(dir.path / "bad.exr", {"R"}), IoError);
}

BOOST_AUTO_TEST_CASE(pixels_the_chunks_cannot_hold_are_refused) {
  ScratchFolder dir;
  std::string bytes = read_all(good_exr(dir));
  const std::size_t window = value_of(bytes, "dataWindow", "box2i");
  put_int(bytes, window + 8, 7999);
  put_int(bytes, window + 12, 7999);
  write_text(dir.path / "big.exr", bytes);
  BOOST_TEST(error_of(dir.path / "big.exr").find("it declares 8000 x 8000 pixels") != std::string::npos);
  // The bound is the compression's: ZIP can expand 1100 times at most.
  BOOST_TEST(exr_max_compression_ratio(3 /* ZIP */) == 1100.0);
  BOOST_TEST(exr_max_compression_ratio(0 /* none */) == 1.0);
}

BOOST_AUTO_TEST_CASE(an_offset_outside_the_file_is_refused) {
  ScratchFolder dir;
  std::string bytes = read_all(good_exr(dir));
  // The offset table follows the header's final 0 byte, after its last attribute (OpenEXR writes
  // them sorted by name): 8 rows of ZIP (16 lines per chunk) are one chunk.
  const std::size_t table = value_of(bytes, "screenWindowWidth", "float") + 4 + 1;
  std::string far_bytes = bytes, zero_bytes = bytes, size_bytes = bytes;
  const std::int64_t far = 1 << 30, zero = 0;
  std::memcpy(&far_bytes[table], &far, 8);
  write_text(dir.path / "offset.exr", far_bytes);
  BOOST_TEST(error_of(dir.path / "offset.exr").find("points outside the file") != std::string::npos);
  // An unfinished file (offset 0): OpenEXR would rebuild the table from the chunks' sizes.
  std::memcpy(&zero_bytes[table], &zero, 8);
  write_text(dir.path / "zero.exr", zero_bytes);
  BOOST_TEST(error_of(dir.path / "zero.exr").find("its offset table is incomplete") != std::string::npos);
  // A chunk whose declared data size exceeds the file (OpenEXR allocates that size).
  std::int64_t chunk = 0;
  std::memcpy(&chunk, &bytes[table], 8);
  put_int(size_bytes, static_cast<std::size_t>(chunk) + 4, 1600000000);
  write_text(dir.path / "size.exr", size_bytes);
  BOOST_TEST(error_of(dir.path / "size.exr").find("declares 1600000000 bytes of data") != std::string::npos);
}

BOOST_AUTO_TEST_CASE(uint_channels_folders_and_other_files_are_refused) {
  ScratchFolder dir;
  std::string bytes = read_all(good_exr(dir));
  const std::size_t channels = value_of(bytes, "channels", "chlist");
  put_int(bytes, channels + 2, 0);  // "B\0" then the type: UINT
  write_text(dir.path / "uint.exr", bytes);
  BOOST_TEST(error_of(dir.path / "uint.exr").empty());  // a legal file...
  try {
    read_exr_channels(dir.path / "uint.exr", {"B"});  // ...whose B is not light
    BOOST_FAIL("UINT accepted");
  } catch (const IoError& e) {
    BOOST_TEST(std::string(e.what()).find("channel B holds UINT samples") != std::string::npos);
  }
  BOOST_TEST(error_of(dir.path).find("it is a folder") != std::string::npos);
  write_text(dir.path / "text.exr", "not an image");
  BOOST_TEST(error_of(dir.path / "text.exr").find("magic number") != std::string::npos);
}

BOOST_AUTO_TEST_CASE(pixel_verification_decodes_every_chunk) {
  ScratchFolder dir;
  const fs::path path = good_exr(dir);
  BOOST_CHECK_NO_THROW(verify_exr_pixels(path));
  const std::string bytes = read_all(path);
  write_text(dir.path / "cut.exr", bytes.substr(0, bytes.size() - 40));
  BOOST_CHECK_THROW(verify_exr_pixels(dir.path / "cut.exr"), IoError);
}

BOOST_AUTO_TEST_CASE(png_verification_reads_every_row_and_the_text) {
  ScratchFolder dir;
  const fs::path png = dir.path / "a.png";
  write_png_display(png, 8, 4, std::vector<float>(8 * 4 * 3, 0.5f), 8, PngColourTag::Srgb,
                    {{"skyspec:scene", "x = 1"}});
  BOOST_TEST(read_png_text_verified(png).at("skyspec:scene") == "x = 1");
  std::string bytes = read_all(png);
  write_text(dir.path / "cut.png", bytes.substr(0, bytes.size() - 20));
  BOOST_CHECK_THROW(read_png_text_verified(dir.path / "cut.png"), IoError);
  bytes[bytes.find("IDAT") + 6] ^= 0x55;  // a flipped byte in the image data: its CRC fails
  write_text(dir.path / "flipped.png", bytes);
  BOOST_CHECK_THROW(read_png_text_verified(dir.path / "flipped.png"), IoError);
}

BOOST_AUTO_TEST_SUITE_END()
