// The values a process keeps by key (base/recent_values.hpp): the newest and a bounded number of
// older ones, of bounded bytes; a value over the bound is never kept; get() builds only what it
// does not find.
#include <boost/test/unit_test.hpp>

#include <memory>
#include <string>

#include "base/recent_values.hpp"

BOOST_AUTO_TEST_SUITE(test_recent_values)

using namespace skyspec;

namespace {
std::shared_ptr<const std::string> text(const std::string& s) { return std::make_shared<const std::string>(s); }
}  // namespace

BOOST_AUTO_TEST_CASE(keeps_the_newest_and_a_bounded_number_of_older_values) {
  RecentValues<std::string> c(2, 1000, [](const std::string& s) { return s.size(); });
  for (const char* k : {"a", "b", "c", "d"}) c.keep(k, text(std::string("value ") + k));
  BOOST_TEST(!c.find("a"));
  for (const char* k : {"b", "c", "d"}) BOOST_TEST(*c.find(k) == std::string("value ") + k);
  BOOST_TEST(!c.find("e"));
}

BOOST_AUTO_TEST_CASE(keeps_older_values_of_bounded_bytes_and_no_value_over_the_bound) {
  RecentValues<std::string> c(10, 8, [](const std::string& s) { return s.size(); });
  c.keep("a", text("12345"));
  c.keep("b", text("12345"));  // a and b: 10 bytes older than c, over the bound: a goes
  c.keep("c", text("1"));
  BOOST_TEST(!c.find("a"));
  BOOST_TEST(c.find("b"));
  BOOST_TEST(c.find("c"));
  c.keep("big", text("123456789"));  // over the bound on its own: not kept
  BOOST_TEST(!c.find("big"));
  BOOST_TEST(c.find("c"));
}

BOOST_AUTO_TEST_CASE(get_builds_what_it_does_not_find) {
  RecentValues<std::string> c(3, 1000, [](const std::string& s) { return s.size(); });
  int built = 0;
  const auto build = [&] {
    ++built;
    return text("built");
  };
  const auto first = c.get("k", build), second = c.get("k", build);
  BOOST_TEST(built == 1);
  BOOST_TEST(first.get() == second.get());
  c.get("other", build);
  BOOST_TEST(built == 2);
}

BOOST_AUTO_TEST_SUITE_END()
