// A zero-filled float array whose memory the system hands out already zeroed on first use
// (calloc: fresh pages for large sizes), so that allocating a large table costs no time until it
// is filled, and a long computation that fills it can stop (cancellation.hpp) before touching it.
#pragma once

#include <cstddef>
#include <cstdlib>
#include <memory>
#include <new>
#include <utility>

namespace skyspec {

class ZeroedFloats {
 public:
  explicit ZeroedFloats(std::size_t n = 0)
      : p_(n ? static_cast<float*>(std::calloc(n, sizeof(float))) : nullptr), n_(n) {
    if (n && !p_) throw std::bad_alloc();
  }
  float* data() { return p_.get(); }
  const float* data() const { return p_.get(); }
  std::size_t size() const { return n_; }
  float& operator[](std::size_t i) { return p_.get()[i]; }
  const float& operator[](std::size_t i) const { return p_.get()[i]; }
  void swap(ZeroedFloats& other) noexcept {
    std::swap(p_, other.p_);
    std::swap(n_, other.n_);
  }

 private:
  struct Free {
    void operator()(float* p) const noexcept { std::free(p); }
  };
  std::unique_ptr<float, Free> p_;
  std::size_t n_;
};

}  // namespace skyspec
