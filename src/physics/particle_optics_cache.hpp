// Particle optics from Lorenz-Mie theory are slow to compute (seconds to a minute per atmosphere)
// and depend only on their inputs: they are kept in memory per key, and, when asked, in the disk
// cache of tables (base/disk_cache.hpp), as files "aerosol-<hash>.bin" that a loaded render reads
// bit for bit as computed. Used by the OPAC aerosol (aerosol_components.cpp) and by media of
// water drops (media/fog.cpp).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "skyspec/aerosol_components.hpp"
#include "skyspec/lorenz_mie.hpp"

namespace skyspec {

/// Optics as computed: volume coefficients per wavelength and the scattering matrix's rows at the
/// medium's cosines (aerosol_scattering_cosines() for spheres) before TabulatedScatteringMatrix
/// normalises them.
struct RawParticleOptics {
  std::vector<double> sca, ext;
  std::vector<std::vector<double>> a1, b1, a3, b2;
};

/// Cosines of scattering angles given in degrees, ascending from 0 to 180: ascending cosines from
/// -1 to 1 (the ends exact), as tabulated scattering functions take them.
std::vector<double> cosines_of_degrees(const std::vector<double>& degrees);

/// Optics per unit of extinction of particles that only scatter (scattering = extinction = 1) from
/// the shares of their light in each interval of the cosines (shares[wavelength][interval]): the
/// phase function's rows, each interval's share over its solid angle, a node the mean of the two
/// intervals beside it; intensity only (b1 = b2 = 0, a3 = a1).
RawParticleOptics optics_from_shares(const std::vector<std::vector<double>>& shares, const std::vector<double>& mu);
/// Appends one wavelength of spheres' optics: the coefficients and the rows sca * P_ij at the nodes
/// (P the normalised matrix, sphere_ensemble.hpp).
void append_sphere_optics(RawParticleOptics& o, double sca, double ext, const std::vector<SphereScatteringMatrix>& p);
/// One row of those: an element's shares in each interval of mu as values at the nodes.
std::vector<double> node_densities(const std::vector<double>& share, const std::vector<double>& mu);

/// The optics of `key` (text naming everything they depend on, the format included): from memory,
/// else from the disk cache when use_disk_cache (a file read back is untrusted: its size, key,
/// checksum and values are checked), else compute() (then written to the cache). `wavelengths`:
/// the grid's size, which a cached file must have.
AerosolMixtureOptics cached_particle_optics(const std::string& key, int wavelengths, const std::vector<double>& mu,
                                            bool use_disk_cache, const std::function<RawParticleOptics()>& compute);

}  // namespace skyspec
