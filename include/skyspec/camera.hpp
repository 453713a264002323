// Cameras: map a pixel to a view ray.
//
// Frames: world space is planet-centred. The local frame at the scene's reference point (the
// point on the planet's surface below the origin of camera coordinates) is east-north-up, with the
// planet's centre at (0, 0, -R): a camera position (e, n, h) in scene coordinates is the world
// point (e, n, R + h). Directions are given as azimuth (degrees clockwise from north, so 90 = east)
// and elevation (degrees above the local horizontal).
// Pixel (0, 0) is the top-left corner of the image; pixel centres sit at half-integers.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "skyspec/camera_spec.hpp"
#include "skyspec/geometry.hpp"

namespace skyspec {

class Camera {
 public:
  virtual ~Camera() = default;
  int width() const { return width_; }
  int height() const { return height_; }
  /// World-space origin of all rays (pinhole cameras).
  const Vec3& origin_m() const { return origin_m_; }
  /// The ray through image point (x, y) in pixels; false if the point maps to no direction
  /// (outside the fisheye circle).
  virtual bool direction(double x, double y, Vec3& dir) const = 0;
  virtual std::string describe() const = 0;
  /// The smallest dir . u over every direction the camera's image spans (u a unit vector), where
  /// that has a closed form (a bound for the pixels' own directions); empty where it has not
  /// (perspective): callers then look at the pixels.
  virtual std::optional<double> lowest_cosine_to(const Vec3& u) const {
    (void)u;
    return std::nullopt;
  }

 protected:
  Camera(int width, int height, Vec3 origin_m) : width_(width), height_(height), origin_m_(std::move(origin_m)) {}
  int width_, height_;
  Vec3 origin_m_;
};

/// The seed tutorial's upward fisheye: image point (x, y) in [-1, 1]^2 (x right, y down), zenith
/// angle theta = acos(1 - x^2 - y^2) (so the horizon is the unit circle: an equal-area,
/// 180-degree view), azimuth phi = atan2(y, x) measured from east towards south in the image,
/// i.e. the image shows the sky as if seen from above with north at the top and east on the right,
/// as in the tutorial.
class FisheyeCamera : public Camera {
 public:
  FisheyeCamera(int width, int height, Vec3 origin_m) : Camera(width, height, std::move(origin_m)) {}
  bool direction(double x, double y, Vec3& dir) const override;
  std::string describe() const override;
  /// Its directions are the upper hemisphere of the east-north-up frame.
  std::optional<double> lowest_cosine_to(const Vec3& u) const override;
};

/// A pinhole camera looking from origin towards a target, with a vertical field of view; "up" is
/// the local zenith (or north when looking straight up or down).
class PerspectiveCamera : public Camera {
 public:
  PerspectiveCamera(int width, int height, Vec3 origin_m, const Vec3& look_at_m, double vertical_fov_deg);
  bool direction(double x, double y, Vec3& dir) const override;
  std::string describe() const override;

 private:
  Vec3 forward_, right_, up_;
  double tan_half_fov_;
  double fov_deg_;
};

/// Latitude-longitude panorama (the HDRI format renderers load): column -> azimuth, row ->
/// elevation linearly from +90 (top) down to min_elevation_deg (bottom): -90 for the whole sphere
/// of directions, 0 for the upper hemisphere (a sky-dome texture; skyspec's convention only).
class EquirectangularCamera : public Camera {
 public:
  EquirectangularCamera(int width, int height, Vec3 origin_m, double min_elevation_deg = -90.0,
                        PanoramaConvention convention = PanoramaConvention::Skyspec);
  bool direction(double x, double y, Vec3& dir) const override;
  std::string describe() const override;
  /// Its directions are those at or above min_elevation_deg in the east-north-up frame.
  std::optional<double> lowest_cosine_to(const Vec3& u) const override;
  /// Azimuth (degrees clockwise from north) and elevation (degrees) of image point (x, y).
  void angles(double x, double y, double& azimuth_deg, double& elevation_deg) const;

 private:
  double min_elevation_deg_;
  PanoramaConvention convention_;
  // At the pixels' centres, the sines and cosines direction() takes: of each column's azimuth and
  // of each row's elevation (computed once; the same values as for any other point).
  std::vector<double> sin_azimuth_, cos_azimuth_, sin_elevation_, cos_elevation_;
};

}  // namespace skyspec
