// A zero-filled float array whose memory the system hands out already zeroed on first use, so that
// allocating a large table costs no time until it is filled, and a long computation that fills it
// can stop (cancellation.hpp) before touching it. Small arrays come from calloc; large ones (4 MiB
// and more) are mapped directly, on 2 MiB boundaries and marked for transparent huge pages, so
// that filling them takes one page fault per 2 MiB rather than per 4 KiB (the faults dominate
// reading a table cache on a virtual machine: docs/performance.md).
#pragma once

#include <cstddef>
#include <utility>

namespace skyspec {

class ZeroedFloats {
 public:
  explicit ZeroedFloats(std::size_t n = 0);
  ~ZeroedFloats();
  ZeroedFloats(const ZeroedFloats&) = delete;
  ZeroedFloats& operator=(const ZeroedFloats&) = delete;
  ZeroedFloats(ZeroedFloats&& other) noexcept { swap(other); }
  ZeroedFloats& operator=(ZeroedFloats&& other) noexcept {
    swap(other);
    return *this;
  }
  float* data() { return p_; }
  const float* data() const { return p_; }
  std::size_t size() const { return n_; }
  float& operator[](std::size_t i) { return p_[i]; }
  const float& operator[](std::size_t i) const { return p_[i]; }
  void swap(ZeroedFloats& other) noexcept {
    std::swap(p_, other.p_);
    std::swap(n_, other.n_);
    std::swap(mapping_, other.mapping_);
    std::swap(mapping_bytes_, other.mapping_bytes_);
  }

 private:
  float* p_ = nullptr;
  std::size_t n_ = 0;
  void* mapping_ = nullptr;  // the whole mapping of a large array (null: p_ is calloc's)
  std::size_t mapping_bytes_ = 0;
};

}  // namespace skyspec
