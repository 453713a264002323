#include "base/zeroed_floats.hpp"

#include <sys/mman.h>

#include <cstdint>
#include <cstdlib>
#include <new>

namespace skyspec {
namespace {
constexpr std::size_t kHugePage = std::size_t{2} << 20;
#if defined(__SANITIZE_ADDRESS__)
// AddressSanitizer watches calloc's blocks (their ends), not a mapping: every array from calloc.
constexpr std::size_t kMappedFrom = SIZE_MAX;
#else
constexpr std::size_t kMappedFrom = std::size_t{4} << 20;  // bytes: smaller arrays come from calloc
#endif
}  // namespace

ZeroedFloats::ZeroedFloats(std::size_t n) : n_(n) {
  if (n == 0) return;
  if (n > SIZE_MAX / sizeof(float) - kHugePage) throw std::bad_alloc();
  const std::size_t bytes = n * sizeof(float);
  if (bytes < kMappedFrom) {
    p_ = static_cast<float*>(std::calloc(n, sizeof(float)));
    if (!p_) throw std::bad_alloc();
    return;
  }
  // Anonymous pages are zero. The array's bytes rounded up to whole huge pages, and one huge page
  // more, so that the array can start on a huge page's boundary and the advice below covers only
  // the mapping.
  const std::size_t whole = (bytes + kHugePage - 1) & ~(kHugePage - 1);
  mapping_bytes_ = whole + kHugePage;
  mapping_ = mmap(nullptr, mapping_bytes_, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (mapping_ == MAP_FAILED) {
    mapping_ = nullptr;
    throw std::bad_alloc();
  }
  const auto start = (reinterpret_cast<std::uintptr_t>(mapping_) + kHugePage - 1) & ~(kHugePage - 1);
  p_ = reinterpret_cast<float*>(start);
  madvise(p_, whole, MADV_HUGEPAGE);  // advice: a kernel without transparent huge pages ignores it
}

ZeroedFloats::~ZeroedFloats() {
  if (mapping_)
    munmap(mapping_, mapping_bytes_);
  else
    std::free(p_);
}

}  // namespace skyspec
