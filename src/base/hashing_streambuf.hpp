// Stream buffers that hash (FNV-1a 64, base/embedded_data.hpp) the bytes passing through them, so
// that a large file can be checksummed as it is written or read, without a copy of it in memory
// (the scattering-order table cache, transport/multiple_scattering.cpp).
#pragma once

#include <cstdint>
#include <streambuf>
#include <string_view>

#include "base/embedded_data.hpp"

namespace skyspec {

/// Passes what is written on to another stream buffer and hashes it on the way.
class HashingStreambuf final : public std::streambuf {
 public:
  explicit HashingStreambuf(std::streambuf* out) : out_(out) {}
  std::uint64_t hash() const { return hash_; }

 protected:
  std::streamsize xsputn(const char* s, std::streamsize n) override {
    hash_ = fnv1a64(std::string_view(s, static_cast<size_t>(n)), hash_);
    return out_->sputn(s, n);
  }
  int_type overflow(int_type c) override {
    if (traits_type::eq_int_type(c, traits_type::eof())) return traits_type::not_eof(c);
    const char ch = traits_type::to_char_type(c);
    return xsputn(&ch, 1) == 1 ? c : traits_type::eof();
  }

 private:
  std::streambuf* out_;
  std::uint64_t hash_ = kFnv1a64Basis;
};

/// Passes on what is read from another stream buffer, unbuffered, and hashes it on the way: the
/// bytes after the last one taken (a checksum that follows, say) stay unread in the other buffer.
class HashingInStreambuf final : public std::streambuf {
 public:
  explicit HashingInStreambuf(std::streambuf* in) : in_(in) {}
  std::uint64_t hash() const { return hash_; }

 protected:
  int_type underflow() override { return in_->sgetc(); }
  int_type uflow() override {
    const int_type c = in_->sbumpc();
    if (!traits_type::eq_int_type(c, traits_type::eof())) {
      const char ch = traits_type::to_char_type(c);
      hash_ = fnv1a64(std::string_view(&ch, 1), hash_);
    }
    return c;
  }
  std::streamsize xsgetn(char* s, std::streamsize n) override {
    const std::streamsize got = in_->sgetn(s, n);
    hash_ = fnv1a64(std::string_view(s, static_cast<size_t>(got)), hash_);
    return got;
  }

 private:
  std::streambuf* in_;
  std::uint64_t hash_ = kFnv1a64Basis;
};
}  // namespace skyspec
