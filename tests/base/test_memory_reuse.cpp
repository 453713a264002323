// Freed memory kept for reuse (src/base/memory_reuse.hpp): a frame's large block, freed and asked
// for again from another thread (the viewer renders on its server's threads), comes back without
// the system faulting its pages in again. The page faults are the kernel's count (getrusage), not
// a time. Each case runs in a child process: the setting is the whole process's.
#include <boost/test/unit_test.hpp>

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstddef>
#include <thread>
#include <vector>

#include "base/memory_reuse.hpp"

BOOST_AUTO_TEST_SUITE(test_memory_reuse)

// glibc's settings, outside AddressSanitizer (whose allocator they do not reach).
#if defined(__GLIBC__) && !defined(__SANITIZE_ADDRESS__)
#define SKYSPEC_GLIBC_HEAP 1
#endif

#if defined(SKYSPEC_GLIBC_HEAP)
namespace {

constexpr std::size_t kFrameFloats = std::size_t{512} * 256 * 41;  // a 512 x 256 frame at 41 wavelengths
constexpr long kPages = static_cast<long>(kFrameFloats * sizeof(float) / 4096);

long minor_faults() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_minflt;
}

// In a child process: (keep_freed_memory_for_reuse() first when `keep`) a frame's block allocated,
// filled and freed on a thread of its own, twice; exits with 0 when the second frame faulted in
// fewer than a tenth of its pages, 1 otherwise.
int second_frame_mostly_reused(bool keep) {
  const pid_t pid = fork();
  if (pid == 0) {
    if (keep) skyspec::keep_freed_memory_for_reuse();
    const auto frame = [] {
      std::vector<float> image(kFrameFloats);
      for (std::size_t i = 0; i < image.size(); i += 1024) image[i] = static_cast<float>(i);
      return image[kFrameFloats / 2];
    };
    std::thread([&] { frame(); }).join();
    const long before = minor_faults();
    std::thread([&] { frame(); }).join();
    _exit(minor_faults() - before < kPages / 10 ? 0 : 1);
  }
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace
#endif

BOOST_AUTO_TEST_CASE(a_freed_frame_is_reused_without_faulting_its_pages_in_again) {
#if defined(SKYSPEC_GLIBC_HEAP)
  BOOST_TEST(second_frame_mostly_reused(true) == 0);
  // Without the setting glibc hands the block back to the system (what the viewer measured): the
  // check above can fail.
  BOOST_TEST(second_frame_mostly_reused(false) == 1);
#else
  BOOST_TEST_MESSAGE("AddressSanitizer's allocator, or not glibc: glibc's settings do not apply");
#endif
}

#undef SKYSPEC_GLIBC_HEAP

BOOST_AUTO_TEST_SUITE_END()
