// Natraj, Li & Yung (2009)'s corrected Coulson-Dave-Sekera tables (tests/data/natraj2009: the
// files, their source and conventions): the grid and a reader, for the tests that compare skyspec's
// vector transport with them (test_natraj_tables: the renderer; test_monte_carlo_polarisation:
// the Monte Carlo).
#pragma once

#include <array>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace skyspec::test {

/// The tables' grid: sun zenith cosines mu0, relative azimuths phi (0: the line of sight towards
/// the sun's azimuth), the ground albedos of the three blocks, and 16 view zenith cosines (read
/// from the rows).
inline constexpr std::array<double, 7> kNatrajSunCosines = {0.1, 0.2, 0.4, 0.6, 0.8, 0.92, 1.0};
inline constexpr std::array<double, 7> kNatrajAzimuthsDeg = {0, 30, 60, 90, 120, 150, 180};
inline constexpr std::array<double, 3> kNatrajAlbedos = {0.0, 0.25, 0.8};
inline constexpr int kNatrajViewCosines = 16;

/// One file ({I,Q,U}_{UP,DN}_TAU_t): rows[albedo][sun * 16 + view] = {mu0, mu, values at the 7 phi}.
struct NatrajTable {
  std::array<std::vector<std::array<double, 9>>, 3> rows;
  const std::array<double, 9>& row(int albedo, int sun, int view) const {
    return rows.at(static_cast<size_t>(albedo)).at(static_cast<size_t>(sun * kNatrajViewCosines + view));
  }
};

/// Reads a file as the authors wrote it (header lines, "albedo = ..." lines, rows of 9 numbers);
/// std::runtime_error when it cannot be read or does not hold 3 blocks of 112 rows.
inline NatrajTable read_natraj_table(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + path);
  NatrajTable t;
  std::string line;
  int block = -1;
  while (std::getline(in, line)) {
    if (line.find("albedo") != std::string::npos) {
      ++block;
      continue;
    }
    std::istringstream s(line);
    std::array<double, 9> r{};
    int n = 0;
    while (n < 9 && s >> r[static_cast<size_t>(n)]) ++n;
    if (n == 9 && block >= 0 && block < 3) t.rows[static_cast<size_t>(block)].push_back(r);
  }
  for (const auto& b : t.rows)
    if (b.size() != kNatrajSunCosines.size() * kNatrajViewCosines)
      throw std::runtime_error(path + ": not 3 blocks of 112 rows");
  return t;
}

}  // namespace skyspec::test
