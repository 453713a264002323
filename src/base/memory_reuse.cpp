#include "base/memory_reuse.hpp"

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace skyspec {

void keep_freed_memory_for_reuse() {
#if defined(__GLIBC__)
  // Each setting alone does not do it (measured: docs/performance.md): with the mapping threshold
  // raised, glibc still trims the heap's top beyond 128 KiB; threads' own heaps shrink on free.
  mallopt(M_MMAP_THRESHOLD, 256 << 20);  // blocks above this still get their own mapping
  mallopt(M_TRIM_THRESHOLD, 1 << 30);
  mallopt(M_ARENA_MAX, 1);
#endif
}

}  // namespace skyspec
