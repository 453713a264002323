// Where the sun is in an observer's sky at a given instant: the Solar Position Algorithm (SPA) of
// Reda & Andreas, "Solar position algorithm for solar radiation applications", Solar Energy 76
// (2004) 577-589, corrigendum Solar Energy 81 (2007) 838, revised as NREL/TP-560-34302 (2008).
// Uncertainty +-0.0003 degrees in zenith and azimuth for the years -2000 to 6000.
//
// The chain (equation numbers of the 2008 report, section 3):
//   1. time scales: Julian day JD from UTC + Delta UT1; ephemeris day JDE = JD + Delta T / 86400;
//      centuries JC, JCE and millennia JME from J2000.0 (eqs. 4-9);
//   2. the Earth's heliocentric longitude L, latitude B and radius vector R from the VSOP87
//      periodic terms (Table A4.2), each series sum_i A_i cos(B_i + C_i JME) (eqs. 9-15);
//   3. geocentric longitude Theta = L + 180, latitude beta = -B (eqs. 13-14);
//   4. nutation in longitude and obliquity, Delta psi and Delta epsilon, from the 63 terms of
//      Table A4.3 (eqs. 15-22); true obliquity epsilon (eqs. 23-24);
//   5. aberration Delta tau = -20.4898" / R, apparent longitude lambda = Theta + Delta psi +
//      Delta tau (eqs. 25-26); apparent sidereal time nu at Greenwich (eqs. 27-28);
//   6. geocentric right ascension alpha and declination delta (eqs. 29-30);
//   7. observer hour angle H = nu + longitude - alpha (eq. 31); parallax of the observer's
//      position on the ellipsoid gives the topocentric alpha', delta', H' (eqs. 32-40);
//   8. topocentric elevation e0 (eq. 41), refraction Delta e (eq. 42, Bennett/Saemundsson with
//      pressure and temperature), e = e0 + Delta e, zenith theta = 90 - e (eqs. 43-44);
//   9. azimuth Phi, measured clockwise from north (eqs. 45-46).
//
// Time scales: DateTime is UTC (via its offset). UT1 = UTC + Delta UT1 (|Delta UT1| < 0.9 s,
// published weekly by the IERS in Bulletin A; 0 costs at most 0.004 degrees). Terrestrial time
// TT = UT1 + Delta T (about 69 s in 2020-2026): by default estimated with the polynomials of
// Espenak & Meeus (2006, NASA/TP-2006-214141), which for 2026 give about 75 s; 6 s of error in
// Delta T moves the sun by 7e-5 degrees, well inside the algorithm's uncertainty.
#pragma once

#include <optional>

#include "physics/date_time.hpp"

namespace skyspec {

struct Observer {
  double latitude_deg = 0.0;   ///< geodetic latitude, -90 to 90, north positive
  double longitude_deg = 0.0;  ///< -180 to 180, east of Greenwich positive
  double altitude_m = 0.0;     ///< above mean sea level, -6500 km to 100 km (SPA's eq. 37-38)
};

struct SolarPositionOptions {
  /// Apply atmospheric refraction to the elevation (and hence the zenith angle).
  bool refraction = true;
  /// Annual mean local pressure and temperature for the refraction formula: 0-5000 hPa (= mbar)
  /// and above -273 up to 6000 degC (SPA's limits).
  double pressure_hPa = 1013.25;
  double temperature_C = 15.0;
  /// Refraction at sunrise/sunset, 0-2 degrees: refraction is applied while the sun's upper limb,
  /// e0 + 0.26667 + this, is above the horizon (SPA's atmos_refract, typically 0.5667).
  double horizon_refraction_deg = 0.5667;
  /// TT - UT1 in seconds; empty: delta_t_estimate_s(year and month of the date).
  std::optional<double> delta_t_s;
  /// UT1 - UTC in seconds, within (-1, 1).
  double delta_ut1_s = 0.0;
};

struct SolarPosition {
  // Time
  double julian_day = 0.0;            ///< UT1
  double julian_ephemeris_day = 0.0;  ///< TT
  double delta_t_s = 0.0;             ///< TT - UT1 used
  // Earth around the sun (heliocentric, mean ecliptic and equinox of date)
  double heliocentric_longitude_deg = 0.0;  ///< L, [0, 360)
  double heliocentric_latitude_deg = 0.0;   ///< B
  double earth_sun_distance_au = 0.0;       ///< R
  // Sun seen from the Earth's centre
  double nutation_longitude_deg = 0.0;      ///< Delta psi
  double nutation_obliquity_deg = 0.0;      ///< Delta epsilon
  double true_obliquity_deg = 0.0;          ///< epsilon
  double apparent_longitude_deg = 0.0;      ///< lambda, [0, 360)
  double apparent_sidereal_time_deg = 0.0;  ///< nu at Greenwich, [0, 360)
  double right_ascension_deg = 0.0;         ///< alpha, [0, 360)
  double declination_deg = 0.0;             ///< delta
  double hour_angle_deg = 0.0;              ///< H at the observer, [0, 360)
  // Sun seen from the observer
  double topocentric_right_ascension_deg = 0.0;   ///< alpha'
  double topocentric_declination_deg = 0.0;       ///< delta'
  double topocentric_hour_angle_deg = 0.0;        ///< H'
  double elevation_without_refraction_deg = 0.0;  ///< e0, geometric
  double refraction_deg = 0.0;                    ///< Delta e (0 with refraction off or the sun well below the horizon)
  double elevation_deg = 0.0;                     ///< e = e0 + Delta e: apparent elevation
  double zenith_deg = 0.0;                        ///< theta = 90 - e
  double azimuth_deg = 0.0;                       ///< Phi, clockwise from north (90 = east), [0, 360)
};

/// The SPA for an instant and an observer. Throws InputError naming the setting ("date_time",
/// "latitude_deg", "longitude_deg", "altitude_m", "pressure_hPa", "temperature_C",
/// "horizon_refraction_deg", "delta_t_s", "delta_ut1_s") for values outside the ranges above or a
/// year outside -2000..6000.
SolarPosition solar_position(const DateTime& time, const Observer& observer, const SolarPositionOptions& options = {});

/// Delta T = TT - UT1 in seconds for a decimal year (Espenak & Meeus 2006 polynomials; their
/// long-term parabola -20 + 32 ((y - 1820) / 100)^2 before -500 and from 2150).
double delta_t_estimate_s(double decimal_year);

}  // namespace skyspec
