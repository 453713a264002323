// SHA-256 of files, for the checksums of job outputs (the manifest, resume, merge): the digest
// anyone can recompute with `sha256sum` or Python's hashlib; and of streams, for the integrity of
// the table caches (base/hashing_streambuf.hpp). Computed by OpenSSL's libcrypto, which uses the
// CPU's SHA instructions where it has them.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>

namespace skyspec {

/// SHA-256 of bytes given piece by piece.
class Sha256 {
 public:
  Sha256();
  ~Sha256();
  Sha256(const Sha256&) = delete;
  Sha256& operator=(const Sha256&) = delete;
  void update(const void* data, std::size_t n);
  /// The digest's first 8 bytes, big-endian, as a number (a checksum); ends the hashing (later
  /// calls return the same value, update() is then an error).
  std::uint64_t first_64_bits();
  /// The digest as 64 lowercase hex digits; ends the hashing as first_64_bits does.
  std::string hex();

 private:
  void finish();
  void* ctx_;
  unsigned char digest_[32] = {};
  bool finished_ = false;
};

/// The SHA-256 of a file's bytes as 64 lowercase hex digits; throws IoError if it cannot be read.
std::string sha256_file_hex(const std::filesystem::path& path);
/// The SHA-256 of bytes, the same way.
std::string sha256_hex(const std::string& bytes);

}  // namespace skyspec
