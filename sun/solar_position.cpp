// NREL's SPA, step by step as in section 3 of NREL/TP-560-34302; the equation numbers in the
// comments are the paper's.
#include "sun/solar_position.h"

#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <span>
#include <string>

#include "core/angles.h"
#include "core/time.h"
#include "sun/spa_tables.h"

namespace glarecam::sun {
namespace {

// ICAO standard atmosphere below 11 km: p = p0 (1 − L h / T0)^(g M / (R L)) with the sea-level
// pressure 1013.25 hPa, lapse rate 0.0065 K/m and 288.15 K (ISO 2533).
constexpr double kSeaLevelPressureHpa = 1013.25;
constexpr double kLapseRatePerMetre = 0.0065 / 288.15;
constexpr double kBarometricExponent = 5.25588;

using std::chrono::microseconds;

constexpr double kUnixEpochJd = 2440587.5;        // JD of 1970-01-01 00:00
constexpr double kSunRadiusDeg = 0.26667;         // SPA's apparent solar radius
constexpr double kHorizonRefractionDeg = 0.5667;  // SPA's refraction at the horizon
constexpr int kFirstYear = -2000;                 // SPA's range
constexpr int kLastYear = 6000;

// x mod 360 in [0, 360): fmod keeps the sign, and adding 360 to a tiny negative can round to 360.
double wrap360(double x_deg) {
  double wrapped = std::fmod(x_deg, 360.0);
  if (wrapped < 0) wrapped += 360.0;
  if (wrapped >= 360.0) wrapped = 0.0;
  return wrapped;
}

// Σ A·cos(B + C·τ) for one series (equations 9 and 10).
double seriesSum(std::span<const spa::PeriodicTerm> terms, double jme) {
  double sum = 0;
  for (const spa::PeriodicTerm& term : terms)
    sum += term.a * std::cos(term.b_rad + term.c_rad * jme);
  return sum;
}

// (Σ_i Series_i · τ^i) / 10⁸ (equation 11), in radians for L and B, AU for R.
template <std::size_t N>
double earthValue(const std::array<std::span<const spa::PeriodicTerm>, N>& series, double jme) {
  double value = 0;
  for (std::size_t i = N; i-- > 0;) value = value * jme + seriesSum(series[i], jme);
  return value / 1e8;
}

// A polynomial c0 + c1·x + c2·x² + ... (Horner).
template <std::size_t N>
double polynomial(const double (&coefficients)[N], double x) {
  double value = 0;
  for (std::size_t i = N; i-- > 0;) value = value * x + coefficients[i];
  return value;
}

std::string formatNumber(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

Status checkRange(const char* name, double value, double low, double high, const char* unit,
                  const char* range_text) {
  if (!std::isfinite(value) || value < low || value > high) {
    return badInput(std::string(name) + " " + formatNumber(value) + unit + " is outside " +
                    range_text);
  }
  return {};
}

}  // namespace

namespace detail {

double refractionDeg(double true_elevation_deg, double pressure_hpa, double temperature_c) {
  if (true_elevation_deg < -(kSunRadiusDeg + kHorizonRefractionDeg)) return 0.0;
  // Equation 42: Bennett's formula scaled by pressure and temperature.
  const double e0 = true_elevation_deg;
  return (pressure_hpa / 1010.0) * (283.0 / (273.0 + temperature_c)) * 1.02 /
         (60.0 * std::tan(radians(e0 + 10.3 / (e0 + 5.11))));
}

Parallax Parallax::of(const SiteLocation& site) {
  // The observer at latitude φ and altitude E on the reference ellipsoid (equations 37–39).
  const double phi = radians(site.latitude_deg);
  const double u = std::atan(0.99664719 * std::tan(phi));
  return {.x = std::cos(u) + site.altitude_m / 6378140.0 * std::cos(phi),
          .y = 0.99664719 * std::sin(u) + site.altitude_m / 6378140.0 * std::sin(phi)};
}

TopocentricShift Parallax::shift(double hour_angle_deg, double declination_deg,
                                 double radius_vector_au) const {
  // Equations 36, 40, 41: the sun's equatorial horizontal parallax ξ, the parallax in right
  // ascension Δα and the topocentric declination δ′.
  const double xi = radians(8.794 / (3600.0 * radius_vector_au));
  const double h = radians(hour_angle_deg);
  const double delta = radians(declination_deg);
  const double denominator = std::cos(delta) - x * std::sin(xi) * std::cos(h);
  const double delta_alpha = std::atan2(-x * std::sin(xi) * std::sin(h), denominator);
  const double delta_prime =
      std::atan2((std::sin(delta) - y * std::sin(xi)) * std::cos(delta_alpha), denominator);
  return {.right_ascension_deg = degrees(delta_alpha), .declination_deg = degrees(delta_prime)};
}

SpaTerms spaTerms(double julian_day_ut1, double delta_t_s, const SiteLocation& site,
                  bool refraction) {
  SpaTerms t;
  // 3.1: Julian day, ephemeris day, centuries and millennia from J2000.0 (equations 4–8).
  const double jd = julian_day_ut1;
  const double jde = jd + delta_t_s / 86400.0;
  const double jc = (jd - detail::kJ2000) / 36525.0;
  const double jce = (jde - detail::kJ2000) / 36525.0;
  const double jme = jce / 10.0;
  t.julian_day = jd;
  t.julian_ephemeris_day = jde;

  // 3.2: the Earth's heliocentric longitude, latitude and radius vector (equations 9–12).
  t.heliocentric_longitude_deg = wrap360(degrees(earthValue(spa::kEarthLongitude, jme)));
  t.heliocentric_latitude_deg = degrees(earthValue(spa::kEarthLatitude, jme));
  t.radius_vector_au = earthValue(spa::kEarthRadius, jme);

  // 3.3: the geocentric longitude and latitude (equations 13, 14).
  const double theta_deg = wrap360(t.heliocentric_longitude_deg + 180.0);
  const double beta_deg = -t.heliocentric_latitude_deg;

  // 3.4: nutation in longitude and obliquity (equations 15–22): the mean elongation of the moon
  // from the sun, the mean anomalies of the sun and the moon, the moon's argument of latitude and
  // the longitude of its ascending node, in degrees.
  const double x[5] = {
      polynomial({297.85036, 445267.111480, -0.0019142, 1.0 / 189474.0}, jce),
      polynomial({357.52772, 35999.050340, -0.0001603, -1.0 / 300000.0}, jce),
      polynomial({134.96298, 477198.867398, 0.0086972, 1.0 / 56250.0}, jce),
      polynomial({93.27191, 483202.017538, -0.0036825, 1.0 / 327270.0}, jce),
      polynomial({125.04452, -1934.136261, 0.0020708, 1.0 / 450000.0}, jce),
  };
  double delta_psi = 0;  // 0.0001″
  double delta_epsilon = 0;
  for (const spa::NutationTerm& term : spa::kNutation) {
    double argument_deg = 0;
    for (int i = 0; i < 5; ++i) argument_deg += term.y[i] * x[i];
    const double argument = radians(argument_deg);
    delta_psi += (term.a + term.b * jce) * std::sin(argument);
    delta_epsilon += (term.c + term.d * jce) * std::cos(argument);
  }
  t.nutation_longitude_deg = delta_psi / 36'000'000.0;
  t.nutation_obliquity_deg = delta_epsilon / 36'000'000.0;

  // 3.5: the true obliquity of the ecliptic (equations 23–25), ε0 in arcseconds.
  const double u = jme / 10.0;
  const double epsilon0_arcsec = polynomial(
      {84381.448, -4680.93, -1.55, 1999.25, -51.38, -249.67, -39.05, 7.12, 27.87, 5.79, 2.45}, u);
  t.true_obliquity_deg = epsilon0_arcsec / 3600.0 + t.nutation_obliquity_deg;

  // 3.6–3.7: aberration, and the apparent sun longitude (equations 26, 27).
  const double aberration_deg = -20.4898 / (3600.0 * t.radius_vector_au);
  t.apparent_longitude_deg = wrap360(theta_deg + t.nutation_longitude_deg + aberration_deg);

  // 3.8: the apparent sidereal time at Greenwich (equations 28–30), from UT1.
  const double nu0_deg = wrap360(280.46061837 + 360.98564736629 * (jd - detail::kJ2000) +
                                 0.000387933 * jc * jc - jc * jc * jc / 38710000.0);
  const double epsilon = radians(t.true_obliquity_deg);
  t.apparent_sidereal_time_deg = wrap360(nu0_deg + t.nutation_longitude_deg * std::cos(epsilon));

  // 3.9–3.10: the geocentric right ascension and declination (equations 31–33).
  const double lambda = radians(t.apparent_longitude_deg);
  const double beta = radians(beta_deg);
  t.right_ascension_deg = wrap360(
      degrees(std::atan2(std::sin(lambda) * std::cos(epsilon) - std::tan(beta) * std::sin(epsilon),
                         std::cos(lambda))));
  const double delta = std::asin(std::sin(beta) * std::cos(epsilon) +
                                 std::cos(beta) * std::sin(epsilon) * std::sin(lambda));
  t.declination_deg = degrees(delta);

  // 3.11: the observer's local hour angle, westward from south (equation 34).
  t.hour_angle_deg =
      wrap360(t.apparent_sidereal_time_deg + site.longitude_deg - t.right_ascension_deg);

  // 3.12: the topocentric right ascension, declination and hour angle (equations 35–45).
  const Parallax parallax = Parallax::of(site);
  const TopocentricShift shift =
      parallax.shift(t.hour_angle_deg, t.declination_deg, t.radius_vector_au);
  const double phi = radians(site.latitude_deg);
  const double delta_prime = radians(shift.declination_deg);
  t.topocentric_right_ascension_deg = t.right_ascension_deg + shift.right_ascension_deg;
  t.topocentric_declination_deg = shift.declination_deg;
  t.topocentric_hour_angle_deg = t.hour_angle_deg - shift.right_ascension_deg;

  // 3.14: the topocentric elevation without and with refraction, and the zenith angle
  // (equations 41–44).
  const double h_prime = radians(t.topocentric_hour_angle_deg);
  t.true_elevation_deg =
      degrees(std::asin(std::sin(phi) * std::sin(delta_prime) +
                        std::cos(phi) * std::cos(delta_prime) * std::cos(h_prime)));
  t.refraction_deg =
      refraction ? refractionDeg(t.true_elevation_deg, site.pressure_hpa, site.temperature_c) : 0.0;
  t.elevation_deg = t.true_elevation_deg + t.refraction_deg;
  t.zenith_deg = 90.0 - t.elevation_deg;

  // 3.15: the topocentric azimuth, from north (equations 45, 46).
  const double gamma = std::atan2(
      std::sin(h_prime), std::cos(h_prime) * std::sin(phi) - std::tan(delta_prime) * std::cos(phi));
  t.azimuth_deg = wrap360(degrees(gamma) + 180.0);
  return t;
}

}  // namespace detail

double deltaTSeconds(double y) {
  // https://eclipse.gsfc.nasa.gov/SEcat5/deltatpoly.html, section by section.
  auto longTerm = [](double year) {
    const double u = (year - 1820.0) / 100.0;
    return -20.0 + 32.0 * u * u;
  };
  if (y < -500) return longTerm(y);
  if (y < 500) {
    return polynomial(
        {10583.6, -1014.41, 33.78311, -5.952053, -0.1798452, 0.022174192, 0.0090316521}, y / 100.0);
  }
  if (y < 1600) {
    return polynomial({1574.2, -556.01, 71.23472, 0.319781, -0.8503463, -0.005050998, 0.0083572073},
                      (y - 1000.0) / 100.0);
  }
  if (y < 1700) return polynomial({120.0, -0.9808, -0.01532, 1.0 / 7129.0}, y - 1600.0);
  if (y < 1800) {
    return polynomial({8.83, 0.1603, -0.0059285, 0.00013336, -1.0 / 1174000.0}, y - 1700.0);
  }
  if (y < 1860) {
    return polynomial({13.72, -0.332447, 0.0068612, 0.0041116, -0.00037436, 0.0000121272,
                       -0.0000001699, 0.000000000875},
                      y - 1800.0);
  }
  if (y < 1900) {
    return polynomial({7.62, 0.5737, -0.251754, 0.01680668, -0.0004473624, 1.0 / 233174.0},
                      y - 1860.0);
  }
  if (y < 1920) {
    return polynomial({-2.79, 1.494119, -0.0598939, 0.0061966, -0.000197}, y - 1900.0);
  }
  if (y < 1941) return polynomial({21.20, 0.84493, -0.076100, 0.0020936}, y - 1920.0);
  if (y < 1961) return polynomial({29.07, 0.407, -1.0 / 233.0, 1.0 / 2547.0}, y - 1950.0);
  if (y < 1986) return polynomial({45.45, 1.067, -1.0 / 260.0, -1.0 / 718.0}, y - 1975.0);
  if (y < 2005) {
    return polynomial({63.86, 0.3345, -0.060374, 0.0017275, 0.000651814, 0.00002373599},
                      y - 2000.0);
  }
  if (y < 2050) return polynomial({62.92, 0.32217, 0.005589}, y - 2000.0);
  if (y < 2150) return longTerm(y) - 0.5628 * (2150.0 - y);
  return longTerm(y);
}

Status validate(const SiteLocation& site) {
  GLARECAM_CHECK(checkRange("latitude", site.latitude_deg, -90, 90, "°", "[-90, 90]"));
  GLARECAM_CHECK(checkRange("longitude", site.longitude_deg, -180, 180, "°", "[-180, 180]"));
  GLARECAM_CHECK(checkRange("altitude", site.altitude_m, -1000, 10000, " m", "[-1000, 10000] m"));
  GLARECAM_CHECK(checkRange("pressure", site.pressure_hpa, 0, 5000, " hPa", "[0, 5000] hPa"));
  // SPA's refraction divides by 273 + T (not 273.15): -273 °C is where it breaks down.
  if (!std::isfinite(site.temperature_c) || site.temperature_c <= -273.0 ||
      site.temperature_c > 100.0) {
    return badInput("temperature " + formatNumber(site.temperature_c) +
                    " °C is outside (-273, 100] °C");
  }
  return {};
}

Status validate(const SolarPositionOptions& options) {
  if (options.delta_t_s) {
    GLARECAM_CHECK(checkRange("ΔT", *options.delta_t_s, -8000, 8000, " s", "[-8000, 8000] s"));
  }
  if (!std::isfinite(options.delta_ut1_s) || std::abs(options.delta_ut1_s) >= 1.0) {
    return badInput("ΔUT1 " + formatNumber(options.delta_ut1_s) + " s is outside (-1, 1) s");
  }
  return {};
}

Status detail::checkInstant(std::chrono::sys_time<microseconds> utc) {
  const std::chrono::year_month_day date{std::chrono::floor<std::chrono::days>(utc)};
  const int year = static_cast<int>(date.year());
  if (year < kFirstYear || year > kLastYear) {
    return badInput("year " + std::to_string(year) + " is outside SPA's range [" +
                    std::to_string(kFirstYear) + ", " + std::to_string(kLastYear) + "]");
  }
  return {};
}

double detail::julianDayUt1(std::chrono::sys_time<microseconds> utc,
                            const SolarPositionOptions& options) {
  // The microseconds since 1970 are exact in an int64; the double JD keeps about 40 µs, i.e.
  // 2·10⁻⁷° of the Earth's rotation.
  const double unix_days = static_cast<double>(utc.time_since_epoch().count()) / 86400e6;
  return kUnixEpochJd + unix_days + options.delta_ut1_s / 86400.0;
}

double detail::deltaTFor(double julian_day_ut1, const SolarPositionOptions& options) {
  const double decimal_year = 2000.0 + (julian_day_ut1 - (detail::kJ2000 - 0.5)) / 365.2425;
  return options.delta_t_s.value_or(deltaTSeconds(decimal_year));
}

Result<SolarPosition> solarPosition(std::chrono::sys_time<microseconds> utc,
                                    const SiteLocation& site, const SolarPositionOptions& options) {
  GLARECAM_CHECK(validate(site));
  GLARECAM_CHECK(validate(options));
  GLARECAM_CHECK(detail::checkInstant(utc));

  const double julian_day = detail::julianDayUt1(utc, options);
  const double delta_t_s = detail::deltaTFor(julian_day, options);

  const detail::SpaTerms t = detail::spaTerms(julian_day, delta_t_s, site, options.refraction);
  SolarPosition position;
  position.zenith_deg = t.zenith_deg;
  position.elevation_deg = t.elevation_deg;
  position.azimuth_deg = t.azimuth_deg;
  position.true_elevation_deg = t.true_elevation_deg;
  position.refraction_deg = t.refraction_deg;
  position.declination_deg = t.topocentric_declination_deg;
  double hour_angle_deg = wrap360(t.topocentric_hour_angle_deg);
  if (hour_angle_deg > 180.0) hour_angle_deg -= 360.0;
  position.hour_angle_deg = hour_angle_deg;
  position.julian_day = julian_day;
  position.delta_t_s = delta_t_s;
  return position;
}

double standardPressureHpa(double altitude_m) {
  return kSeaLevelPressureHpa *
         std::pow(1.0 - kLapseRatePerMetre * altitude_m, kBarometricExponent);
}

nlohmann::json solarPositionJson(const SolarPosition& sun, const SiteLocation& site, UtcTime time) {
  return {{"time", formatIsoTime(time)},          {"latitude_deg", site.latitude_deg},
          {"longitude_deg", site.longitude_deg},  {"altitude_m", site.altitude_m},
          {"pressure_hpa", site.pressure_hpa},    {"temperature_c", site.temperature_c},
          {"elevation_deg", sun.elevation_deg},   {"zenith_deg", sun.zenith_deg},
          {"azimuth_deg", sun.azimuth_deg},       {"true_elevation_deg", sun.true_elevation_deg},
          {"refraction_deg", sun.refraction_deg}, {"declination_deg", sun.declination_deg},
          {"hour_angle_deg", sun.hour_angle_deg}, {"delta_t_s", sun.delta_t_s}};
}

}  // namespace glarecam::sun
