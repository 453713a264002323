// The zero-filled arrays of the tables (src/base/zeroed_floats.hpp): zero wherever read, writable
// over their whole length, large ones on huge-page boundaries, moved without a copy.
#include <boost/test/unit_test.hpp>

#include <cstdint>
#include <utility>

#include "base/zeroed_floats.hpp"

BOOST_AUTO_TEST_SUITE(test_zeroed_floats)

using skyspec::ZeroedFloats;

namespace {
void check_zero_then_writable(ZeroedFloats& a) {
  bool zero = true;
  for (std::size_t i = 0; i < a.size(); i += 1021) zero = zero && a[i] == 0.0f;
  BOOST_TEST(zero);
  BOOST_TEST(a[a.size() - 1] == 0.0f);
  for (std::size_t i = 0; i < a.size(); ++i) a[i] = static_cast<float>(i % 7);
  BOOST_TEST(a[a.size() - 1] == static_cast<float>((a.size() - 1) % 7));
}
}  // namespace

BOOST_AUTO_TEST_CASE(small_and_large_arrays_are_zero_and_writable) {
  ZeroedFloats none;
  BOOST_TEST(none.size() == 0u);
  BOOST_TEST(none.data() == nullptr);
  ZeroedFloats small(1000);  // calloc's
  check_zero_then_writable(small);
  ZeroedFloats large((std::size_t{6} << 20) / sizeof(float) + 3);  // a mapping (6 MiB and a bit)
  check_zero_then_writable(large);
#if !defined(__SANITIZE_ADDRESS__)
  BOOST_TEST(reinterpret_cast<std::uintptr_t>(large.data()) % (std::size_t{2} << 20) == 0u);
#endif
}

BOOST_AUTO_TEST_CASE(moving_hands_the_memory_over) {
  ZeroedFloats a((std::size_t{5} << 20) / sizeof(float));
  a[7] = 3.0f;
  const float* p = a.data();
  ZeroedFloats b(std::move(a));
  BOOST_TEST(b.data() == p);
  BOOST_TEST(b[7] == 3.0f);
  ZeroedFloats c(10);
  c = std::move(b);
  BOOST_TEST(c.data() == p);
  BOOST_TEST(c.size() == (std::size_t{5} << 20) / sizeof(float));
  c.swap(b);
  BOOST_TEST(b.data() == p);
}

BOOST_AUTO_TEST_SUITE_END()
