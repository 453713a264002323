#include "base/memory_reuse.hpp"

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace skyspec {

void keep_freed_memory_for_reuse() {
#if defined(__GLIBC__)
  // All three (docs/performance.md has each alone): threads' own heaps shrink on free; glibc's own
  // mapping threshold, which rises after frees, stops at 32 MiB and stops rising once either
  // threshold is set; with only the mapping threshold set the heap's top is trimmed beyond 128 KiB.
  mallopt(M_MMAP_THRESHOLD, 256 << 20);  // blocks above this still get their own mapping
  mallopt(M_TRIM_THRESHOLD, 1 << 30);
  mallopt(M_ARENA_MAX, 1);
#endif
}

}  // namespace skyspec
