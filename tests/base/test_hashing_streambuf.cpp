#include <boost/test/unit_test.hpp>

#include <istream>
#include <ostream>
#include <sstream>
#include <string>

#include "skyspec/error.hpp"

#include "base/embedded_data.hpp"
#include "base/hashing_streambuf.hpp"
#include "base/sha256.hpp"

BOOST_AUTO_TEST_SUITE(test_hashing_streambuf)

using namespace skyspec;

namespace {
std::uint64_t checksum_of(const std::string& s) {
  Sha256 h;
  h.update(s.data(), s.size());
  return h.first_64_bits();
}
}  // namespace

namespace {
// Bytes of every value, some written one at a time (overflow / uflow), some in blocks (xsputn / xsgetn).
std::string sample_bytes() {
  std::string s;
  for (int i = 0; i < 70000; ++i) s.push_back(static_cast<char>((i * 131) ^ (i >> 7)));
  return s;
}
}  // namespace

BOOST_AUTO_TEST_CASE(fnv1a64_in_pieces_is_the_hash_of_the_whole) {
  const std::string s = sample_bytes();
  BOOST_TEST(fnv1a64("") == kFnv1a64Basis);
  // The published FNV-1a 64 test vector for "a".
  BOOST_TEST(fnv1a64("a") == 0xaf63dc4c8601ec8cull);
  BOOST_TEST(fnv1a64(std::string_view(s).substr(1234), fnv1a64(std::string_view(s).substr(0, 1234))) == fnv1a64(s));
}

BOOST_AUTO_TEST_CASE(sha256_in_pieces_is_the_digest_of_the_whole) {
  // FIPS 180-2's examples: "abc", and the empty string's digest.
  Sha256 abc;
  abc.update("ab", 2);
  abc.update("c", 1);
  BOOST_TEST(abc.hex() == "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  BOOST_TEST(abc.first_64_bits() == 0xba7816bf8f01cfeaull);  // the same digest's first 8 bytes
  BOOST_TEST(sha256_hex("") == "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  const std::string s = sample_bytes();
  Sha256 pieces;
  pieces.update(s.data(), 1234);
  pieces.update(s.data() + 1234, s.size() - 1234);
  BOOST_TEST(pieces.hex() == sha256_hex(s));
  BOOST_CHECK_THROW(pieces.update("x", 1), Error);  // nothing after the digest
}

BOOST_AUTO_TEST_CASE(writing_passes_every_byte_on_and_hashes_it) {
  const std::string s = sample_bytes();
  std::ostringstream sink;
  HashingStreambuf hashing(sink.rdbuf());
  std::ostream out(&hashing);
  out.put(s[0]);
  out.write(s.data() + 1, 9999);
  for (size_t i = 10000; i < 10100; ++i) out << s[i];
  out.write(s.data() + 10100, static_cast<std::streamsize>(s.size() - 10100));
  BOOST_TEST(static_cast<bool>(out));
  BOOST_TEST(sink.str() == s);
  BOOST_TEST(hashing.hash() == checksum_of(s));
}

BOOST_AUTO_TEST_CASE(reading_hashes_only_what_is_taken_and_leaves_the_rest) {
  const std::string s = sample_bytes();
  std::istringstream source(s + "CHECKSUM");
  HashingInStreambuf hashing(source.rdbuf());
  std::istream in(&hashing);
  std::string got(s.size(), '\0');
  got[0] = static_cast<char>(in.get());
  BOOST_TEST(in.peek() == static_cast<unsigned char>(s[1]));  // a look ahead hashes nothing
  in.read(&got[1], static_cast<std::streamsize>(s.size() - 1));
  BOOST_TEST(static_cast<bool>(in));
  BOOST_TEST(got == s);
  BOOST_TEST(hashing.hash() == checksum_of(s));
  std::string rest(8, '\0');
  source.read(&rest[0], 8);
  BOOST_TEST(rest == "CHECKSUM");
}

BOOST_AUTO_TEST_SUITE_END()
