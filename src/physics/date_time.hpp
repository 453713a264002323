// Civil date-times with their offset from UTC, ISO 8601 text, and the Julian day.
//
// A DateTime is what a clock on the wall shows plus the zone's offset from UTC:
// "2026-06-21T12:00:00+02:00" is 10:00 UTC. The instant is UTC = local time - utc_offset.
//
// Calendar: the Gregorian calendar from 1582-10-15 on and the Julian calendar before it, the
// convention of the Julian-day formula below (Meeus 1998, ch. 7; Reda & Andreas 2004/2008, eq. 4),
// so historical dates mean what the records of their time meant. (ISO 8601 itself counts every
// date in the proleptic Gregorian calendar: the two agree from 1582-10-15 on.) 1582-10-05 to
// 1582-10-14 did not exist and are rejected.
#pragma once

#include <string>
#include <string_view>

namespace skyspec {

struct DateTime {
  int year = 2000;
  int month = 1;                  ///< 1-12
  int day = 1;                    ///< 1-31, within the month
  int hour = 0;                   ///< 0-23
  int minute = 0;                 ///< 0-59
  double second = 0.0;            ///< [0, 61): 60.x is a leap second
  double utc_offset_hours = 0.0;  ///< local time minus UTC, within +-18 h (e.g. -7 for MST)
};

/// Parses an ISO 8601 / RFC 3339 date-time with an explicit UTC offset:
///   YYYY-MM-DDThh:mm[:ss[.fff]] followed by Z or +hh:mm / -hh:mm (also +hhmm or +hh);
/// 't' or a space may replace 'T', 'z' may replace 'Z', ',' may be the decimal mark.
/// Throws InputError(setting, "<text>", what is expected and what is wrong) on anything else,
/// including impossible dates (2026-02-30) and a missing offset (a bare local time is ambiguous).
DateTime parse_iso8601(std::string_view text, const std::string& setting = "date_time");

/// The date-time as ISO 8601 text, e.g. "2026-06-21T12:00:00+02:00" or "...Z" for offset 0;
/// fractional seconds appear only when present (to the microsecond).
std::string to_iso8601(const DateTime& t);

/// The same instant moved by `seconds` (may be negative), keeping the UTC offset; proleptic
/// Gregorian calendar, no leap seconds.
DateTime add_seconds(const DateTime& t, double seconds);
/// Seconds from a to b (b - a), both taken with their UTC offsets.
double seconds_between(const DateTime& a, const DateTime& b);

/// Throws InputError(setting, ...) if a field is out of its range or the date does not exist.
void validate(const DateTime& t, const std::string& setting = "date_time");

/// True if the year has a 29 February in the calendar in force (Julian before 1582, Gregorian after).
bool is_leap_year(int year);
/// Days in the month (28-31).
int days_in_month(int year, int month);

/// Julian day of the instant, on the UTC time scale (days since -4712-01-01 12:00 UT):
///   JD = INT(365.25 (Y + 4716)) + INT(30.6001 (M + 1)) + D + B - 1524.5 - utc_offset / 24
/// with Y = year - 1, M = month + 12 for January and February, D the day with its fraction, and
/// B = 2 - A + INT(A / 4), A = INT(Y / 100) in the Gregorian calendar, B = 0 in the Julian one
/// (Meeus 1998, eq. 7.1; Reda & Andreas 2008, eq. 4). 2000-01-01T12:00Z is 2451545.0.
/// Validates first (throws InputError naming `setting`).
double julian_day_utc(const DateTime& t, const std::string& setting = "date_time");

/// The year as a decimal number for the middle of the date's month, y = year + (month - 0.5) / 12
/// (the argument of the Delta T polynomials).
double decimal_year(const DateTime& t);

}  // namespace skyspec
