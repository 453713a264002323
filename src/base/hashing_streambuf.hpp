// Stream buffers that hash (SHA-256, base/sha256.hpp) the bytes passing through them, so that a
// large file can be checksummed as it is written or read, without a copy of it in memory (the
// scattering-order table cache, transport/multiple_scattering.cpp). The checksum is the digest's
// first 64 bits.
#pragma once

#include <cstdint>
#include <streambuf>

#include "base/sha256.hpp"

namespace skyspec {

/// Passes what is written on to another stream buffer and hashes it on the way.
class HashingStreambuf final : public std::streambuf {
 public:
  explicit HashingStreambuf(std::streambuf* out) : out_(out) {}
  /// The checksum of everything written; ends the hashing.
  std::uint64_t hash() { return sha_.first_64_bits(); }

 protected:
  std::streamsize xsputn(const char* s, std::streamsize n) override {
    sha_.update(s, static_cast<size_t>(n));
    return out_->sputn(s, n);
  }
  int_type overflow(int_type c) override {
    if (traits_type::eq_int_type(c, traits_type::eof())) return traits_type::not_eof(c);
    const char ch = traits_type::to_char_type(c);
    return xsputn(&ch, 1) == 1 ? c : traits_type::eof();
  }

 private:
  std::streambuf* out_;
  Sha256 sha_;
};

/// Passes on what is read from another stream buffer, unbuffered, and hashes it on the way: the
/// bytes after the last one taken (a checksum that follows, say) stay unread in the other buffer.
class HashingInStreambuf final : public std::streambuf {
 public:
  explicit HashingInStreambuf(std::streambuf* in) : in_(in) {}
  /// The checksum of everything taken; ends the hashing.
  std::uint64_t hash() { return sha_.first_64_bits(); }

 protected:
  int_type underflow() override { return in_->sgetc(); }
  int_type uflow() override {
    const int_type c = in_->sbumpc();
    if (!traits_type::eq_int_type(c, traits_type::eof())) {
      const char ch = traits_type::to_char_type(c);
      sha_.update(&ch, 1);
    }
    return c;
  }
  std::streamsize xsgetn(char* s, std::streamsize n) override {
    const std::streamsize got = in_->sgetn(s, n);
    if (got > 0) sha_.update(s, static_cast<size_t>(got));
    return got;
  }

 private:
  std::streambuf* in_;
  Sha256 sha_;
};
}  // namespace skyspec
