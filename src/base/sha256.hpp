// SHA-256 of files, for the checksums of job outputs (the manifest, resume, merge): the digest
// anyone can recompute with `sha256sum` or Python's hashlib. Computed by OpenSSL's libcrypto.
#pragma once

#include <filesystem>
#include <string>

namespace skyspec {

/// The SHA-256 of a file's bytes as 64 lowercase hex digits; throws IoError if it cannot be read.
std::string sha256_file_hex(const std::filesystem::path& path);
/// The SHA-256 of bytes, the same way.
std::string sha256_hex(const std::string& bytes);

}  // namespace skyspec
