#include "physics/particle_optics_cache.hpp"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <mutex>
#include <string_view>
#include <system_error>

#include "base/atomic_file.hpp"
#include "base/disk_cache.hpp"
#include "base/embedded_data.hpp"
#include "skyspec/units.hpp"

namespace skyspec {

namespace {
// The cache file: "skyspec-aerosol\n", the key's length and text, the sizes, the raw sums
// (scattering, extinction, then a1, b1, a3, b2 per wavelength: what compute() hands to the
// TabulatedScatteringMatrix, so that a loaded file gives bit for bit the optics just computed),
// and the FNV-1a 64 hash of everything before it. Host byte order, with a marker.
constexpr char kMagic[] = "skyspec-aerosol\n";
constexpr std::uint32_t kByteOrder = 0x01020304u;

template <typename T>
void put(std::string& out, const T& v) {
  out.append(reinterpret_cast<const char*>(&v), sizeof v);
}
template <typename T>
bool get(const std::string& in, size_t& at, T& v) {
  if (in.size() - at < sizeof v) return false;
  std::memcpy(&v, in.data() + at, sizeof v);
  at += sizeof v;
  return true;
}

std::string serialise(const std::string& key, const RawParticleOptics& r) {
  std::string out(kMagic);
  put(out, kByteOrder);
  put(out, static_cast<std::uint64_t>(key.size()));
  out += key;
  const auto n = static_cast<std::uint32_t>(r.sca.size());
  const auto m = static_cast<std::uint32_t>(r.a1.empty() ? 0 : r.a1[0].size());
  put(out, n);
  put(out, m);
  for (const auto* v : {&r.sca, &r.ext})
    for (double x : *v) put(out, x);
  for (const auto* rows : {&r.a1, &r.b1, &r.a3, &r.b2})
    for (const auto& row : *rows)
      for (double x : row) put(out, x);
  put(out, fnv1a64(out));
  return out;
}

// A file read back is untrusted: every size is checked against the key's and the file's, the
// checksum must hold and every value be finite; anything else is "not cached".
bool deserialise(const std::string& in, const std::string& key, size_t n_expected, size_t m_expected,
                 RawParticleOptics& r) {
  const std::string magic(kMagic);
  if (in.size() < magic.size() + sizeof(std::uint64_t) || in.compare(0, magic.size(), magic) != 0) return false;
  std::uint64_t stored = 0;
  std::memcpy(&stored, in.data() + in.size() - sizeof stored, sizeof stored);
  if (fnv1a64(std::string_view(in.data(), in.size() - sizeof stored)) != stored) return false;
  size_t at = magic.size();
  std::uint32_t order = 0, n = 0, m = 0;
  std::uint64_t key_size = 0;
  if (!get(in, at, order) || order != kByteOrder || !get(in, at, key_size) || key_size != key.size()) return false;
  if (in.size() - at < key_size || in.compare(at, key_size, key) != 0) return false;
  at += key_size;
  if (!get(in, at, n) || !get(in, at, m) || n != n_expected || m != m_expected) return false;
  const size_t values = 2 * static_cast<size_t>(n) + 4 * static_cast<size_t>(n) * m;
  if (in.size() - at != values * sizeof(double) + sizeof stored) return false;
  auto read = [&](std::vector<double>& v, size_t count) {
    v.resize(count);
    for (double& x : v)
      if (!get(in, at, x) || !std::isfinite(x)) return false;
    return true;
  };
  if (!read(r.sca, n) || !read(r.ext, n)) return false;
  for (auto* rows : {&r.a1, &r.b1, &r.a3, &r.b2}) {
    rows->resize(n);
    for (auto& row : *rows)
      if (!read(row, m)) return false;
  }
  return true;
}

AerosolMixtureOptics from_raw(RawParticleOptics r, const std::vector<double>& mu) {
  AerosolMixtureOptics o;
  const int n = static_cast<int>(r.sca.size());
  o.scattering_per_m = Eigen::Map<const SpectrumD>(r.sca.data(), n);
  o.extinction_per_m = Eigen::Map<const SpectrumD>(r.ext.data(), n);
  o.matrix = std::make_shared<const TabulatedScatteringMatrix>(mu, std::move(r.a1), std::move(r.b1), std::move(r.a3),
                                                               std::move(r.b2));
  return o;
}

AerosolMixtureOptics load_or_compute(const std::string& key, int wavelengths, const std::vector<double>& mu,
                                     bool use_disk_cache, const std::function<RawParticleOptics()>& compute) {
  const std::filesystem::path dir = use_disk_cache ? table_cache_directory() : std::filesystem::path();
  std::filesystem::path path;
  if (!dir.empty()) {
    char name[48];
    std::snprintf(name, sizeof name, "aerosol-%016llx.bin", static_cast<unsigned long long>(fnv1a64(key)));
    path = dir / name;
  }
  const std::uint64_t cap = path.empty() ? 0 : table_cache_cap_bytes();  // a bad value: refused before any work
  // Only a regular file of exactly the size this key's optics take is read (a file read back is
  // untrusted: never read a huge one whole).
  const size_t values = static_cast<size_t>(wavelengths) * (2 + 4 * mu.size());
  const std::uintmax_t expected = sizeof(kMagic) - 1 + sizeof(kByteOrder) + sizeof(std::uint64_t) + key.size() +
                                  2 * sizeof(std::uint32_t) + values * sizeof(double) + sizeof(std::uint64_t);
  const auto load = [&](RawParticleOptics& raw) {
    std::error_code size_error;
    if (path.empty() || !is_regular_input(path) || std::filesystem::file_size(path, size_error) != expected ||
        size_error)
      return false;
    std::ifstream in(path, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (!(in.good() || in.eof()) || !deserialise(bytes, key, static_cast<size_t>(wavelengths), mu.size(), raw))
      return false;
    mark_cache_file_used(path);
    return true;
  };
  if (RawParticleOptics raw; load(raw)) return from_raw(std::move(raw), mu);
  // Computed by one process at a time: another that is computing these optics now is waited for.
  const CacheFileClaim claim(path.empty() || !usable_cache_directory(dir) ? std::filesystem::path() : path);
  if (RawParticleOptics raw; claim.waited() && load(raw)) return from_raw(std::move(raw), mu);
  RawParticleOptics raw = compute();
  if (!path.empty() && usable_cache_directory(dir)) {
    try {
      write_file_atomically(path, serialise(key, raw));
      evict_table_cache(dir, cap, path);
    } catch (const std::exception&) {
      warn_cache_unusable(dir, "the aerosol file could not be written");
    }
  }
  return from_raw(std::move(raw), mu);
}
}  // namespace

AerosolMixtureOptics cached_particle_optics(const std::string& key, int wavelengths, const std::vector<double>& mu,
                                            bool use_disk_cache, const std::function<RawParticleOptics()>& compute) {
  static std::mutex mutex;
  static std::map<std::string, AerosolMixtureOptics> cache;
  {
    std::lock_guard<std::mutex> lock(mutex);
    const auto it = cache.find(key);
    if (it != cache.end()) return it->second;
  }
  AerosolMixtureOptics o = load_or_compute(key, wavelengths, mu, use_disk_cache, compute);
  std::lock_guard<std::mutex> lock(mutex);
  if (cache.size() > 16) cache.clear();  // a bound for long-lived processes (the viewer, Python)
  return cache.emplace(key, std::move(o)).first->second;
}

std::vector<double> cosines_of_degrees(const std::vector<double>& degrees) {
  std::vector<double> mu;
  for (auto it = degrees.rbegin(); it != degrees.rend(); ++it) mu.push_back(std::cos(*it * kPi / 180.0));
  mu.front() = -1.0;
  mu.back() = 1.0;
  return mu;
}

std::vector<double> node_densities(const std::vector<double>& share, const std::vector<double>& mu) {
  std::vector<double> density(share.size()), at_nodes(mu.size());
  for (size_t k = 0; k < density.size(); ++k) density[k] = share[k] / (2.0 * kPi * (mu[k + 1] - mu[k]));
  for (size_t k = 0; k < mu.size(); ++k) {
    const double below = k > 0 ? density[k - 1] : density[k], above = k < density.size() ? density[k] : below;
    at_nodes[k] = 0.5 * (below + above);
  }
  return at_nodes;
}

void append_sphere_optics(RawParticleOptics& o, double sca, double ext, const std::vector<SphereScatteringMatrix>& p) {
  o.sca.push_back(sca);
  o.ext.push_back(ext);
  std::vector<double> a1(p.size()), b1(p.size()), a3(p.size()), b2(p.size());
  for (size_t k = 0; k < p.size(); ++k) {
    a1[k] = sca * p[k].s11;
    b1[k] = sca * p[k].s12;
    a3[k] = sca * p[k].s33;
    b2[k] = sca * p[k].s34;
  }
  o.a1.push_back(std::move(a1));
  o.b1.push_back(std::move(b1));
  o.a3.push_back(std::move(a3));
  o.b2.push_back(std::move(b2));
}

RawParticleOptics optics_from_shares(const std::vector<std::vector<double>>& shares, const std::vector<double>& mu) {
  RawParticleOptics o;
  o.sca.assign(shares.size(), 1.0);
  o.ext.assign(shares.size(), 1.0);
  for (const std::vector<double>& share : shares) {
    std::vector<double> a1 = node_densities(share, mu);
    o.a1.push_back(a1);
    o.a3.push_back(std::move(a1));
    o.b1.emplace_back(mu.size(), 0.0);
    o.b2.emplace_back(mu.size(), 0.0);
  }
  return o;
}

}  // namespace skyspec
