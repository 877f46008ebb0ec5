// The sun's position in the sky of a site at an instant: NREL's Solar Position Algorithm (SPA;
// Reda & Andreas, "Solar Position Algorithm for Solar Radiation Applications", NREL/TP-560-34302,
// 2004, revised 2008), implemented from the paper's equations. Its stated uncertainty is ±0.0003°
// for the years −2000 to 6000; the glare measurement's budget is 0.05°.
//
// Conventions: angles in degrees at this interface. Azimuth is measured clockwise from true north
// (east 90°), in [0, 360). The position is topocentric (seen from the site, parallax included) and
// apparent (aberration and nutation included); elevation and zenith include atmospheric refraction
// unless SolarPositionOptions::refraction is off. The instant is UTC; times are proleptic
// Gregorian, like std::chrono (before 1582 this differs from the paper's Julian-calendar dates).
//
// Time scales: SPA needs UT1 for the Earth's rotation and TT for the ephemeris. UT1 = UTC +
// delta_ut1_s and TT = UT1 + delta_t_s. They matter very differently: one second of ΔUT1 turns the
// Earth, and so the sun's hour angle, by 0.0042°, while one second of ΔT only moves the sun along
// its orbit by 0.000011°. So ΔUT1 (|ΔUT1| < 0.9 s, IERS Bulletin A) is worth giving when 0.004°
// matters, and the default ΔT from deltaTSeconds() (a few seconds off the observed value) is fine.
//
// Failures: an invalid site or option, or an instant outside the years −2000..6000, is kBadInput
// with a message naming the field and its value.
#pragma once

#include <chrono>
#include <nlohmann/json.hpp>
#include <optional>

#include "core/error.h"
#include "core/time.h"

namespace glarecam::sun {

struct SiteLocation {
  double latitude_deg = 0;        // north positive, [-90, 90]
  double longitude_deg = 0;       // east positive, [-180, 180]
  double altitude_m = 0;          // above sea level (parallax), [-1000, 10000]
  double pressure_hpa = 1013.25;  // for refraction (annual mean local pressure), [0, 5000]
  double temperature_c = 12;      // for refraction (annual mean local temperature), (-273, 100]
};

struct SolarPositionOptions {
  std::optional<double> delta_t_s;  // TT − UT1, |x| <= 8000 s; default deltaTSeconds(the year)
  double delta_ut1_s = 0;           // UT1 − UTC, |x| < 1 s (IERS Bulletin A)
  bool refraction = true;
};

struct SolarPosition {            // topocentric, apparent
  double zenith_deg = 0;          // 90° − elevation_deg
  double elevation_deg = 0;       // refraction-corrected when options.refraction
  double azimuth_deg = 0;         // clockwise from north, [0, 360)
  double true_elevation_deg = 0;  // without refraction
  double refraction_deg = 0;      // elevation_deg − true_elevation_deg; 0 below the horizon
  double declination_deg = 0;     // topocentric
  double hour_angle_deg = 0;      // topocentric, positive west of the meridian, (-180, 180]
  double julian_day = 0;          // of the instant in UT1
  double delta_t_s = 0;           // TT − UT1 used
};

// The sun's topocentric position at `utc` seen from `site`.
Result<SolarPosition> solarPosition(std::chrono::sys_time<std::chrono::microseconds> utc,
                                    const SiteLocation& site,
                                    const SolarPositionOptions& options = {});

// ΔT = TT − UT1 in seconds at a decimal year (2003.79 is mid-October 2003): the polynomials of
// Espenak & Meeus, "Five Millennium Canon of Solar Eclipses: −1999 to +3000" (NASA/TP-2006-214141),
// as published at https://eclipse.gsfc.nasa.gov/SEcat5/deltatpoly.html. They were fitted in 2004:
// for 2020–2030 they give 71.6–77.6 s where the observed ΔT is about 69 s, an error worth 0.0001°
// of solar longitude. Outside −500..2150 the long-term parabola −20 + 32·((y − 1820)/100)².
double deltaTSeconds(double decimal_year);

// The standard atmosphere's pressure at `altitude_m` (the default when a site gives none).
double standardPressureHpa(double altitude_m);

// The position as JSON, with the site and the time (`glarecam sun --json`): time, latitude_deg,
// longitude_deg, altitude_m, pressure_hpa, temperature_c, elevation_deg, zenith_deg, azimuth_deg,
// true_elevation_deg, refraction_deg, declination_deg, hour_angle_deg, delta_t_s.
nlohmann::json solarPositionJson(const SolarPosition& sun, const SiteLocation& site, UtcTime time);

// The first problem of a site or of options in words ("latitude 91° is outside [-90, 90]"), as
// kBadInput; also refuses NaN and infinities.
Status validate(const SiteLocation& site);
Status validate(const SolarPositionOptions& options);

namespace detail {

inline constexpr double kJ2000 = 2451545.0;  // JD of 2000-01-01 12:00 TT (SPA, Meeus)

// SPA's intermediate quantities, in the paper's names and units (degrees unless said), for tests
// against the paper's worked example (its Table A5.1).
struct SpaTerms {
  double julian_day = 0;                       // JD, UT1
  double julian_ephemeris_day = 0;             // JDE, TT
  double heliocentric_longitude_deg = 0;       // L, [0, 360)
  double heliocentric_latitude_deg = 0;        // B
  double radius_vector_au = 0;                 // R
  double nutation_longitude_deg = 0;           // Δψ
  double nutation_obliquity_deg = 0;           // Δε
  double true_obliquity_deg = 0;               // ε
  double apparent_longitude_deg = 0;           // λ, [0, 360)
  double apparent_sidereal_time_deg = 0;       // ν, [0, 360)
  double right_ascension_deg = 0;              // α (geocentric), [0, 360)
  double declination_deg = 0;                  // δ (geocentric)
  double hour_angle_deg = 0;                   // H (geocentric), [0, 360)
  double topocentric_right_ascension_deg = 0;  // α′
  double topocentric_declination_deg = 0;      // δ′
  double topocentric_hour_angle_deg = 0;       // H′
  double true_elevation_deg = 0;               // e0
  double refraction_deg = 0;                   // Δe
  double elevation_deg = 0;                    // e
  double zenith_deg = 0;                       // θ
  double azimuth_deg = 0;                      // Φ, from north, [0, 360)
};

// All of SPA for a Julian day in UT1 and ΔT; no validation (solarPosition() validates).
SpaTerms spaTerms(double julian_day_ut1, double delta_t_s, const SiteLocation& site,
                  bool refraction);

// The observer's parallax terms x = ρ cos φ′ and y = ρ sin φ′ (SPA equations 37–39), fixed for a
// site, and the topocentric shift of the sun at an hour angle (equations 36, 40, 41).
struct TopocentricShift {
  double right_ascension_deg = 0;  // Δα: α′ = α + Δα, H′ = H − Δα
  double declination_deg = 0;      // δ′
};
struct Parallax {
  double x = 0, y = 0;
  static Parallax of(const SiteLocation& site);
  TopocentricShift shift(double hour_angle_deg, double declination_deg,
                         double radius_vector_au) const;
};

// The Julian day in UT1 of a UTC instant (UTC + ΔUT1), and ΔT there (the option's, or
// deltaTSeconds()).
double julianDayUt1(std::chrono::sys_time<std::chrono::microseconds> utc,
                    const SolarPositionOptions& options);
double deltaTFor(double julian_day_ut1, const SolarPositionOptions& options);
// kBadInput when the instant's year is outside SPA's −2000..6000.
Status checkInstant(std::chrono::sys_time<std::chrono::microseconds> utc);

// SPA's refraction correction Δe (equation 42) for a true elevation e0, in degrees: zero when the
// sun's upper limb is below the horizon, e0 < −(0.26667° + 0.5667°).
double refractionDeg(double true_elevation_deg, double pressure_hpa, double temperature_c);

}  // namespace detail
}  // namespace glarecam::sun
