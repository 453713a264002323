// Uses only the installed public headers: derives a Rayleigh coefficient and renders a tiny sky.
#include <cmath>
#include <cstdio>

#include "skyspec/skyspec.hpp"

int main() {
  using namespace skyspec;
  Scene scene = default_scene();
  scene.camera.width = 8;
  scene.camera.height = 8;
  scene.render.scattering_orders = 1;
  const SpectralImageBuffer image = render_to_memory(scene);
  double sum = 0.0;
  for (float v : image.spectral) sum += v;
  std::printf("skyspec %s: %dx%d, %zu wavelengths, mean radiance %.4g W m^-2 sr^-1 nm^-1\n",
              version_string(), image.width, image.height, image.wavelengths_nm.size(),
              sum / static_cast<double>(image.spectral.size()));
  return std::isfinite(sum) && sum > 0.0 ? 0 : 1;
}
