#include "skyspec/camera.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "skyspec/units.hpp"

namespace skyspec {

bool FisheyeCamera::direction(double x, double y, Vec3& dir) const {
  const double u = 2.0 * x / width_ - 1.0, v = 2.0 * y / height_ - 1.0;
  const double z2 = u * u + v * v;
  if (z2 > 1.0) return false;
  // Equal-area: cos(theta) = 1 - z^2, azimuth phi = atan2(v, u). Then sin(theta) = z sqrt(2 - z^2)
  // and (cos phi, sin phi) = (u, v) / z, so the direction needs neither the angle nor its sine
  // and cosine: (sin theta cos phi, sin theta sin phi) = sqrt(2 - z^2) (u, v).
  const double s = std::sqrt(2.0 - z2);
  // The tutorial's frame (x east, y up, z south) in east-north-up.
  dir = Vec3(s * u, -s * v, 1.0 - z2);
  return true;
}

namespace {
// The smallest d . u over the unit vectors d with d_z >= s (a cap about the z axis, down to
// elevation asin s): -1 if it holds -u; otherwise on its rim, where d = (sqrt(1 - s^2) h, s)
// for a horizontal unit h, at h opposite to u's horizontal part.
double lowest_cosine_over_cap(const Vec3& u, double s) {
  if (-u.z() >= s) return -1.0;
  return s * u.z() - std::sqrt(std::max(0.0, 1.0 - s * s)) * std::hypot(u.x(), u.y());
}
}  // namespace

std::optional<double> FisheyeCamera::lowest_cosine_to(const Vec3& u) const { return lowest_cosine_over_cap(u, 0.0); }

std::optional<double> EquirectangularCamera::lowest_cosine_to(const Vec3& u) const {
  return lowest_cosine_over_cap(u, std::sin(degrees_to_radians(min_elevation_deg_)));
}

std::string FisheyeCamera::describe() const {
  std::ostringstream s;
  s << "fisheye (upward, equal-area, 180 deg), " << width_ << "x" << height_;
  return s.str();
}

PerspectiveCamera::PerspectiveCamera(int width, int height, Vec3 origin_m, const Vec3& look_at_m,
                                     double vertical_fov_deg)
    : Camera(width, height, std::move(origin_m)), fov_deg_(vertical_fov_deg) {
  forward_ = (look_at_m - origin_m_).normalized();
  Vec3 up_hint = origin_m_.normalized();                                    // local zenith at the camera
  if (std::abs(forward_.dot(up_hint)) > 0.999999) up_hint = Vec3(0, 1, 0);  // looking straight up/down
  right_ = forward_.cross(up_hint).normalized();
  up_ = right_.cross(forward_);
  tan_half_fov_ = std::tan(degrees_to_radians(vertical_fov_deg) * 0.5);
}

bool PerspectiveCamera::direction(double x, double y, Vec3& dir) const {
  const double aspect = static_cast<double>(width_) / height_;
  const double sx = (2.0 * x / width_ - 1.0) * tan_half_fov_ * aspect;
  const double sy = (1.0 - 2.0 * y / height_) * tan_half_fov_;
  dir = (forward_ + sx * right_ + sy * up_).normalized();
  return true;
}

std::string PerspectiveCamera::describe() const {
  std::ostringstream s;
  s << "perspective, vertical field of view " << fov_deg_ << " deg, " << width_ << "x" << height_;
  return s.str();
}

EquirectangularCamera::EquirectangularCamera(int width, int height, Vec3 origin_m, double min_elevation_deg,
                                             PanoramaConvention convention)
    : Camera(width, height, std::move(origin_m)), min_elevation_deg_(min_elevation_deg), convention_(convention) {
  if (!(min_elevation_deg >= -90.0 && min_elevation_deg < 90.0))
    throw std::invalid_argument("EquirectangularCamera: min_elevation_deg must be in [-90, 90)");
  if (convention != PanoramaConvention::Skyspec && min_elevation_deg != -90.0)
    throw std::invalid_argument(
        "EquirectangularCamera: the blender and openexr conventions cover the whole sphere "
        "(min_elevation_deg = -90)");
  if (convention == PanoramaConvention::OpenExr && (width < 2 || height < 2))
    throw std::invalid_argument("EquirectangularCamera: the openexr convention needs at least 2 x 2 pixels");
  for (int i = 0; i < width; ++i) {
    double azimuth_deg, elevation_deg;
    angles(i + 0.5, 0.5, azimuth_deg, elevation_deg);
    sin_azimuth_.push_back(std::sin(degrees_to_radians(azimuth_deg)));
    cos_azimuth_.push_back(std::cos(degrees_to_radians(azimuth_deg)));
  }
  for (int j = 0; j < height; ++j) {
    double azimuth_deg, elevation_deg;
    angles(0.5, j + 0.5, azimuth_deg, elevation_deg);
    const double el = degrees_to_radians(std::clamp(elevation_deg, -90.0, 90.0));
    sin_elevation_.push_back(std::sin(el));
    cos_elevation_.push_back(std::cos(el));
  }
}

void EquirectangularCamera::angles(double x, double y, double& azimuth_deg, double& elevation_deg) const {
  switch (convention_) {
    case PanoramaConvention::Skyspec:
      azimuth_deg = 360.0 * x / width_;
      elevation_deg = 90.0 - (90.0 - min_elevation_deg_) * y / height_;
      return;
    case PanoramaConvention::Blender:  // u = x / width = 1/4 + azimuth / 360; v = 1 - y / height
      azimuth_deg = 360.0 * x / width_ - 90.0;
      elevation_deg = 90.0 - 180.0 * y / height_;
      return;
    case PanoramaConvention::OpenExr: {  // pixel i's centre is x = i + 1/2
      const double longitude_deg = 180.0 - 360.0 * (x - 0.5) / (width_ - 1);
      azimuth_deg = 180.0 - longitude_deg;
      elevation_deg = 90.0 - 180.0 * (y - 0.5) / (height_ - 1);
      return;
    }
  }
}

bool EquirectangularCamera::direction(double x, double y, Vec3& dir) const {
  // A pixel's centre: direction_from_angles's products of the sines and cosines computed once.
  const double column = x - 0.5, row = y - 0.5;
  if (column >= 0.0 && column < width_ && row >= 0.0 && row < height_ && column == std::floor(column) &&
      row == std::floor(row)) {
    const auto i = static_cast<size_t>(column), j = static_cast<size_t>(row);
    dir = Vec3(cos_elevation_[j] * sin_azimuth_[i], cos_elevation_[j] * cos_azimuth_[i], sin_elevation_[j]);
    return true;
  }
  double azimuth_deg, elevation_deg;
  angles(x, y, azimuth_deg, elevation_deg);
  // OpenEXR's first and last rows are the poles' centres; points beyond them (x, y outside the
  // pixel centres) stay on the sphere.
  dir = direction_from_angles(azimuth_deg, std::clamp(elevation_deg, -90.0, 90.0));
  return true;
}

std::string EquirectangularCamera::describe() const {
  std::ostringstream s;
  s << "equirectangular (latitude-longitude, ";
  if (min_elevation_deg_ == -90.0)
    s << "full sphere";
  else if (min_elevation_deg_ == 0.0)
    s << "upper hemisphere";
  else
    s << "elevation 90 down to " << min_elevation_deg_ << " deg";
  s << ", " << panorama_convention_name(convention_) << " convention), " << width_ << "x" << height_;
  return s.str();
}

}  // namespace skyspec
