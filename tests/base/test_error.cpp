// InputError: neutral setting ids, respelled by each front end in its own words.
#include <boost/test/unit_test.hpp>

#include <string>
#include <utility>
#include <vector>

#include "skyspec/error.hpp"

BOOST_AUTO_TEST_SUITE(test_error)

using namespace skyspec;

namespace {
const std::vector<std::pair<std::string, std::string>> kSpellings = {
    {"display.view", "--view"}, {"display.look", "--look"}, {"display.exposure.ev", "--exposure"}};
}

BOOST_AUTO_TEST_CASE(a_structured_error_is_recomposed_in_the_front_ends_words) {
  const InputError e("display.look", "\"x\"", "only with display.look = reinhard", "file.toml:3:1");
  const InputError cli = e.respelled(kSpellings);
  BOOST_TEST(cli.setting() == "--look");
  BOOST_TEST(std::string(cli.what()) == "file.toml:3:1: --look = \"x\" is not allowed: only with --look = reinhard");
  BOOST_TEST(cli.value() == "\"x\"");  // the user's value is never respelled
  BOOST_TEST(cli.origin() == "file.toml:3:1");
}

BOOST_AUTO_TEST_CASE(only_whole_ids_are_respelled) {
  // display.views (a longer word), xdisplay.view and display.view.x are other names; the longest
  // id that matches wins, and a sentence's full stop ends a word.
  const InputError e("display.exposure.ev", "1", "see display.views, xdisplay.view, display.view.x and display.view.");
  const InputError cli = e.respelled(kSpellings);
  BOOST_TEST(cli.setting() == "--exposure");
  BOOST_TEST(std::string(cli.what()) ==
             "--exposure = 1 is not allowed: see display.views, xdisplay.view, display.view.x and --view.");
}

BOOST_AUTO_TEST_CASE(a_composed_refusal_is_respelled_in_its_message) {
  const InputError e = InputError::refused("budget.force", "too big (use budget.force to render anyway)");
  const InputError cli = e.respelled({{"budget.force", "--force"}});
  BOOST_TEST(cli.setting() == "--force");
  BOOST_TEST(std::string(cli.what()) == "too big (use --force to render anyway)");
  // Scene keys are nobody's to respell: an unknown spelling leaves everything as it was.
  const InputError key("camera.width", "-5", "a whole number from 1 to 65536", "--width");
  BOOST_TEST(std::string(key.respelled(kSpellings).what()) == std::string(key.what()));
}

BOOST_AUTO_TEST_SUITE_END()
