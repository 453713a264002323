#include <boost/test/unit_test.hpp>

// The Solar Position Algorithm against the worked example of Reda & Andreas (NREL/TP-560-34302,
// 2008, Table A5.1; the same figures are printed by NREL's spa_tester.c and checked by
// pvlib-python's test suite), against published equinox and solstice instants, and against the
// geometry of the Earth's orbit.

#include <algorithm>
#include <cmath>
#include <functional>
#include <iomanip>
#include <string>

#include "physics/date_time.hpp"
#include "physics/solar_position.hpp"
#include "skyspec/error.hpp"

BOOST_AUTO_TEST_SUITE(test_solar_position)

using namespace skyspec;

namespace {

/// The report's example: 17 October 2003, 12:30:30 local time at UTC-7 (Golden, Colorado), the
/// NREL site: 39.742476 N, 105.1786 W, 1830.14 m; 820 mbar, 11 degC; Delta T = 67 s,
/// Delta UT1 = 0, refraction at the horizon 0.5667 degrees.
SolarPosition report_example() {
  const DateTime time{2003, 10, 17, 12, 30, 30.0, -7.0};
  const Observer golden{39.742476, -105.1786, 1830.14};
  SolarPositionOptions options;
  options.pressure_hPa = 820.0;
  options.temperature_C = 11.0;
  options.delta_t_s = 67.0;
  options.delta_ut1_s = 0.0;
  options.horizon_refraction_deg = 0.5667;
  return solar_position(time, golden, options);
}

/// |value - published| within half a unit of the published figure's last digit (plus rounding
/// slack of the same size), reported with both numbers.
void check_published(const char* what, double value, double published, double tolerance) {
  BOOST_TEST_INFO(what << ": computed " << std::setprecision(12) << value << ", published " << published);
  BOOST_TEST(std::abs(value - published) <= tolerance);
}

DateTime utc(int year, int month, int day, int hour, int minute, double second = 0.0) {
  return DateTime{year, month, day, hour, minute, second, 0.0};
}

/// `start` (a UTC time) plus a number of minutes, within the same month.
DateTime plus_minutes(const DateTime& start, double minutes) {
  const double total_min = start.hour * 60.0 + start.minute + start.second / 60.0 + minutes;
  const int day_shift = static_cast<int>(std::floor(total_min / 1440.0));
  double in_day_min = total_min - day_shift * 1440.0;
  DateTime t = start;
  t.day += day_shift;
  t.hour = static_cast<int>(in_day_min / 60.0);
  in_day_min -= t.hour * 60.0;
  t.minute = static_cast<int>(in_day_min);
  t.second = (in_day_min - t.minute) * 60.0;
  return t;
}

/// Minutes from `start` to the instant at which f crosses zero, by bisection within
/// [0, span_min]; f must change sign over the span.
double crossing_minutes(const DateTime& start, double span_min, const std::function<double(const DateTime&)>& f) {
  double lo = 0.0, hi = span_min;
  const double f_lo = f(plus_minutes(start, lo));
  BOOST_REQUIRE(f_lo * f(plus_minutes(start, hi)) < 0.0);
  for (int i = 0; i < 50; ++i) {
    const double mid = 0.5 * (lo + hi);
    if ((f(plus_minutes(start, mid)) < 0.0) == (f_lo < 0.0))
      lo = mid;
    else
      hi = mid;
  }
  return 0.5 * (lo + hi);
}

/// A signed angle difference a - b in (-180, 180].
double angle_difference_deg(double a, double b) {
  double d = std::fmod(a - b, 360.0);
  if (d > 180.0) d -= 360.0;
  if (d <= -180.0) d += 360.0;
  return d;
}

const Observer kGreenwich{51.4769, 0.0, 0.0};

}  // namespace

BOOST_AUTO_TEST_SUITE(published_example)

BOOST_AUTO_TEST_CASE(final_angles_match_the_report) {
  const SolarPosition p = report_example();
  // The report's results: topocentric zenith 50.11162, azimuth 194.34024 degrees; spa_tester.c
  // prints 50.111622 and 194.340241. The brief asks for 1e-4 degrees; we hold the printed digits.
  check_published("zenith", p.zenith_deg, 50.111622, 1e-6);
  check_published("azimuth", p.azimuth_deg, 194.340241, 1e-6);
  check_published("elevation without refraction e0", p.elevation_without_refraction_deg, 39.872046, 1e-6);
  check_published("refraction Delta e", p.refraction_deg, 0.016332, 1e-6);
  check_published("apparent elevation e", p.elevation_deg, 39.888378, 1e-6);
}

BOOST_AUTO_TEST_CASE(intermediate_values_match_the_report) {
  // Every intermediate figure of the report's Table A5.1 that this implementation exposes. The
  // ten-decimal L, B and R check the periodic-term tables: a mistyped term of amplitude >= 1e-7
  // rad in L0 would move L by ~1e-6 degrees.
  const SolarPosition p = report_example();
  check_published("Julian day", p.julian_day, 2452930.312847, 1e-6);
  check_published("Julian ephemeris day", p.julian_ephemeris_day, 2452930.313623, 1e-6);
  check_published("heliocentric longitude L", p.heliocentric_longitude_deg, 24.0182616917, 1e-9);
  check_published("heliocentric latitude B", p.heliocentric_latitude_deg, -0.0001011219, 1e-10);
  check_published("radius vector R", p.earth_sun_distance_au, 0.9965422974, 1e-10);
  check_published("nutation in longitude", p.nutation_longitude_deg, -0.00399840, 1e-8);
  check_published("nutation in obliquity", p.nutation_obliquity_deg, 0.00166657, 1e-8);
  check_published("true obliquity", p.true_obliquity_deg, 23.440465, 1e-6);
  check_published("apparent sun longitude", p.apparent_longitude_deg, 204.0085519281, 1e-9);
  check_published("apparent sidereal time", p.apparent_sidereal_time_deg, 318.511910, 1e-6);
  check_published("geocentric right ascension", p.right_ascension_deg, 202.22741, 1e-5);
  check_published("geocentric declination", p.declination_deg, -9.31434, 1e-5);
  check_published("observer hour angle", p.hour_angle_deg, 11.105902, 1e-6);
  check_published("topocentric right ascension", p.topocentric_right_ascension_deg, 202.22704, 1e-5);
  check_published("topocentric declination", p.topocentric_declination_deg, -9.316179, 1e-6);
  check_published("topocentric hour angle", p.topocentric_hour_angle_deg, 11.10627, 2e-5);
}

BOOST_AUTO_TEST_CASE(the_offset_only_moves_the_instant) {
  // 12:30:30 at UTC-7 is 19:30:30 UTC: the same result.
  const Observer golden{39.742476, -105.1786, 1830.14};
  SolarPositionOptions options;
  options.delta_t_s = 67.0;
  const SolarPosition local = solar_position(DateTime{2003, 10, 17, 12, 30, 30.0, -7.0}, golden, options);
  const SolarPosition in_utc = solar_position(parse_iso8601("2003-10-17T19:30:30Z"), golden, options);
  BOOST_TEST(local.julian_day == in_utc.julian_day);
  BOOST_TEST(local.azimuth_deg == in_utc.azimuth_deg);
}

BOOST_AUTO_TEST_SUITE_END()

BOOST_AUTO_TEST_SUITE(seasons)

// Instants of the 2026 equinoxes and solstices, UT, as tabulated (to the minute) from the U.S.
// Naval Observatory's data in Wikipedia's "June solstice" article and, within a minute, by IMCCE:
// March equinox 03-20 14:46, June solstice 06-21 08:25, September equinox 09-23 00:06, December
// solstice 12-21 20:50. They are the instants at which the sun's apparent geocentric longitude is
// 0, 90, 180 and 270 degrees. The default Delta T estimate is used, as a user would.

BOOST_AUTO_TEST_CASE(equinox_and_solstice_instants) {
  struct Event {
    const char* name;
    DateTime search_start;
    double published_minutes_after_start;
    double longitude_deg;
  };
  const Event events[] = {{"March equinox", utc(2026, 3, 20, 12, 0), 166.0, 0.0},
                          {"June solstice", utc(2026, 6, 21, 6, 0), 145.0, 90.0},
                          {"September equinox", utc(2026, 9, 22, 22, 0), 126.0, 180.0},
                          {"December solstice", utc(2026, 12, 21, 18, 0), 170.0, 270.0}};
  for (const Event& e : events) {
    const double minutes = crossing_minutes(e.search_start, 300.0, [&](const DateTime& t) {
      return angle_difference_deg(solar_position(t, kGreenwich).apparent_longitude_deg, e.longitude_deg);
    });
    BOOST_TEST_INFO(e.name << ": computed " << minutes << " min after the search start, published "
                           << e.published_minutes_after_start);
    BOOST_TEST(std::abs(minutes - e.published_minutes_after_start) <= 1.0);
  }
}

BOOST_AUTO_TEST_CASE(declination_at_the_solstices_equals_the_obliquity) {
  // At the solstices lambda = +-90 degrees, so sin(delta) = sin(beta) cos(epsilon) + cos(beta)
  // sin(epsilon) sin(lambda) gives delta = +-epsilon + beta cos(epsilon), and the sun's ecliptic
  // latitude beta stays within 2e-4 degrees: delta = +-23.436 degrees in 2026 (23.4393 at
  // J2000.0, falling 0.013 per century).
  const SolarPosition june = solar_position(utc(2026, 6, 21, 8, 25), kGreenwich);
  const SolarPosition december = solar_position(utc(2026, 12, 21, 20, 50), kGreenwich);
  BOOST_TEST(std::abs(june.declination_deg - june.true_obliquity_deg) < 2.5e-4);
  BOOST_TEST(std::abs(december.declination_deg + december.true_obliquity_deg) < 2.5e-4);
  BOOST_TEST(std::abs(june.declination_deg - 23.436) < 0.004);
  BOOST_TEST(std::abs(december.declination_deg + 23.436) < 0.004);
  // At the equinoxes the declination crosses zero (it moves ~0.4 degrees a day).
  BOOST_TEST(std::abs(solar_position(utc(2026, 3, 20, 14, 46), kGreenwich).declination_deg) < 0.005);
  BOOST_TEST(std::abs(solar_position(utc(2026, 9, 23, 0, 6), kGreenwich).declination_deg) < 0.005);
}

BOOST_AUTO_TEST_CASE(earth_sun_distance_at_perihelion_and_aphelion) {
  // The orbit's eccentricity 0.0167: R = 1 -+ 0.0167 AU at perihelion (early January) and
  // aphelion (early July). Scan hourly and compare the extremes.
  const auto extreme = [](int month, int first_day, int last_day, bool minimum) {
    double best = minimum ? 10.0 : 0.0;
    for (int day = first_day; day <= last_day; ++day)
      for (int hour = 0; hour < 24; ++hour) {
        const double r = solar_position(utc(2026, month, day, hour, 0), kGreenwich).earth_sun_distance_au;
        best = minimum ? std::min(best, r) : std::max(best, r);
      }
    return best;
  };
  const double perihelion_au = extreme(1, 1, 6, true);
  const double aphelion_au = extreme(7, 3, 9, false);
  BOOST_TEST_INFO("perihelion " << perihelion_au << " AU, aphelion " << aphelion_au << " AU");
  BOOST_TEST(std::abs(perihelion_au - 0.9833) < 1.5e-4);
  BOOST_TEST(std::abs(aphelion_au - 1.0167) < 1.5e-4);
}

BOOST_AUTO_TEST_SUITE_END()

BOOST_AUTO_TEST_SUITE(conventions)

BOOST_AUTO_TEST_CASE(azimuth_is_clockwise_from_north) {
  // On the equator at an equinox the sun rises due east and sets due west.
  const Observer equator{0.0, 0.0, 0.0};
  const SolarPosition morning = solar_position(utc(2026, 3, 20, 7, 0), equator);
  const SolarPosition evening = solar_position(utc(2026, 3, 20, 17, 0), equator);
  BOOST_TEST(std::abs(morning.azimuth_deg - 90.0) < 0.5);
  BOOST_TEST(std::abs(evening.azimuth_deg - 270.0) < 0.5);
  // At the meridian transit (topocentric hour angle 0, found by bisection; about 12:02 UTC on the
  // Greenwich meridian that day, the equation of time being -2 min) the sun is due south from the
  // northern mid-latitudes and due north from the southern ones, at zenith angle
  // |latitude - declination|.
  for (double latitude_deg : {48.0, -35.0}) {
    const Observer observer{latitude_deg, 0.0, 0.0};
    const DateTime start = utc(2026, 6, 21, 11, 0);
    const double minutes = crossing_minutes(start, 120.0, [&](const DateTime& t) {
      return angle_difference_deg(solar_position(t, observer).topocentric_hour_angle_deg, 0.0);
    });
    const SolarPosition noon = solar_position(plus_minutes(start, minutes), observer);
    const double expected_azimuth_deg = latitude_deg > 0.0 ? 180.0 : 0.0;
    BOOST_TEST(std::abs(angle_difference_deg(noon.azimuth_deg, expected_azimuth_deg)) < 1e-6);
    BOOST_TEST(std::abs(noon.elevation_without_refraction_deg -
                        (90.0 - std::abs(latitude_deg - noon.topocentric_declination_deg))) < 1e-6);
    BOOST_TEST(std::abs(minutes - 62.0) < 1.0);
  }
}

BOOST_AUTO_TEST_CASE(refraction_option) {
  const Observer golden{39.742476, -105.1786, 1830.14};
  SolarPositionOptions on, off;
  off.refraction = false;
  const DateTime time{2003, 10, 17, 12, 30, 30.0, -7.0};
  const SolarPosition with = solar_position(time, golden, on);
  const SolarPosition without = solar_position(time, golden, off);
  BOOST_TEST(without.refraction_deg == 0.0);
  BOOST_TEST(without.elevation_deg == without.elevation_without_refraction_deg);
  BOOST_TEST(without.zenith_deg == 90.0 - without.elevation_without_refraction_deg);
  BOOST_TEST(with.elevation_without_refraction_deg == without.elevation_without_refraction_deg);
  BOOST_TEST(with.azimuth_deg == without.azimuth_deg);
  BOOST_TEST(with.refraction_deg > 0.0);

  // Near the horizon the standard atmosphere lifts the sun by about half a degree (Bennett's
  // formula at e0 = 0 with 1010 hPa and 10 degC gives 1.02 / (60 tan(10.3 / 5.11 deg)) = 0.483).
  // Find a sunset at the equator and look at e0 ~ 0.
  const Observer equator{0.0, 0.0, 0.0};
  SolarPositionOptions standard;
  standard.pressure_hPa = 1010.0;
  standard.temperature_C = 10.0;
  const double minutes = crossing_minutes(utc(2026, 3, 20, 17, 0), 120.0, [&](const DateTime& t) {
    return solar_position(t, equator, standard).elevation_without_refraction_deg;
  });
  const SolarPosition sunset = solar_position(plus_minutes(utc(2026, 3, 20, 17, 0), minutes), equator, standard);
  BOOST_TEST(std::abs(sunset.elevation_without_refraction_deg) < 1e-3);
  BOOST_TEST(std::abs(sunset.refraction_deg - 0.483) < 0.003);
  // Well below the horizon no refraction is applied.
  BOOST_TEST(solar_position(utc(2026, 3, 20, 22, 0), equator, standard).refraction_deg == 0.0);
}

BOOST_AUTO_TEST_CASE(delta_t_estimate) {
  // The polynomials' constant terms at their reference years, and the observed ~69 s of the
  // 2020s within the estimate's known bias (the 2005-2050 polynomial overshoots by a few seconds).
  BOOST_TEST(std::abs(delta_t_estimate_s(2000.0) - 63.86) < 1e-9);
  BOOST_TEST(std::abs(delta_t_estimate_s(1975.0) - 45.45) < 1e-9);
  BOOST_TEST(std::abs(delta_t_estimate_s(2026.5) - 69.0) < 8.0);
  // Continuity at the range boundaries used by recent dates (within a second).
  for (double y : {1900.0, 1920.0, 1941.0, 1961.0, 1986.0, 2005.0, 2050.0, 2150.0})
    BOOST_TEST(std::abs(delta_t_estimate_s(y - 1e-9) - delta_t_estimate_s(y)) < 1.0, "boundary " << y);
}

BOOST_AUTO_TEST_SUITE_END()

BOOST_AUTO_TEST_SUITE(input_errors)

BOOST_AUTO_TEST_CASE(out_of_range_inputs_name_the_setting) {
  const DateTime time = utc(2026, 6, 21, 12, 0);
  const auto setting_of = [&](const Observer& o, const SolarPositionOptions& opt, const DateTime& t) {
    try {
      solar_position(t, o, opt);
    } catch (const InputError& e) {
      return e.setting();
    }
    return std::string("(no error)");
  };
  SolarPositionOptions ok;
  BOOST_TEST(setting_of(Observer{91.0, 0.0, 0.0}, ok, time) == "latitude_deg");
  BOOST_TEST(setting_of(Observer{0.0, -180.5, 0.0}, ok, time) == "longitude_deg");
  BOOST_TEST(setting_of(Observer{0.0, 0.0, std::nan("")}, ok, time) == "altitude_m");
  SolarPositionOptions bad = ok;
  bad.pressure_hPa = -1.0;
  BOOST_TEST(setting_of(Observer{}, bad, time) == "pressure_hPa");
  bad = ok;
  bad.delta_ut1_s = 1.0;
  BOOST_TEST(setting_of(Observer{}, bad, time) == "delta_ut1_s");
  BOOST_TEST(setting_of(Observer{}, ok, utc(6001, 1, 1, 0, 0)) == "date_time");
  BOOST_TEST(setting_of(Observer{}, ok, utc(2026, 2, 29, 0, 0)) == "date_time");
  BOOST_CHECK_THROW(solar_position(utc(2026, 13, 1, 0, 0), Observer{}), InputError);
}

BOOST_AUTO_TEST_SUITE_END()

BOOST_AUTO_TEST_SUITE_END()  // test_solar_position
