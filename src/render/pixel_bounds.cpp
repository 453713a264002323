// Pixel bounds (pbrt's --pixelbounds): a tile of the camera's image, rendered on its own.
#include <cstdlib>
#include <string>

#include "skyspec/error.hpp"
#include "skyspec/render.hpp"

namespace skyspec {

PixelBounds parse_pixel_bounds(const std::string& text, const std::string& setting) {
  const std::string allowed = "x0,x1,y0,y1: whole numbers, columns x0 to x1 - 1 and rows y0 to y1 - 1 (pbrt's order)";
  int v[4];
  std::size_t pos = 0;
  for (int k = 0; k < 4; ++k) {
    const std::size_t end = k < 3 ? text.find(',', pos) : text.size();
    if (end == std::string::npos) throw InputError(setting, "\"" + text + "\"", allowed);
    const std::string item = text.substr(pos, end - pos);
    char* stop = nullptr;
    const long x = std::strtol(item.c_str(), &stop, 10);
    if (item.empty() || *stop || x < 0 || x > 65536) throw InputError(setting, "\"" + text + "\"", allowed);
    v[k] = static_cast<int>(x);
    pos = end + 1;
  }
  return {v[0], v[1], v[2], v[3]};
}

void check_pixel_bounds(const PixelBounds& b, const CameraSpec& camera, const std::string& setting) {
  if (0 <= b.x0 && b.x0 < b.x1 && b.x1 <= camera.width && 0 <= b.y0 && b.y0 < b.y1 && b.y1 <= camera.height) return;
  throw InputError(
      setting,
      std::to_string(b.x0) + "," + std::to_string(b.x1) + "," + std::to_string(b.y0) + "," + std::to_string(b.y1),
      "0 <= x0 < x1 <= " + std::to_string(camera.width) + " and 0 <= y0 < y1 <= " + std::to_string(camera.height) +
          " (the camera's image)");
}

}  // namespace skyspec
