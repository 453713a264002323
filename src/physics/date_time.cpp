// Civil date-times, ISO 8601 text and the Julian day; see date_time.hpp. The calendars (leap years,
// month lengths, day counts) are Howard Hinnant's date library (date/date.h: the proleptic
// Gregorian calendar; date/julian.h: the Julian one); the ISO 8601 reader is ours, for its
// messages (docs/architecture.md).
#include "physics/date_time.hpp"

#include <date/date.h>
#include <date/julian.h>

#include <cmath>
#include <cstdio>
#include <sstream>

#include "base/text_format.hpp"
#include "skyspec/error.hpp"

namespace skyspec {
namespace {

constexpr const char* kIsoForm =
    "an ISO 8601 date-time with a UTC offset, YYYY-MM-DDThh:mm[:ss[.fff]] then Z or +hh:mm / -hh:mm "
    "(e.g. 2026-06-21T12:00:00+02:00 or 2026-06-21T10:00:00Z)";
constexpr double kMaxOffset_hours = 18.0;

/// The first day of the Gregorian calendar, 1582-10-15, as a comparable number.
constexpr long kGregorianStart = 15821015L;
long date_key(int year, int month, int day) { return static_cast<long>(year) * 10000L + month * 100L + day; }
bool is_gregorian(int year, int month, int day) { return date_key(year, month, day) >= kGregorianStart; }

std::string two_digits(int v) {
  char buf[8];
  std::snprintf(buf, sizeof buf, "%02d", v);
  return buf;
}

/// A small cursor over the text being parsed.
class Cursor {
 public:
  Cursor(std::string_view text, const std::string& setting) : text_(text), setting_(setting) {}
  bool at_end() const { return pos_ >= text_.size(); }
  char peek() const { return at_end() ? '\0' : text_[pos_]; }
  [[noreturn]] void fail(const std::string& why) const {
    throw InputError(setting_, "\"" + std::string(text_) + "\"", std::string(kIsoForm) + "; " + why);
  }
  /// Exactly `count` decimal digits.
  int digits(int count, const char* what) {
    int value = 0;
    for (int i = 0; i < count; ++i) {
      const char c = peek();
      if (c < '0' || c > '9') fail(std::string("expected ") + std::to_string(count) + " digits for the " + what);
      value = value * 10 + (c - '0');
      ++pos_;
    }
    return value;
  }
  void expect(char c, const char* what) {
    if (peek() != c) fail(std::string("expected '") + c + "' " + what);
    ++pos_;
  }
  bool accept(char c) {
    if (peek() != c) return false;
    ++pos_;
    return true;
  }
  /// Digits after a decimal mark, as a fraction in [0, 1).
  double fraction() {
    double value = 0.0, scale = 0.1;
    int count = 0;
    while (peek() >= '0' && peek() <= '9') {
      value += (peek() - '0') * scale;
      scale *= 0.1;
      ++pos_;
      ++count;
    }
    if (count == 0) fail("expected digits after the decimal mark of the seconds");
    return value;
  }

 private:
  std::string_view text_;
  const std::string& setting_;
  size_t pos_ = 0;
};

}  // namespace

bool is_leap_year(int year) {
  if (year < 1582) return julian::year{year}.is_leap();
  return date::year{year}.is_leap();
}

int days_in_month(int year, int month) {
  const auto m = static_cast<unsigned>(month);
  if (year < 1582)
    return static_cast<int>(static_cast<unsigned>((julian::year{year} / julian::month{m} / julian::last).day()));
  return static_cast<int>(static_cast<unsigned>((date::year{year} / date::month{m} / date::last).day()));
}

void validate(const DateTime& t, const std::string& setting) {
  const auto fail = [&](const std::string& why) { throw InputError(setting, to_iso8601(t), why); };
  if (t.month < 1 || t.month > 12) fail("a month from 1 to 12");
  if (t.day < 1 || t.day > days_in_month(t.year, t.month))
    fail("a day from 1 to " + std::to_string(days_in_month(t.year, t.month)) + " in " + std::to_string(t.year) + "-" +
         two_digits(t.month));
  if (t.year == 1582 && t.month == 10 && t.day > 4 && t.day < 15)
    fail("an existing date: 1582-10-05 to 1582-10-14 were skipped when the Gregorian calendar began");
  if (t.hour < 0 || t.hour > 23) fail("an hour from 0 to 23");
  if (t.minute < 0 || t.minute > 59) fail("a minute from 0 to 59");
  if (!(t.second >= 0.0 && t.second < 61.0)) fail("seconds from 0 to less than 61 (60.x is a leap second)");
  if (!(std::abs(t.utc_offset_hours) <= kMaxOffset_hours)) fail("a UTC offset within -18:00 to +18:00");
}

DateTime parse_iso8601(std::string_view text, const std::string& setting) {
  Cursor in(text, setting);
  DateTime t;
  t.year = in.digits(4, "year (YYYY)");
  in.expect('-', "after the year");
  t.month = in.digits(2, "month (MM)");
  in.expect('-', "after the month");
  t.day = in.digits(2, "day (DD)");
  if (!(in.accept('T') || in.accept('t') || in.accept(' '))) in.fail("expected 'T' between the date and the time");
  t.hour = in.digits(2, "hour (hh)");
  in.expect(':', "after the hour");
  t.minute = in.digits(2, "minute (mm)");
  if (in.accept(':')) {
    t.second = in.digits(2, "seconds (ss)");
    if (in.accept('.') || in.accept(',')) t.second += in.fraction();
  }
  if (in.accept('Z') || in.accept('z')) {
    t.utc_offset_hours = 0.0;
  } else if (in.peek() == '+' || in.peek() == '-') {
    const double sign = in.peek() == '-' ? -1.0 : 1.0;
    in.accept(in.peek());
    const int hours = in.digits(2, "offset hours (hh)");
    int minutes = 0;
    if (in.accept(':')) {
      minutes = in.digits(2, "offset minutes (mm)");
    } else if (in.peek() >= '0' && in.peek() <= '9') {
      minutes = in.digits(2, "offset minutes (mm)");
    }
    if (minutes > 59) in.fail("the offset's minutes must be 00-59");
    t.utc_offset_hours = sign * (hours + minutes / 60.0);
  } else if (in.at_end()) {
    in.fail("the UTC offset is missing: add Z for UTC or the zone's offset such as +02:00");
  } else {
    in.fail("expected Z or a UTC offset (+hh:mm or -hh:mm) after the time");
  }
  if (!in.at_end()) in.fail("unexpected text after the UTC offset");
  try {
    validate(t, setting);
  } catch (const InputError& e) {
    in.fail("no such date-time, expected " + e.allowed());
  }
  return t;
}

std::string to_iso8601(const DateTime& t) {
  std::ostringstream s;
  char date[32];
  std::snprintf(date, sizeof date, "%04d-%02d-%02dT%02d:%02d:", t.year, t.month, t.day, t.hour, t.minute);
  s << date;
  // Seconds: whole when whole, else to the microsecond without trailing zeros.
  const double whole = std::floor(t.second);
  char sec[32];
  if (t.second == whole) {
    std::snprintf(sec, sizeof sec, "%02d", static_cast<int>(whole));
  } else {
    std::snprintf(sec, sizeof sec, "%09.6f", t.second);
    std::string trimmed = sec;
    while (!trimmed.empty() && trimmed.back() == '0') trimmed.pop_back();
    std::snprintf(sec, sizeof sec, "%s", trimmed.c_str());
  }
  s << sec;
  if (t.utc_offset_hours == 0.0) {
    s << "Z";
  } else {
    const double magnitude_min = std::round(std::abs(t.utc_offset_hours) * 60.0);
    const int hours = static_cast<int>(magnitude_min / 60.0);
    const int minutes = static_cast<int>(magnitude_min - hours * 60.0);
    s << (t.utc_offset_hours < 0 ? "-" : "+") << two_digits(hours) << ":" << two_digits(minutes);
  }
  return s.str();
}

double julian_day_utc(const DateTime& t, const std::string& setting) {
  validate(t, setting);
  int y = t.year, m = t.month;
  if (m <= 2) {
    y -= 1;
    m += 12;
  }
  const double day_fraction = (t.hour + (t.minute + t.second / 60.0) / 60.0) / 24.0;
  double b = 0.0;
  if (is_gregorian(t.year, t.month, t.day)) {
    const double a = std::trunc(y / 100.0);
    b = 2.0 - a + std::trunc(a / 4.0);
  }
  // floor rather than INT (truncation): identical for the positive arguments here (y > -4716).
  const double jd_local =
      std::floor(365.25 * (y + 4716)) + std::floor(30.6001 * (m + 1)) + t.day + day_fraction + b - 1524.5;
  return jd_local - t.utc_offset_hours / 24.0;
}

double decimal_year(const DateTime& t) { return t.year + (t.month - 0.5) / 12.0; }

namespace {
// Seconds since 1970-01-01T00:00 in the date-time's own local time.
double local_seconds(const DateTime& t) {
  const date::sys_days day = date::year{t.year} / static_cast<unsigned>(t.month) / static_cast<unsigned>(t.day);
  return static_cast<double>(day.time_since_epoch().count()) * 86400.0 + t.hour * 3600.0 + t.minute * 60.0 + t.second;
}
}  // namespace

DateTime add_seconds(const DateTime& t, double seconds) {
  const double total = local_seconds(t) + seconds;
  const double day_floor = std::floor(total / 86400.0);
  double rest = total - day_floor * 86400.0;
  const date::year_month_day ymd{date::sys_days{date::days{static_cast<int>(day_floor)}}};
  DateTime out = t;
  out.year = static_cast<int>(ymd.year());
  out.month = static_cast<int>(static_cast<unsigned>(ymd.month()));
  out.day = static_cast<int>(static_cast<unsigned>(ymd.day()));
  out.hour = static_cast<int>(rest / 3600.0);
  rest -= out.hour * 3600.0;
  out.minute = static_cast<int>(rest / 60.0);
  out.second = rest - out.minute * 60.0;
  if (out.second < 1e-9) out.second = 0.0;  // keep whole minutes whole
  return out;
}

double seconds_between(const DateTime& a, const DateTime& b) {
  return (local_seconds(b) - b.utc_offset_hours * 3600.0) - (local_seconds(a) - a.utc_offset_hours * 3600.0);
}

}  // namespace skyspec
