#include <boost/test/unit_test.hpp>

// ISO 8601 date-times with a UTC offset, calendar rules and the Julian day (Meeus 1998, ch. 7,
// whose examples give the reference Julian days below).

#include <date/date.h>
#include <date/julian.h>

#include <cmath>
#include <initializer_list>
#include <sstream>
#include <string>

#include "physics/date_time.hpp"
#include "skyspec/error.hpp"

BOOST_AUTO_TEST_SUITE(test_date_time)

using namespace skyspec;

namespace {

/// The InputError a text provokes (its setting and message), or fails the test.
InputError parse_error(const std::string& text, const std::string& setting = "sun.date_time") {
  try {
    parse_iso8601(text, setting);
  } catch (const InputError& e) {
    return e;
  }
  BOOST_FAIL("\"" << text << "\" was accepted");
  throw;  // unreachable
}

}  // namespace

BOOST_AUTO_TEST_SUITE(parsing)

BOOST_AUTO_TEST_CASE(offsets_and_forms) {
  DateTime t = parse_iso8601("2026-06-21T12:00:00+02:00");
  BOOST_TEST(t.year == 2026);
  BOOST_TEST(t.month == 6);
  BOOST_TEST(t.day == 21);
  BOOST_TEST(t.hour == 12);
  BOOST_TEST(t.minute == 0);
  BOOST_TEST(t.second == 0.0);
  BOOST_TEST(t.utc_offset_hours == 2.0);

  BOOST_TEST(parse_iso8601("2026-06-21T10:00:00Z").utc_offset_hours == 0.0);
  BOOST_TEST(parse_iso8601("2026-06-21t10:00z").utc_offset_hours == 0.0);
  BOOST_TEST(parse_iso8601("2003-10-17T12:30:30-07:00").utc_offset_hours == -7.0);
  BOOST_TEST(parse_iso8601("2026-06-21 17:45+0545").utc_offset_hours == 5.75);
  BOOST_TEST(parse_iso8601("2026-06-21T01:00-03").utc_offset_hours == -3.0);
  BOOST_TEST(parse_iso8601("2026-06-21T10:00:30.25Z").second == 30.25);
  BOOST_TEST(parse_iso8601("2026-06-21T10:00:30,5Z").second == 30.5);
  BOOST_TEST(parse_iso8601("2016-12-31T23:59:60Z").second == 60.0);  // a leap second
  BOOST_TEST(parse_iso8601("2024-02-29T00:00:00Z").day == 29);
  BOOST_TEST(parse_iso8601("2000-02-29T00:00:00Z").day == 29);
}

BOOST_AUTO_TEST_CASE(the_same_instant_in_two_zones) {
  // Equal to rounding: 1e-9 day is 86 microseconds.
  BOOST_TEST(std::abs(julian_day_utc(parse_iso8601("2026-06-21T12:00:00+02:00")) -
                      julian_day_utc(parse_iso8601("2026-06-21T10:00:00Z"))) < 1e-9);
  BOOST_TEST(std::abs(julian_day_utc(parse_iso8601("2026-01-01T01:00:00+05:00")) -
                      julian_day_utc(parse_iso8601("2025-12-31T20:00:00Z"))) < 1e-9);
}

BOOST_AUTO_TEST_CASE(round_trip) {
  for (const char* text : {"2026-06-21T12:00:00+02:00", "2026-06-21T10:00:00Z", "2003-10-17T12:30:30-07:00",
                           "2026-06-21T17:45:00+05:45", "2026-06-21T10:00:30.25Z"})
    BOOST_TEST(to_iso8601(parse_iso8601(text)) == text);
}

BOOST_AUTO_TEST_CASE(errors_name_the_setting_and_say_why) {
  struct Case {
    const char* text;
    const char* reason;  // a fragment the message must contain
  };
  const Case cases[] = {
      {"", "digits for the year"},
      {"2026-06-21T12:00:00", "UTC offset is missing"},
      {"2026-06-21", "'T'"},
      {"2026/06/21T12:00Z", "'-'"},
      {"26-06-21T12:00Z", "digits for the year"},
      {"2026-13-01T00:00Z", "month from 1 to 12"},
      {"2026-02-29T00:00Z", "day from 1 to 28"},
      {"1900-02-29T00:00Z", "day from 1 to 28"},
      {"2026-04-31T00:00Z", "day from 1 to 30"},
      {"1582-10-10T00:00Z", "skipped"},
      {"2026-06-21T24:00Z", "hour from 0 to 23"},
      {"2026-06-21T12:60Z", "minute from 0 to 59"},
      {"2026-06-21T12:00:61Z", "less than 61"},
      {"2026-06-21T12:00+19:00", "-18:00 to +18:00"},
      {"2026-06-21T12:00+02:75", "00-59"},
      {"2026-06-21T12:00:00.Z", "digits after the decimal mark"},
      {"2026-06-21T12:00:00Z trailing", "unexpected text"},
      {"2026-06-21T12:00:00 +02:00", "expected Z or a UTC offset"},
  };
  for (const Case& c : cases) {
    const InputError e = parse_error(c.text);
    const std::string message = e.what();
    BOOST_TEST_INFO("\"" << c.text << "\" -> " << message);
    BOOST_TEST(e.setting() == "sun.date_time");
    BOOST_TEST(e.value() == "\"" + std::string(c.text) + "\"");
    BOOST_TEST(message.find(c.reason) != std::string::npos);
    BOOST_TEST(message.find("2026-06-21T12:00:00+02:00") != std::string::npos);  // the example of the form
  }
}

BOOST_AUTO_TEST_SUITE_END()

BOOST_AUTO_TEST_SUITE(calendar)

BOOST_AUTO_TEST_CASE(julian_days_of_meeus_examples) {
  // Meeus, Astronomical Algorithms (2nd ed. 1998), ch. 7: 1957 October 4.81 = 2436116.31;
  // 333 January 27.5 (Julian calendar) = 1842713.0; J2000.0 = 2000 January 1.5 = 2451545.0;
  // 1582 October 15.0 (first Gregorian day) = 2299160.5 and the day before, October 4.0
  // (Julian calendar) = 2299159.5.
  BOOST_TEST(std::abs(julian_day_utc(DateTime{1957, 10, 4, 19, 26, 24.0, 0.0}) - 2436116.31) < 1e-9);
  BOOST_TEST(julian_day_utc(DateTime{333, 1, 27, 12, 0, 0.0, 0.0}) == 1842713.0);
  BOOST_TEST(julian_day_utc(DateTime{2000, 1, 1, 12, 0, 0.0, 0.0}) == 2451545.0);
  BOOST_TEST(julian_day_utc(DateTime{1582, 10, 15, 0, 0, 0.0, 0.0}) == 2299160.5);
  BOOST_TEST(julian_day_utc(DateTime{1582, 10, 4, 0, 0, 0.0, 0.0}) == 2299159.5);
}

// Meeus' Julian-day formula (the SPA's eq. 4, what solar_position uses) against the day count of
// Howard Hinnant's date library, an independent implementation of both calendars: JD =
// 2440587.5 + days since 1970-01-01 (in the calendar in force) + the fraction of the day.
BOOST_AUTO_TEST_CASE(julian_days_agree_with_the_date_library) {
  for (int year : {-1000, -1, 0, 4, 333, 1000, 1582, 1583, 1600, 1700, 1900, 2000, 2024, 2026, 3000, 6000})
    for (int month : {1, 2, 3, 10, 12})
      for (int day : {1, 4, 15, 28}) {
        if (year == 1582 && month == 10 && day > 4 && day < 15) continue;  // did not exist
        const bool julian_calendar = year < 1582 || (year == 1582 && (month < 10 || (month == 10 && day < 15)));
        const date::sys_days d =
            julian_calendar
                ? date::sys_days(julian::year{year} / static_cast<unsigned>(month) / static_cast<unsigned>(day))
                : date::sys_days(date::year{year} / static_cast<unsigned>(month) / static_cast<unsigned>(day));
        const double expected = 2440587.5 + d.time_since_epoch().count() + 0.25;  // 06:00
        BOOST_TEST_CONTEXT(year << "-" << month << "-" << day) {
          BOOST_TEST(julian_day_utc(DateTime{year, month, day, 6, 0, 0.0, 0.0}) == expected);
        }
      }
}

// The ISO 8601 reader gives the instant the date library's parser gives for the forms both read.
BOOST_AUTO_TEST_CASE(the_reader_agrees_with_date_parse) {
  const DateTime epoch{1970, 1, 1, 0, 0, 0.0, 0.0};
  for (const char* text : {"2026-06-21T12:00:00+02:00", "2026-06-21T10:00:00Z", "1999-12-31T23:59:59-07:00",
                           "2024-02-29T00:00:00+05:30", "1600-03-01T12:34:56-11:00", "2100-02-28T23:00:00+14:00"}) {
    std::istringstream in(text);
    date::sys_seconds instant;
    const std::string form = std::string(text).back() == 'Z' ? "%FT%TZ" : "%FT%T%Ez";
    in >> date::parse(form, instant);
    BOOST_TEST_CONTEXT(text) {
      BOOST_REQUIRE(!in.fail());
      BOOST_TEST(seconds_between(epoch, parse_iso8601(text)) ==
                 static_cast<double>(instant.time_since_epoch().count()));
    }
  }
}

BOOST_AUTO_TEST_CASE(leap_years) {
  BOOST_TEST(is_leap_year(2024));
  BOOST_TEST(!is_leap_year(2026));
  BOOST_TEST(is_leap_year(2000));
  BOOST_TEST(!is_leap_year(1900));
  BOOST_TEST(is_leap_year(1500));  // Julian calendar
  BOOST_TEST(days_in_month(2026, 2) == 28);
  BOOST_TEST(days_in_month(2024, 2) == 29);
  BOOST_TEST(days_in_month(2026, 12) == 31);
}

BOOST_AUTO_TEST_SUITE_END()

BOOST_AUTO_TEST_CASE(adding_time_crosses_days_months_and_years) {
  const DateTime t = parse_iso8601("2024-12-31T23:30:00+02:00");
  const DateTime u = add_seconds(t, 3600.0);
  BOOST_TEST(to_iso8601(u) == to_iso8601(parse_iso8601("2025-01-01T00:30:00+02:00")));
  const DateTime leap = add_seconds(parse_iso8601("2024-02-28T12:00:00Z"), 86400.0);
  BOOST_TEST(leap.month == 2);
  BOOST_TEST(leap.day == 29);
  BOOST_TEST(seconds_between(t, u) == 3600.0);
  // Offsets count: 12:00+02:00 is 10:00Z.
  BOOST_TEST(seconds_between(parse_iso8601("2026-06-21T12:00:00+02:00"), parse_iso8601("2026-06-21T10:00:00Z")) == 0.0);
  const DateTime back = add_seconds(parse_iso8601("2026-03-01T00:10:00Z"), -1200.0);
  BOOST_TEST(back.month == 2);
  BOOST_TEST(back.day == 28);
  BOOST_TEST(back.hour == 23);
  BOOST_TEST(back.minute == 50);
}

BOOST_AUTO_TEST_SUITE_END()  // test_date_time
