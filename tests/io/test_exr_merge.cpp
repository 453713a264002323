// Tiles merged (io/exr_merge.hpp): tiles of an image written with data windows, in any layout,
// merge into the bytes of the whole image written at once; tiles that overlap, leave a gap, belong
// to another image or hold a non-finite value are refused with the tile named, and leave no file.
#include <boost/test/unit_test.hpp>

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfIntAttribute.h>
#include <ImfOutputFile.h>

#include <array>
#include <cmath>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "io/exr_merge.hpp"
#include "io/spectral_exr.hpp"
#include "scratch_folder.hpp"
#include "skyspec/error.hpp"

BOOST_AUTO_TEST_SUITE(test_exr_merge)

using namespace skyspec;
using skyspec::test::read_all;
using skyspec::test::ScratchFolder;

namespace {

constexpr int kWidth = 37, kHeight = 71;
const std::vector<double> kWavelengths = {400, 500, 600, 700};

struct Image {
  std::vector<float> spectral, rgb;
};

Image random_image(unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<float> value(0.0f, 30.0f);
  Image im;
  im.spectral.resize(static_cast<size_t>(kWidth) * kHeight * kWavelengths.size());
  im.rgb.resize(static_cast<size_t>(kWidth) * kHeight * 3);
  for (auto& v : im.spectral) v = value(random);
  for (auto& v : im.rgb) v = value(random);
  return im;
}

SpectralExrMetadata metadata(const std::string& compression, bool half) {
  SpectralExrMetadata meta;
  meta.compression = compression;
  meta.half_spectral = half;
  meta.strings["skyspec:scene"] = "[camera]\nwidth = 37\n";
  meta.doubles["skyspec:exposureScale"] = 0.25;
  return meta;
}

// The tile [x0, x1) x [y0, y1) of the image, written as the renderer writes one.
void write_tile(const std::filesystem::path& path, const Image& im, std::array<int, 4> w, SpectralExrMetadata meta) {
  meta.data_window = w;
  const auto [x0, x1, y0, y1] = w;
  const size_t n = kWavelengths.size();
  std::vector<float> spectral, rgb;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) {
      const size_t p = static_cast<size_t>(y) * kWidth + x;
      spectral.insert(spectral.end(), im.spectral.begin() + static_cast<long>(p * n),
                      im.spectral.begin() + static_cast<long>((p + 1) * n));
      rgb.insert(rgb.end(), im.rgb.begin() + static_cast<long>(p * 3), im.rgb.begin() + static_cast<long>(p * 3 + 3));
    }
  SpectralExrWriter writer(path, kWidth, kHeight, kWavelengths, meta);
  writer.write_rows(y1 - y0, spectral.data(), rgb.data());
  writer.finish();
}

std::string error_of(const std::vector<std::filesystem::path>& tiles, const std::filesystem::path& out) {
  try {
    merge_spectral_exr_tiles(tiles, out);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

// A tile rewritten by OpenEXR itself (skyspec's writer would refuse what the tests plant): `header`
// changes its header (a channel it adds reads as zeros), `pixels` its channels' values, one plane
// per channel in the header's order.
void rewrite_with_openexr(const std::filesystem::path& from, const std::filesystem::path& to,
                          const std::function<void(Imf::Header&)>& header,
                          const std::function<void(std::vector<std::vector<float>>&)>& pixels = {}) {
  Imf::InputFile in(from.c_str());
  Imf::Header h = in.header();
  if (header) header(h);
  const auto w = h.dataWindow();
  const int width = w.max.x - w.min.x + 1, rows = w.max.y - w.min.y + 1;
  std::vector<std::vector<float>> planes;
  Imf::FrameBuffer frame;
  for (auto c = h.channels().begin(); c != h.channels().end(); ++c) {
    planes.emplace_back(static_cast<size_t>(width) * rows);
    frame.insert(c.name(), Imf::Slice::Make(Imf::FLOAT, planes.back().data(), w, sizeof(float), sizeof(float) * width));
  }
  in.setFrameBuffer(frame);
  in.readPixels(w.min.y, w.max.y);
  if (pixels) pixels(planes);
  Imf::OutputFile out(to.c_str(), h);
  out.setFrameBuffer(frame);
  out.writePixels(rows);
}

}  // namespace

BOOST_AUTO_TEST_CASE(tiles_in_any_layout_merge_into_the_bytes_of_the_whole_image) {
  const Image im = random_image(7);
  // Strips, a grid with uneven cuts, one-pixel slivers, and a single tile that is the image.
  const std::vector<std::vector<std::array<int, 4>>> layouts = {
      {{0, kWidth, 0, 20}, {0, kWidth, 20, 21}, {0, kWidth, 21, kHeight}},
      {{0, 10, 0, 33}, {10, kWidth, 0, 33}, {0, 30, 33, kHeight}, {30, kWidth, 33, kHeight}},
      {{0, 1, 0, kHeight}, {1, kWidth, 0, 1}, {1, kWidth, 1, kHeight}},
      {{0, kWidth, 0, kHeight}},
  };
  for (const auto& [compression, half] :
       std::vector<std::pair<std::string, bool>>{{"piz", false}, {"zip", false}, {"none", false}, {"piz", true}}) {
    ScratchFolder dir("merge");
    const SpectralExrMetadata meta = metadata(compression, half);
    {
      SpectralExrWriter whole(dir.path / "whole.exr", kWidth, kHeight, kWavelengths, meta);
      whole.write_rows(kHeight, im.spectral.data(), im.rgb.data());
      whole.finish();
    }
    for (std::size_t l = 0; l < layouts.size(); ++l) {
      std::vector<std::filesystem::path> tiles;
      for (std::size_t t = 0; t < layouts[l].size(); ++t) {
        tiles.push_back(dir.path / ("tile" + std::to_string(l) + "_" + std::to_string(t) + ".exr"));
        write_tile(tiles.back(), im, layouts[l][t], meta);
      }
      std::reverse(tiles.begin(), tiles.end());  // the order given does not matter
      const auto out = dir.path / ("merged" + std::to_string(l) + ".exr");
      const MergeSummary m = merge_spectral_exr_tiles(tiles, out);
      BOOST_TEST(m.tiles == static_cast<int>(tiles.size()));
      BOOST_TEST(m.width == kWidth);
      BOOST_TEST(m.height == kHeight);
      BOOST_TEST((read_all(out) == read_all(dir.path / "whole.exr")),
                 compression << (half ? " half" : "") << " layout " << l);
    }
  }
}

BOOST_AUTO_TEST_CASE(tiles_that_do_not_make_one_image_are_refused_by_name) {
  ScratchFolder dir("merge-bad");
  const Image im = random_image(8);
  const SpectralExrMetadata meta = metadata("piz", false);
  const auto tile = [&](const std::string& name, std::array<int, 4> w, SpectralExrMetadata m) {
    write_tile(dir.path / name, im, w, m);
    return dir.path / name;
  };
  const auto top = tile("top.exr", {0, kWidth, 0, 40}, meta);
  const auto bottom = tile("bottom.exr", {0, kWidth, 40, kHeight}, meta);
  const auto overlapping = tile("overlapping.exr", {0, kWidth, 39, kHeight}, meta);
  const auto short_bottom = tile("short.exr", {0, kWidth, 41, kHeight}, meta);
  SpectralExrMetadata other_scene = meta;
  other_scene.strings["skyspec:scene"] = "[camera]\nwidth = 38\n";
  const auto foreign = tile("foreign.exr", {0, kWidth, 40, kHeight}, other_scene);
  const auto zipped = tile("zipped.exr", {0, kWidth, 40, kHeight}, metadata("zip", false));
  const auto out = dir.path / "out.exr";
  std::string e = error_of({top, overlapping}, out);
  BOOST_TEST(e.find("overlapping.exr") != std::string::npos, e);
  BOOST_TEST(e.find("y 39..39") != std::string::npos, e);
  e = error_of({top, short_bottom}, out);
  BOOST_TEST(e.find("37 pixel(s) are in no tile") != std::string::npos, e);
  e = error_of({top, foreign}, out);
  BOOST_TEST(e.find("foreign.exr") != std::string::npos, e);
  BOOST_TEST(e.find("skyspec:scene differs") != std::string::npos, e);
  e = error_of({top, zipped}, out);
  BOOST_TEST(e.find("compression differs") != std::string::npos, e);
  e = error_of({top, dir.path / "missing.exr"}, out);
  BOOST_TEST(e.find("missing.exr") != std::string::npos, e);
  BOOST_TEST(!std::filesystem::exists(out));
  BOOST_TEST(dir.entries().size() == 6u);  // no temporary left behind
  BOOST_TEST(error_of({top, bottom}, out).empty());
}

BOOST_AUTO_TEST_CASE(a_tile_with_a_non_finite_value_is_refused) {
  ScratchFolder dir("merge-nan");
  const Image im = random_image(9);
  const SpectralExrMetadata meta = metadata("none", false);
  const auto top = dir.path / "top.exr";
  write_tile(top, im, {0, kWidth, 0, 40}, meta);
  write_tile(dir.path / "bottom.exr", im, {0, kWidth, 40, kHeight}, meta);
  // The bottom tile rewritten by OpenEXR itself with one NaN (skyspec's writer refuses to write one).
  const auto bad = dir.path / "nan.exr";
  rewrite_with_openexr(dir.path / "bottom.exr", bad, {},
                       [](std::vector<std::vector<float>>& planes) { planes[1][17] = std::nanf(""); });
  const auto out = dir.path / "out.exr";
  const std::string e = error_of({top, bad}, out);
  BOOST_TEST(e.find("not finite") != std::string::npos, e);
  BOOST_TEST(!std::filesystem::exists(out));
}

// The merged file is written by the render's own writer, from what the tiles' header says: tiles
// whose header that writer would not have written (an attribute of a type it does not write, a
// channel other than S0-S3 and R, G, B) are refused, naming what is foreign, and leave no file.
BOOST_AUTO_TEST_CASE(tiles_skyspec_would_not_have_written_are_refused_by_name) {
  ScratchFolder dir("merge-foreign");
  const Image im = random_image(10);
  const SpectralExrMetadata meta = metadata("piz", false);
  const auto top = dir.path / "top.exr", bottom = dir.path / "bottom.exr";
  write_tile(top, im, {0, kWidth, 0, 40}, meta);
  write_tile(bottom, im, {0, kWidth, 40, kHeight}, meta);
  const auto out = dir.path / "out.exr";
  const auto with_int = [](Imf::Header& h) { h.insert("studio:shot", Imf::IntAttribute(42)); };
  rewrite_with_openexr(top, dir.path / "top-int.exr", with_int);
  rewrite_with_openexr(bottom, dir.path / "bottom-int.exr", with_int);
  std::string e = error_of({dir.path / "top-int.exr", dir.path / "bottom-int.exr"}, out);
  BOOST_TEST(e.find("its attribute studio:shot is of type int, which skyspec does not write") != std::string::npos, e);
  const auto with_alpha = [](Imf::Header& h) { h.channels().insert("A", Imf::Channel(Imf::FLOAT)); };
  rewrite_with_openexr(top, dir.path / "top-a.exr", with_alpha);
  rewrite_with_openexr(bottom, dir.path / "bottom-a.exr", with_alpha);
  e = error_of({dir.path / "top-a.exr", dir.path / "bottom-a.exr"}, out);
  BOOST_TEST(e.find("it has a channel A") != std::string::npos, e);
  BOOST_TEST(!std::filesystem::exists(out));
  // The tiles as skyspec wrote them merge.
  BOOST_TEST(error_of({top, bottom}, out).empty());
}

BOOST_AUTO_TEST_SUITE_END()
