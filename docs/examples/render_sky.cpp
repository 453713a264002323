// A first C++ program with skyspec (docs/cpp.md): a scene from a preset with typed overrides, a
// render into memory, the spectrum of the pixel at the zenith, and the files `skyspec render`
// writes (the spectral EXR, a PNG through a display of your choosing). Compiled and run against
// the installed package by the test install_consumer (tests/consumer/).
//
//   cmake -S . -B build -DCMAKE_PREFIX_PATH=<skyspec's install prefix> && cmake --build build
//   build/render_sky out/
#include <cstdio>
#include <filesystem>

#include "skyspec/skyspec.hpp"

int main(int argc, char** argv) {
  const std::filesystem::path out = argc > 1 ? argv[1] : ".";
  try {
    skyspec::SceneLoader loader("default");  // a preset (skyspec::preset_names())
    loader.apply_quality("draft");           // fewer samples; keys set after it override it
    loader.set("camera.width", 64);          // every key: docs/scene-keys.md
    loader.set("camera.height", 64);
    loader.set("sun.elevation_deg", 10.0);
    loader.set("atmosphere.mie.scattering_per_m", 2e-5);
    const skyspec::Scene scene = loader.finish();  // checks the keys together

    const skyspec::SpectralImageBuffer image = skyspec::render_to_memory(scene);
    // The default camera is a fisheye looking up: its centre pixel looks at the zenith.
    const int x = image.width / 2, y = image.height / 2;
    const float* radiance = image.spectrum(x, y);  // W m^-2 sr^-1 nm^-1, one per wavelength
    std::printf("zenith (pixel %d, %d; direction z = %.3f):\n", x, y, image.direction(x, y).z());
    for (size_t i = 0; i < image.wavelengths_nm.size(); i += 10)
      std::printf("  %5.0f nm  %.5f\n", image.wavelengths_nm[i], radiance[i]);

    skyspec::write_spectral_exr(image, out / "sky.exr");
    skyspec::DisplaySettings display;  // skyspec's OpenColorIO config unless display.config names one
    display.display = "Display P3";
    const double scale = skyspec::write_display_png(image, out / "sky.png", display);
    std::printf("wrote %s and %s (exposure scale %.4g)\n", (out / "sky.exr").c_str(), (out / "sky.png").c_str(), scale);

    loader.set("camera.width", 64.5);  // bad input: an InputError naming the key and what is allowed
  } catch (const skyspec::InputError& e) {
    std::printf("refused: %s\n", e.what());
    return 0;
  } catch (const skyspec::Error& e) {
    std::fprintf(stderr, "skyspec: %s\n", e.what());
    return 1;
  }
  return 1;  // the bad width was not refused
}
