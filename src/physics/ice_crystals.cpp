#include "skyspec/ice_crystals.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <string>

#include <Eigen/Geometry>

#include "base/csv_table.hpp"
#include "base/embedded_data.hpp"
#include "base/text_format.hpp"
#include "skyspec/error.hpp"
#include "skyspec/units.hpp"
#include "skyspec/vec3.hpp"

namespace skyspec {

namespace {
struct IndexTable {
  std::vector<double> nm, n;
};

const IndexTable& index_table() {
  static const IndexTable table = [] {
    const std::string_view file = "ice/warren_brandt2008.csv";
    IndexTable t;
    for (const CsvRow& row : parse_csv(file, embedded_file(file), {"wavelength_um", "n", "k"})) {
      t.nm.push_back(1000.0 * csv_number(file, row, 0));
      t.n.push_back(csv_number(file, row, 1));
    }
    return t;
  }();
  return table;
}
}  // namespace

double ice_refractive_index(double nm, const char* setting) {
  const IndexTable& t = index_table();
  if (!(nm >= t.nm.front() && nm <= t.nm.back()))
    throw InputError(setting, format_number(nm) + " nm",
                     "wavelengths from " + format_number(t.nm.front()) + " to " + format_number(t.nm.back()) +
                         " nm (the refractive index of ice as skyspec carries it, Warren & Brandt 2008)");
  const size_t k = std::min<size_t>(static_cast<size_t>(std::upper_bound(t.nm.begin(), t.nm.end(), nm) - t.nm.begin()),
                                    t.nm.size() - 1);
  const double w = (nm - t.nm[k - 1]) / (t.nm[k] - t.nm[k - 1]);
  return t.n[k - 1] + w * (t.n[k] - t.n[k - 1]);
}

double prism_minimum_deviation(double n, double apex_rad) {
  return 2.0 * std::asin(n * std::sin(0.5 * apex_rad)) - apex_rad;
}

namespace {
// The prism as the intersection of 8 half-spaces n . x <= h: six side faces (outward normals every
// 60 degrees about the c axis z, at the apothem) and two basal faces (z = +-L/2).
struct Prism {
  std::array<Vec3, 8> normal;
  std::array<double, 8> offset;
  double bound_radius;  // of a sphere about the centre that holds it
  explicit Prism(double aspect_ratio) {
    const double side = 1.0, length = 2.0 * side * aspect_ratio, apothem = side * std::sqrt(3.0) / 2.0;
    for (int k = 0; k < 6; ++k) {
      const double a = k * kPi / 3.0;
      normal[static_cast<size_t>(k)] = Vec3(std::cos(a), std::sin(a), 0.0);
      offset[static_cast<size_t>(k)] = apothem;
    }
    normal[6] = Vec3(0.0, 0.0, 1.0);
    normal[7] = Vec3(0.0, 0.0, -1.0);
    offset[6] = offset[7] = 0.5 * length;
    bound_radius = std::hypot(side, 0.5 * length);
  }
  // A ray from outside: the distance to where it enters and the face, or false if it misses.
  bool enter(const Vec3& o, const Vec3& d, double& t, int& face) const {
    double t_in = -1e300, t_out = 1e300;
    face = -1;
    for (int k = 0; k < 8; ++k) {
      const double denom = normal[static_cast<size_t>(k)].dot(d);
      const double num = offset[static_cast<size_t>(k)] - normal[static_cast<size_t>(k)].dot(o);
      if (denom < 0.0) {
        if (num / denom > t_in) {
          t_in = num / denom;
          face = k;
        }
      } else if (denom > 0.0) {
        t_out = std::min(t_out, num / denom);
      } else if (num < 0.0) {
        return false;
      }
    }
    t = t_in;
    return face >= 0 && t_in <= t_out;
  }
  // A ray inside: the distance to the face it leaves through.
  double leave(const Vec3& o, const Vec3& d, int& face) const {
    double t_out = 1e300;
    face = -1;
    for (int k = 0; k < 8; ++k) {
      const double denom = normal[static_cast<size_t>(k)].dot(d);
      if (denom > 1e-12) {
        const double t = (offset[static_cast<size_t>(k)] - normal[static_cast<size_t>(k)].dot(o)) / denom;
        if (t < t_out) {
          t_out = t;
          face = k;
        }
      }
    }
    return t_out;
  }
};

// Fresnel reflectance of unpolarised light from index n1 into n2 at incidence cosine cos_i (> 0);
// 1 beyond the critical angle. cos_t: the refracted ray's cosine.
double fresnel_reflectance(double n1, double n2, double cos_i, double& cos_t) {
  const double sin_t2 = (n1 / n2) * (n1 / n2) * (1.0 - cos_i * cos_i);
  if (sin_t2 >= 1.0) return 1.0;
  cos_t = std::sqrt(1.0 - sin_t2);
  const double rs = (n1 * cos_i - n2 * cos_t) / (n1 * cos_i + n2 * cos_t);
  const double rp = (n2 * cos_i - n1 * cos_t) / (n2 * cos_i + n1 * cos_t);
  return 0.5 * (rs * rs + rp * rp);
}

// d reflected about a face of normal m.
Vec3 reflect(const Vec3& d, const Vec3& m) { return d - 2.0 * d.dot(m) * m; }
// d refracted through a face whose normal m points back against d (m . d < 0), eta = n1 / n2.
Vec3 refract(const Vec3& d, const Vec3& m, double eta, double cos_i, double cos_t) {
  return eta * d + (eta * cos_i - cos_t) * m;
}

struct Uniform {
  std::mt19937_64 engine;
  explicit Uniform(std::uint64_t seed) : engine(seed) {}
  double operator()() { return static_cast<double>(engine() >> 11) * 0x1.0p-53; }
};
}  // namespace

PrismScattering hexagonal_prism_scattering(const HexagonalPrism& shape, double n, const std::vector<double>& mu,
                                           long long rays, std::uint64_t seed) {
  if (!(shape.aspect_ratio > 0.0) || !(n > 1.0) || mu.size() < 2 || mu.front() != -1.0 || mu.back() != 1.0)
    throw Error("hexagonal_prism_scattering: needs an aspect ratio > 0, an index > 1 and cosines from -1 to 1");
  const Prism prism(shape.aspect_ratio);
  Uniform u(seed);
  PrismScattering out;
  out.share.assign(mu.size() - 1, 0.0);
  const auto score = [&](const Vec3& d_in, const Vec3& d_out) {
    const double c = std::clamp(d_in.dot(d_out), -1.0, 1.0);
    const size_t k =
        std::min(static_cast<size_t>(std::upper_bound(mu.begin(), mu.end(), c) - mu.begin()), mu.size() - 1) - 1;
    out.share[k] += 1.0;
  };
  while (out.rays < rays) {
    // A random orientation of the prism is a direction of incidence uniform over the sphere in the
    // prism's frame; the entry point is uniform over a disk across it that covers the prism.
    const double z = 2.0 * u() - 1.0, phi = 2.0 * kPi * u();
    const double s = std::sqrt(std::max(0.0, 1.0 - z * z));
    const Vec3 d0(s * std::cos(phi), s * std::sin(phi), z);
    const Vec3 e1 = (std::abs(d0.x()) < 0.9 ? Vec3(1.0, 0.0, 0.0) : Vec3(0.0, 1.0, 0.0)).cross(d0).normalized();
    const Vec3 e2 = d0.cross(e1);
    const double r = prism.bound_radius * std::sqrt(u()), a = 2.0 * kPi * u();
    Vec3 o = r * std::cos(a) * e1 + r * std::sin(a) * e2 - 2.0 * prism.bound_radius * d0;
    double t = 0.0;
    int face = -1;
    if (!prism.enter(o, d0, t, face)) continue;  // missed: not a ray of this orientation's cross-section
    ++out.rays;
    const Vec3& m = prism.normal[static_cast<size_t>(face)];
    double cos_t = 0.0;
    const double cos_i = -m.dot(d0);
    if (u() < fresnel_reflectance(1.0, n, cos_i, cos_t)) {  // reflected off the outside
      score(d0, reflect(d0, m));
      continue;
    }
    Vec3 d = refract(d0, m, 1.0 / n, cos_i, cos_t);
    o = o + t * d0;
    bool left = false;
    for (int hit = 0; hit < PrismScattering::kMaxInteractions && !left; ++hit) {
      const double step = prism.leave(o, d, face);
      o = o + step * d;
      const Vec3& out_normal = prism.normal[static_cast<size_t>(face)];
      const double c = out_normal.dot(d);
      if (u() < fresnel_reflectance(n, 1.0, c, cos_t)) {
        d = reflect(d, out_normal);
      } else {
        score(d0, refract(d, -out_normal, n, c, cos_t).normalized());
        left = true;
      }
    }
    if (!left) ++out.lost;
  }
  for (double& v : out.share) v /= static_cast<double>(out.rays);
  return out;
}

}  // namespace skyspec
