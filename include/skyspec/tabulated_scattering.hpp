// A scattering matrix tabulated per wavelength at cosines of the scattering angle: what Lorenz-Mie
// theory over a size distribution gives (sphere_ensemble.hpp), in the form the renderer, the
// scattering-order tables and the Monte Carlo use. For randomly oriented spheres the matrix has four
// independent elements (Bohren & Huffman 1983, eq. 4.77; the block form of
// physics/scattering_matrix.hpp with a2 = a1, a4 = a3):
//
//   a1 = P11 (the phase function, sr^-1), b1 = P12, a3 = P33, b2 = P34.
//
// Between the tabulated cosines every element is linear in mu. That interpolant IS the phase
// function here: it is normalised so that 2 pi integral a1 dmu = 1 exactly (the trapezoidal rule
// is exact for it), the Monte Carlo samples it exactly (a linear density on each interval), and
// the renderer evaluates it, so that both see the same function. How fine the cosines must be is
// the caller's choice (aerosol_components.hpp states its grid and what it misses).
#pragma once

#include <cstddef>
#include <memory>
#include <vector>

namespace skyspec {

/// The elements of one scattering matrix (sr^-1), Bohren & Huffman's convention: b1 < 0 where
/// scattered unpolarised light is polarised perpendicular to the scattering plane.
struct SphereMatrixElements {
  double a1 = 0.0, b1 = 0.0, a3 = 0.0, b2 = 0.0;
};

class TabulatedScatteringMatrix {
 public:
  /// mu: strictly increasing from -1 to 1. a1, b1, a3, b2: [wavelength][mu] (rows of mu.size()),
  /// any positive scale per wavelength (a1 > 0 somewhere); each wavelength's four rows are scaled
  /// together so that its a1 integrates to 1. Throws std::invalid_argument otherwise.
  TabulatedScatteringMatrix(std::vector<double> mu, std::vector<std::vector<double>> a1,
                            std::vector<std::vector<double>> b1, std::vector<std::vector<double>> a3,
                            std::vector<std::vector<double>> b2);

  int wavelengths() const { return static_cast<int>(a1_.size()); }
  const std::vector<double>& mu() const { return mu_; }
  /// Where mu lies: the interval [k, k + 1] of the table and the weight of node k + 1.
  struct Position {
    int k = 0;
    double w = 0.0;
  };
  Position locate(double mu) const;
  /// The phase function a1 of wavelength i at mu (sr^-1).
  double phase(int i, double mu) const { return phase(i, locate(mu)); }
  double phase(int i, Position p) const { return lerp(a1_[static_cast<std::size_t>(i)], p); }
  /// b1 (P12) of wavelength i at a located cosine.
  double b1(int i, Position p) const { return lerp(b1_[static_cast<std::size_t>(i)], p); }
  SphereMatrixElements elements(int i, double mu) const;
  /// The means of a1 and of b1 over the cosines from lo to hi (lo <= hi; the value at lo when they
  /// coincide), exact for the interpolant, for every wavelength, times `weight`, added to
  /// out[0 .. wavelengths()): what a direction of a coarse quadrature stands for when the
  /// directions about it see scattering angles over that range.
  void add_mean_phases(Position lo, Position hi, double weight, float* out) const {
    add_means(a1_by_node_, a1_integral_, lo, hi, weight, out);
  }
  void add_mean_b1s(Position lo, Position hi, double weight, float* out) const {
    add_means(b1_by_node_, b1_integral_, lo, hi, weight, out);
  }
  /// The asymmetry parameter g = 2 pi integral a1 mu dmu of wavelength i (exact for the interpolant).
  double asymmetry(int i) const { return g_[static_cast<std::size_t>(i)]; }
  /// A cosine drawn from a1 of wavelength i given u uniform in [0, 1): exact inversion of the
  /// piecewise-linear density.
  double sample_mu(int i, double u) const;
  /// The table's rows, for hashing (a1 normalised; then b1, a3, b2).
  const std::vector<std::vector<double>>& a1() const { return a1_; }
  const std::vector<std::vector<double>>& b1() const { return b1_; }
  const std::vector<std::vector<double>>& a3() const { return a3_; }
  const std::vector<std::vector<double>>& b2() const { return b2_; }

 private:
  double lerp(const std::vector<double>& row, Position p) const {
    return row[static_cast<std::size_t>(p.k)] * (1.0 - p.w) + row[static_cast<std::size_t>(p.k) + 1] * p.w;
  }
  double cosine(Position p) const {
    return mu_[static_cast<std::size_t>(p.k)] * (1.0 - p.w) + mu_[static_cast<std::size_t>(p.k) + 1] * p.w;
  }
  /// Means from an element by node ([node][wavelength]) and its integrals from -1 to each node.
  void add_means(const std::vector<double>& by_node, const std::vector<double>& integrals, Position lo, Position hi,
                 double weight, float* out) const;
  std::vector<double> mu_;
  std::vector<std::vector<double>> a1_, b1_, a3_, b2_;
  std::vector<std::vector<double>> cdf_;  // [wavelength][node]: probability of mu below the node
  // [node][wavelength] (contiguous in the wavelength): a1 and b1, and their integrals from -1 to the node
  std::vector<double> a1_by_node_, b1_by_node_, a1_integral_, b1_integral_;
  std::vector<double> g_;
};

/// A matrix with its forward peak cut off, and the share of scattered light the cut took away.
struct TruncatedScatteringMatrix {
  std::shared_ptr<const TabulatedScatteringMatrix> matrix;
  /// Per wavelength: f = the share of the phase function's integral inside the cone that the cut
  /// removed (0 <= f < 1).
  std::vector<double> removed;
};

/// The forward peak of `m` cut flat inside the cone of scattering angles below cone_rad (Potter
/// 1970's truncation, the delta-M idea of Wiscombe 1977 with the peak taken out of the table rather
/// than out of its Legendre series): inside the cone a1 takes its value at the cone's edge, and b1,
/// a3 and b2 keep their ratio to a1 at each angle (the light's polarisation is unchanged); the
/// cone's edge becomes a node of the table (the function is unchanged outside the cone). The cut
/// share f of each wavelength is what radiative transfer then treats as unscattered light: the
/// scattering coefficient becomes (1 - f) beta_sca, the extinction beta_ext - f beta_sca, and the
/// phase function the returned matrix, renormalised. Throws std::invalid_argument unless
/// 0 < cone_rad < pi.
TruncatedScatteringMatrix truncate_forward_peak(const TabulatedScatteringMatrix& m, double cone_rad);

}  // namespace skyspec
