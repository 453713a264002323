#include "base/sha256.hpp"

#include <openssl/evp.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>

#include "skyspec/error.hpp"

namespace skyspec {

Sha256::Sha256() : ctx_(EVP_MD_CTX_new()) {
  if (!ctx_ || EVP_DigestInit_ex(static_cast<EVP_MD_CTX*>(ctx_), EVP_sha256(), nullptr) != 1) {
    EVP_MD_CTX_free(static_cast<EVP_MD_CTX*>(ctx_));
    throw Error("SHA-256: OpenSSL digest unavailable");
  }
}

Sha256::~Sha256() { EVP_MD_CTX_free(static_cast<EVP_MD_CTX*>(ctx_)); }

void Sha256::update(const void* data, std::size_t n) {
  if (finished_) throw Error("SHA-256: update after the digest");
  if (n > 0 && EVP_DigestUpdate(static_cast<EVP_MD_CTX*>(ctx_), data, n) != 1)
    throw Error("SHA-256: digest update failed");
}

void Sha256::finish() {
  if (finished_) return;
  unsigned int len = 0;
  if (EVP_DigestFinal_ex(static_cast<EVP_MD_CTX*>(ctx_), digest_, &len) != 1 || len != sizeof digest_)
    throw Error("SHA-256: digest failed");
  finished_ = true;
}

std::uint64_t Sha256::first_64_bits() {
  finish();
  std::uint64_t v = 0;
  for (int i = 0; i < 8; ++i) v = (v << 8) | digest_[i];
  return v;
}

std::string Sha256::hex() {
  finish();
  static const char* digits = "0123456789abcdef";
  std::string out(2 * sizeof digest_, '0');
  for (std::size_t i = 0; i < sizeof digest_; ++i) {
    out[2 * i] = digits[digest_[i] >> 4];
    out[2 * i + 1] = digits[digest_[i] & 15];
  }
  return out;
}

std::string sha256_file_hex(const std::filesystem::path& path) {
  std::unique_ptr<FILE, int (*)(FILE*)> f(std::fopen(path.c_str(), "rb"), &std::fclose);
  if (!f) throw IoError("cannot read " + path.string() + ": " + std::strerror(errno));
  Sha256 d;
  char buf[1 << 16];
  std::size_t n;
  while ((n = std::fread(buf, 1, sizeof buf, f.get())) > 0) d.update(buf, n);
  if (std::ferror(f.get())) throw IoError("cannot read " + path.string());
  return d.hex();
}

std::string sha256_hex(const std::string& bytes) {
  Sha256 d;
  d.update(bytes.data(), bytes.size());
  return d.hex();
}

}  // namespace skyspec
