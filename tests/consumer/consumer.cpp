// Uses only the installed public headers: renders a tiny sky into memory, writes it through a
// display pipeline of its own choosing (display, view, a manual exposure: skyspec/display.hpp),
// and checks that a wrong view is an InputError naming its neutral setting id.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include "skyspec/skyspec.hpp"

int main(int argc, char** argv) {
  using namespace skyspec;
  const std::filesystem::path out = argc > 1 ? argv[1] : ".";
  Scene scene = default_scene();
  scene.camera.width = 8;
  scene.camera.height = 8;
  scene.render.scattering_orders = 1;
  const SpectralImageBuffer image = render_to_memory(scene);
  double sum = 0.0;
  for (float v : image.spectral) sum += v;
  std::printf("skyspec %s: %dx%d, %zu wavelengths, mean radiance %.4g W m^-2 sr^-1 nm^-1\n", version_string(),
              image.width, image.height, image.wavelengths_nm.size(), sum / static_cast<double>(image.spectral.size()));
  if (!(std::isfinite(sum) && sum > 0.0)) return 1;

  DisplaySettings display;
  display.display = "Display P3";
  display.view = "ACES 1.0 - SDR Video";
  display.exposure.mode = ExposureSettings::Mode::Manual;
  display.exposure.ev = -8.0;
  display.png_bit_depth = 16;
  const double scale = write_display_png(image, out / "consumer.png", display);
  std::printf("wrote %s (Display P3, ACES 1.0 - SDR Video, 16 bits), exposure scale %.6g\n",
              (out / "consumer.png").string().c_str(), scale);
  if (std::abs(scale - std::exp2(-8.0)) > 1e-12 || !std::filesystem::exists(out / "consumer.png")) return 1;

  display.view = "Filmic";
  try {
    write_display_png(image, out / "never.png", display);
    return 1;
  } catch (const InputError& e) {
    std::printf("refused: %s\n", e.what());
    if (e.setting() != display_setting::kView || std::filesystem::exists(out / "never.png")) return 1;
  }
  return 0;
}
