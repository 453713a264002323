// The Solar Position Algorithm of Reda & Andreas (2004, 2008); see solar_position.hpp.
// Equation numbers are those of NREL/TP-560-34302 (revised January 2008), section 3.
#include "physics/solar_position.hpp"

#include <array>
#include <cmath>
#include <map>
#include <string_view>
#include <vector>

#include "base/csv_table.hpp"
#include "base/embedded_data.hpp"
#include "base/text_format.hpp"
#include "skyspec/error.hpp"
#include "skyspec/units.hpp"

namespace skyspec {
namespace {

// ---------------------------------------------------------------------------------------------
// The periodic-term tables (data/solar_position/, compiled into the library)
// ---------------------------------------------------------------------------------------------

constexpr std::string_view kEarthTermsFile = "solar_position/spa_earth_periodic_terms.csv";
constexpr std::string_view kNutationTermsFile = "solar_position/spa_nutation_terms.csv";

struct PeriodicTerm {
  double a, b, c;  ///< A cos(B + C JME)
};
/// One VSOP87 quantity: series[k] is multiplied by JME^k.
using Vsop = std::vector<std::vector<PeriodicTerm>>;

struct NutationTerm {
  std::array<double, 5> y;  ///< multipliers of X0..X4
  double a, b, c, d;        ///< (a + b JCE) sin(.), (c + d JCE) cos(.), 0.0001 arcsec
};

struct SpaTables {
  Vsop longitude, latitude, radius;  ///< L0-L5, B0-B1, R0-R4
  std::vector<NutationTerm> nutation;
};

SpaTables load_tables() {
  SpaTables t;
  t.longitude.resize(6);
  t.latitude.resize(2);
  t.radius.resize(5);
  const std::map<char, Vsop*> by_letter = {{'L', &t.longitude}, {'B', &t.latitude}, {'R', &t.radius}};
  for (const CsvRow& row : parse_csv(kEarthTermsFile, embedded_file(kEarthTermsFile), {"series", "A", "B", "C"})) {
    const std::string& series = row.fields[0];
    const auto fail = [&] {
      return Error(std::string(kEarthTermsFile) + ":" + std::to_string(row.line_number) + ": unknown series '" +
                   series + "' (L0-L5, B0-B1, R0-R4)");
    };
    if (series.size() != 2 || !by_letter.count(series[0]) || series[1] < '0' || series[1] > '9') throw fail();
    Vsop& vsop = *by_letter.at(series[0]);
    const size_t power = static_cast<size_t>(series[1] - '0');
    if (power >= vsop.size()) throw fail();
    vsop[power].push_back({csv_number(kEarthTermsFile, row, 1), csv_number(kEarthTermsFile, row, 2),
                           csv_number(kEarthTermsFile, row, 3)});
  }
  for (const CsvRow& row : parse_csv(kNutationTermsFile, embedded_file(kNutationTermsFile),
                                     {"y0", "y1", "y2", "y3", "y4", "a", "b", "c", "d"})) {
    NutationTerm n{};
    for (size_t j = 0; j < 5; ++j) n.y[j] = csv_number(kNutationTermsFile, row, j);
    n.a = csv_number(kNutationTermsFile, row, 5);
    n.b = csv_number(kNutationTermsFile, row, 6);
    n.c = csv_number(kNutationTermsFile, row, 7);
    n.d = csv_number(kNutationTermsFile, row, 8);
    t.nutation.push_back(n);
  }
  return t;
}

const SpaTables& tables() {
  static const SpaTables t = load_tables();
  return t;
}

// ---------------------------------------------------------------------------------------------
// Small helpers
// ---------------------------------------------------------------------------------------------

constexpr double kJ2000_jd = 2451545.0;
constexpr double kSecondsPerDay = 86400.0;

double sind(double deg) { return std::sin(degrees_to_radians(deg)); }
double cosd(double deg) { return std::cos(degrees_to_radians(deg)); }
double tand(double deg) { return std::tan(degrees_to_radians(deg)); }
double asind(double x) { return radians_to_degrees(std::asin(x)); }
double atan2d(double y, double x) { return radians_to_degrees(std::atan2(y, x)); }

/// An angle reduced to [0, 360) degrees (the report's "limit to 0-360").
double limit_degrees(double deg) {
  double r = std::fmod(deg, 360.0);
  if (r < 0.0) r += 360.0;
  return r;
}

/// Eqs. 9-10: sum over powers k of JME^k * sum_i A_i cos(B_i + C_i JME), divided by 1e8.
double evaluate_vsop(const Vsop& vsop, double jme) {
  double total = 0.0, power = 1.0;
  for (const std::vector<PeriodicTerm>& series : vsop) {
    double sum = 0.0;
    for (const PeriodicTerm& term : series) sum += term.a * std::cos(term.b + term.c * jme);
    total += sum * power;
    power *= jme;
  }
  return total / 1e8;
}

/// A polynomial c[0] + c[1] x + c[2] x^2 + ... (Horner).
template <size_t N>
double polynomial(const std::array<double, N>& c, double x) {
  double v = 0.0;
  for (size_t i = N; i-- > 0;) v = v * x + c[i];
  return v;
}

void check_range(const std::string& setting, double value, double lo, double hi, const std::string& allowed) {
  if (!(value >= lo && value <= hi)) throw InputError(setting, format_number(value), allowed);
}

}  // namespace

// ---------------------------------------------------------------------------------------------

double delta_t_estimate_s(double y) {
  // Espenak & Meeus (2006), "Five Millennium Canon of Solar Eclipses", NASA/TP-2006-214141,
  // section on Delta T; y is the decimal year. Long-term parabola outside -500..2150.
  // Coefficients as transcribed in pvlib-python (pvlib/spa.py, calculate_deltat).
  const auto parabola = [](double year) {
    const double u = (year - 1820.0) / 100.0;
    return -20.0 + 32.0 * u * u;
  };
  if (y < -500.0) return parabola(y);
  if (y < 500.0)
    return polynomial<7>({10583.6, -1014.41, 33.78311, -5.952053, -0.1798452, 0.022174192, 0.0090316521}, y / 100.0);
  if (y < 1600.0)
    return polynomial<7>({1574.2, -556.01, 71.23472, 0.319781, -0.8503463, -0.005050998, 0.0083572073},
                         (y - 1000.0) / 100.0);
  if (y < 1700.0) return polynomial<4>({120.0, -0.9808, -0.01532, 1.0 / 7129.0}, y - 1600.0);
  if (y < 1800.0) return polynomial<5>({8.83, 0.1603, -0.0059285, 0.00013336, -1.0 / 1174000.0}, y - 1700.0);
  if (y < 1860.0)
    return polynomial<8>(
        {13.72, -0.332447, 0.0068612, 0.0041116, -0.00037436, 0.0000121272, -0.0000001699, 0.000000000875}, y - 1800.0);
  if (y < 1900.0) return polynomial<6>({7.6, 0.5737, -0.251754, 0.01680668, -0.0004473624, 1.0 / 233174.0}, y - 1860.0);
  if (y < 1920.0) return polynomial<5>({-2.79, 1.494119, -0.0598939, 0.0061966, -0.000197}, y - 1900.0);
  if (y < 1941.0) return polynomial<4>({21.20, 0.84493, -0.076100, 0.0020936}, y - 1920.0);
  if (y < 1961.0) return polynomial<4>({29.07, 0.407, -1.0 / 233.0, 1.0 / 2547.0}, y - 1950.0);
  if (y < 1986.0) return polynomial<4>({45.45, 1.067, -1.0 / 260.0, -1.0 / 718.0}, y - 1975.0);
  if (y < 2005.0) return polynomial<6>({63.86, 0.3345, -0.060374, 0.0017275, 0.000651814, 0.00002373599}, y - 2000.0);
  if (y < 2050.0) return polynomial<3>({62.92, 0.32217, 0.005589}, y - 2000.0);
  if (y < 2150.0) return parabola(y) - 0.5628 * (2150.0 - y);
  return parabola(y);
}

SolarPosition solar_position(const DateTime& time, const Observer& observer, const SolarPositionOptions& options) {
  // --- inputs -------------------------------------------------------------------------------
  validate(time, "date_time");
  if (time.year < -2000 || time.year > 6000)
    throw InputError("date_time", to_iso8601(time),
                     "a year from -2000 to 6000 (the range of the Solar Position Algorithm)");
  check_range("latitude_deg", observer.latitude_deg, -90.0, 90.0, "a latitude from -90 to 90 degrees (north positive)");
  check_range("longitude_deg", observer.longitude_deg, -180.0, 180.0,
              "a longitude from -180 to 180 degrees (east positive)");
  check_range("altitude_m", observer.altitude_m, -6.5e6, 1e5, "an altitude from -6500000 to 100000 m above sea level");
  check_range("pressure_hPa", options.pressure_hPa, 0.0, 5000.0, "a pressure from 0 to 5000 hPa (mbar)");
  // Above absolute zero: the refraction formula divides by 273 + T.
  check_range("temperature_C", options.temperature_C, -272.99, 6000.0, "a temperature above -273 and up to 6000 degC");
  // At most 2 degrees keeps Bennett's formula away from its pole at e0 = -5.11 degrees.
  check_range("horizon_refraction_deg", options.horizon_refraction_deg, 0.0, 2.0,
              "a refraction at the horizon from 0 to 2 degrees (typically 0.5667)");
  check_range("delta_ut1_s", options.delta_ut1_s, -1.0 + 1e-12, 1.0 - 1e-12,
              "UT1 - UTC in seconds, strictly between -1 and 1 (IERS Bulletin A)");
  const double delta_t_s = options.delta_t_s ? *options.delta_t_s : delta_t_estimate_s(decimal_year(time));
  check_range("delta_t_s", delta_t_s, -8000.0, 8000.0, "TT - UT1 from -8000 to 8000 seconds");

  SolarPosition p;
  const double phi = observer.latitude_deg;
  const double sigma = observer.longitude_deg;

  // --- 1. time scales (eqs. 4-8) --------------------------------------------------------------
  p.delta_t_s = delta_t_s;
  p.julian_day = julian_day_utc(time, "date_time") + options.delta_ut1_s / kSecondsPerDay;
  p.julian_ephemeris_day = p.julian_day + delta_t_s / kSecondsPerDay;
  const double jc = (p.julian_day - kJ2000_jd) / 36525.0;
  const double jce = (p.julian_ephemeris_day - kJ2000_jd) / 36525.0;
  const double jme = jce / 10.0;

  // --- 2. Earth heliocentric longitude, latitude, radius vector (eqs. 9-12) --------------------
  const SpaTables& t = tables();
  p.heliocentric_longitude_deg = limit_degrees(radians_to_degrees(evaluate_vsop(t.longitude, jme)));
  p.heliocentric_latitude_deg = radians_to_degrees(evaluate_vsop(t.latitude, jme));
  p.earth_sun_distance_au = evaluate_vsop(t.radius, jme);
  const double r_au = p.earth_sun_distance_au;

  // --- 3. geocentric longitude and latitude (eqs. 13-14) ---------------------------------------
  const double theta = limit_degrees(p.heliocentric_longitude_deg + 180.0);
  const double beta = -p.heliocentric_latitude_deg;

  // --- 4. nutation (eqs. 15-22) and the obliquity of the ecliptic (eqs. 23-24) -----------------
  // Mean elongation of the moon from the sun, mean anomalies of the sun and the moon, the moon's
  // argument of latitude, longitude of the moon's ascending node: degrees.
  const std::array<double, 5> x = {polynomial<4>({297.85036, 445267.111480, -0.0019142, 1.0 / 189474.0}, jce),
                                   polynomial<4>({357.52772, 35999.050340, -0.0001603, -1.0 / 300000.0}, jce),
                                   polynomial<4>({134.96298, 477198.867398, 0.0086972, 1.0 / 56250.0}, jce),
                                   polynomial<4>({93.27191, 483202.017538, -0.0036825, 1.0 / 327270.0}, jce),
                                   polynomial<4>({125.04452, -1934.136261, 0.0020708, 1.0 / 450000.0}, jce)};
  double sum_psi = 0.0, sum_epsilon = 0.0;
  for (const NutationTerm& n : t.nutation) {
    double argument_deg = 0.0;
    for (size_t j = 0; j < 5; ++j) argument_deg += x[j] * n.y[j];
    sum_psi += (n.a + n.b * jce) * sind(argument_deg);
    sum_epsilon += (n.c + n.d * jce) * cosd(argument_deg);
  }
  // Units of 0.0001 arcsecond -> degrees.
  p.nutation_longitude_deg = sum_psi / 36000000.0;
  p.nutation_obliquity_deg = sum_epsilon / 36000000.0;
  const double u = jme / 10.0;
  const double epsilon0_arcsec =
      polynomial<11>({84381.448, -4680.93, -1.55, 1999.25, -51.38, -249.67, -39.05, 7.12, 27.87, 5.79, 2.45}, u);
  p.true_obliquity_deg = epsilon0_arcsec / 3600.0 + p.nutation_obliquity_deg;
  const double epsilon = p.true_obliquity_deg;

  // --- 5. aberration, apparent longitude, sidereal time (eqs. 25-28) ---------------------------
  const double aberration_deg = -20.4898 / (3600.0 * r_au);
  p.apparent_longitude_deg = limit_degrees(theta + p.nutation_longitude_deg + aberration_deg);
  const double lambda = p.apparent_longitude_deg;
  const double nu0 = limit_degrees(280.46061837 + 360.98564736629 * (p.julian_day - kJ2000_jd) + 0.000387933 * jc * jc -
                                   jc * jc * jc / 38710000.0);
  p.apparent_sidereal_time_deg = limit_degrees(nu0 + p.nutation_longitude_deg * cosd(epsilon));

  // --- 6. geocentric right ascension and declination (eqs. 29-30) ------------------------------
  p.right_ascension_deg =
      limit_degrees(atan2d(sind(lambda) * cosd(epsilon) - tand(beta) * sind(epsilon), cosd(lambda)));
  p.declination_deg = asind(sind(beta) * cosd(epsilon) + cosd(beta) * sind(epsilon) * sind(lambda));
  const double alpha = p.right_ascension_deg, delta = p.declination_deg;

  // --- 7. hour angle and parallax (eqs. 31-39) -------------------------------------------------
  p.hour_angle_deg = limit_degrees(p.apparent_sidereal_time_deg + sigma - alpha);
  const double h = p.hour_angle_deg;
  const double xi = 8.794 / (3600.0 * r_au);  // equatorial horizontal parallax of the sun, degrees
  // The observer on the reference ellipsoid (flattening ratio 0.99664719, equatorial radius
  // 6378140 m): u is the reduced latitude, x and y the observer's distance from the polar axis and
  // the equatorial plane in Earth radii.
  const double u_deg = radians_to_degrees(std::atan(0.99664719 * tand(phi)));
  const double x_er = cosd(u_deg) + observer.altitude_m / 6378140.0 * cosd(phi);
  const double y_er = 0.99664719 * sind(u_deg) + observer.altitude_m / 6378140.0 * sind(phi);
  const double delta_alpha = atan2d(-x_er * sind(xi) * sind(h), cosd(delta) - x_er * sind(xi) * cosd(h));
  p.topocentric_right_ascension_deg = limit_degrees(alpha + delta_alpha);
  p.topocentric_declination_deg =
      atan2d((sind(delta) - y_er * sind(xi)) * cosd(delta_alpha), cosd(delta) - x_er * sind(xi) * cosd(h));
  p.topocentric_hour_angle_deg = limit_degrees(h - delta_alpha);
  const double delta_p = p.topocentric_declination_deg, h_p = p.topocentric_hour_angle_deg;

  // --- 8. elevation, refraction, zenith (eqs. 40-44) -------------------------------------------
  const double e0 = asind(sind(phi) * sind(delta_p) + cosd(phi) * cosd(delta_p) * cosd(h_p));
  p.elevation_without_refraction_deg = e0;
  // Bennett's refraction formula with Saemundsson's pressure and temperature factors, e0 in
  // degrees, result in degrees; applied while the sun's upper limb is above the refracted horizon
  // (the report's condition e0 >= -(0.26667 + atmos_refract)), which also keeps e0 + 5.11 > 0.
  constexpr double kSunRadius_deg = 0.26667;
  if (options.refraction && e0 >= -(kSunRadius_deg + options.horizon_refraction_deg)) {
    p.refraction_deg = (options.pressure_hPa / 1010.0) * (283.0 / (273.0 + options.temperature_C)) * 1.02 /
                       (60.0 * tand(e0 + 10.3 / (e0 + 5.11)));
  }
  p.elevation_deg = e0 + p.refraction_deg;
  p.zenith_deg = 90.0 - p.elevation_deg;

  // --- 9. azimuth (eqs. 45-46): astronomers' azimuth from south, then navigators' from north ----
  const double gamma = atan2d(sind(h_p), cosd(h_p) * sind(phi) - tand(delta_p) * cosd(phi));
  p.azimuth_deg = limit_degrees(gamma + 180.0);
  return p;
}

}  // namespace skyspec
