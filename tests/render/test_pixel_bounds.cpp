// Pixel bounds (render_window, parse_pixel_bounds): a tile's pixels are exactly the whole image's
// pixels at those places (every bit: merged tiles must give the whole render's file), and the
// bounds' text and range are checked with the flag named.
#include <boost/test/unit_test.hpp>

#include <cstring>
#include <string>
#include <vector>

#include "check_helpers.hpp"
#include "scene_fixtures.hpp"
#include "skyspec/error.hpp"
#include "skyspec/render.hpp"

BOOST_AUTO_TEST_SUITE(test_pixel_bounds)

using namespace skyspec;

BOOST_AUTO_TEST_CASE(a_window_holds_the_whole_images_values_bit_for_bit) {
  // A fisheye (pixels outside its circle too), a sun in the image, the sky-view table and a march.
  for (const char* table : {"true", "false"}) {
    const Scene s = test::scene_with(std::string("[camera]\nwidth = 41\nheight = 29\n[sun]\nelevation_deg = 60\n"
                                                 "[render]\nscattering_orders = 1\nsky_view_table = ") +
                                     table + "\n");
    const SkyRenderer r(s);
    const int w = r.width(), h = r.height(), n = r.grid().size();
    std::vector<float> spectral(static_cast<size_t>(w) * h * n), rgb(static_cast<size_t>(w) * h * 3);
    r.render_rows(0, h, spectral.data(), rgb.data());
    for (const PixelBounds b : {PixelBounds{0, 41, 0, 29}, PixelBounds{3, 17, 5, 6}, PixelBounds{40, 41, 0, 29},
                                PixelBounds{10, 35, 12, 29}}) {
      const int ww = b.x1 - b.x0, rows = b.y1 - b.y0;
      std::vector<float> ts(static_cast<size_t>(ww) * rows * n), trgb(static_cast<size_t>(ww) * rows * 3);
      r.render_window(b.x0, b.x1, b.y0, rows, ts.data(), trgb.data());
      bool same = true;
      for (int y = 0; y < rows; ++y)
        for (int x = 0; x < ww; ++x) {
          const size_t whole = static_cast<size_t>(b.y0 + y) * w + b.x0 + x, tile = static_cast<size_t>(y) * ww + x;
          same &= std::memcmp(&spectral[whole * n], &ts[tile * n], sizeof(float) * n) == 0;
          same &= std::memcmp(&rgb[whole * 3], &trgb[tile * 3], sizeof(float) * 3) == 0;
        }
      BOOST_TEST(same, "window " << b.x0 << "," << b.x1 << "," << b.y0 << "," << b.y1);
    }
    std::vector<float> one(static_cast<size_t>(n) * 2), one_rgb(6);
    BOOST_CHECK_THROW(r.render_window(40, 42, 0, 1, one.data(), one_rgb.data()), Error);
  }
}

BOOST_AUTO_TEST_CASE(bounds_text_and_range) {
  const PixelBounds b = parse_pixel_bounds("0,512,128,256", "--pixel-bounds");
  BOOST_TEST(b.x0 == 0);
  BOOST_TEST(b.x1 == 512);
  BOOST_TEST(b.y0 == 128);
  BOOST_TEST(b.y1 == 256);
  for (const char* bad : {"0,512,128", "0,512,128,256,1", "a,1,2,3", "0,-1,2,3", "", "1,2,3,4x"})
    BOOST_TEST(test::error_setting([&] { parse_pixel_bounds(bad, "--pixel-bounds"); }) == "--pixel-bounds", bad);
  CameraSpec camera;
  camera.width = 100;
  camera.height = 50;
  check_pixel_bounds({0, 100, 0, 50}, camera, "--pixel-bounds");
  for (const PixelBounds bad : {PixelBounds{0, 101, 0, 50}, PixelBounds{5, 5, 0, 50}, PixelBounds{0, 100, 30, 20}})
    BOOST_TEST(test::error_setting([&] { check_pixel_bounds(bad, camera, "--pixel-bounds"); }) == "--pixel-bounds");
}

BOOST_AUTO_TEST_SUITE_END()
