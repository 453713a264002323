#include <boost/test/unit_test.hpp>

#include <string>

#include "scene/toml_limits.hpp"
#include "skyspec/error.hpp"
#include "skyspec/scene.hpp"

BOOST_AUTO_TEST_SUITE(test_toml_limits)

using namespace skyspec;

namespace {
std::string repeat(const std::string& s, int n) {
  std::string out;
  for (int i = 0; i < n; ++i) out += s;
  return out;
}
// The message of the InputError check_toml_limits throws, or "" when it accepts the text.
std::string refusal(const std::string& text) {
  try {
    check_toml_limits(text, "scene file", "t.toml");
  } catch (const InputError& e) {
    return e.what();
  }
  return {};
}
}  // namespace

BOOST_AUTO_TEST_CASE(the_default_scene_is_far_within_the_limits) {
  BOOST_TEST(refusal(scene_to_toml(default_scene())).empty());
}

BOOST_AUTO_TEST_CASE(nesting_up_to_the_limit_is_accepted_beyond_it_refused_with_a_position) {
  BOOST_TEST(refusal("x = " + repeat("[", kMaxTomlNesting) + repeat("]", kMaxTomlNesting)).empty());
  BOOST_TEST(refusal("x = " + repeat("[", kMaxTomlNesting + 1) + repeat("]", kMaxTomlNesting + 1))
                 .find("t.toml:1:37: arrays") == 0);
  BOOST_TEST(refusal("x = " + repeat("{a=", 40000) + "1" + repeat("}", 40000)).find("nested more than 32 deep") !=
             std::string::npos);
  BOOST_TEST(refusal("\n\n[" + repeat("a.", 40000) + "a]").find("t.toml:3:") == 0);
}

BOOST_AUTO_TEST_CASE(dotted_keys_count_parts_outside_strings_and_comments) {
  BOOST_TEST(refusal(repeat("a.", kMaxTomlKeyParts - 1) + "a = 1").empty());
  BOOST_TEST(refusal(repeat("a.", kMaxTomlKeyParts) + "a = 1").find("a dotted key of more than 32 parts") !=
             std::string::npos);
  // Dots and brackets inside strings, literal strings, multi-line strings and comments do not count.
  const std::string dots = repeat(".[{", 100);
  BOOST_TEST(refusal("a = \"" + dots + "\"").empty());
  BOOST_TEST(refusal("a = '" + dots + "'").empty());
  BOOST_TEST(refusal("a = \"\"\"\n" + dots + "\n\"\"\"").empty());
  BOOST_TEST(refusal("a = '''" + dots + "'''").empty());
  BOOST_TEST(refusal("a = \"x\\\"" + dots + "\"").empty());  // an escaped quote does not end the string
  BOOST_TEST(refusal("a = 1 # " + dots).empty());
  // Numbers' dots are reset by the separators: a long array of floats is fine.
  BOOST_TEST(refusal("a = [" + repeat("1.5, ", 1000) + "2.5]").empty());
}

BOOST_AUTO_TEST_CASE(the_size_limit_names_the_size) {
  BOOST_TEST(refusal(std::string(kMaxTomlBytes, ' ')).empty());
  BOOST_TEST(refusal(std::string(kMaxTomlBytes + 1, ' ')).find("bytes of TOML; skyspec reads at most 1 MiB") !=
             std::string::npos);
}

// Every way in: scene text, --set values; the parser never sees the deep text.
BOOST_AUTO_TEST_CASE(the_scene_loader_applies_the_limits) {
  SceneLoader loader;
  BOOST_CHECK_THROW(loader.apply_toml(repeat("a.", 70000) + "a = 1", "deep.toml"), InputError);
  BOOST_CHECK_THROW(loader.apply_override("spectrum.wavelengths_nm", repeat("[", 40000) + repeat("]", 40000), "--set"),
                    InputError);
  BOOST_CHECK_NO_THROW(loader.finish());
}

BOOST_AUTO_TEST_SUITE_END()
