// EnergyPlus weather files (EPW): the sun's brightness hour by hour from a measured or typical
// year, for the glare assessment's `--sun weather FILE.epw` (docs/weather-files.md).
//
// The format (EnergyPlus "Auxiliary Programs", ch. 2 "Weather Converter Program", section
// "EnergyPlus Weather File (EPW) Data Dictionary"): comma-separated text, 8 header lines
// (LOCATION, DESIGN CONDITIONS, TYPICAL/EXTREME PERIODS, GROUND TEMPERATURES, HOLIDAYS/DAYLIGHT
// SAVINGS, COMMENTS 1, COMMENTS 2, DATA PERIODS), then one record per hour: Year, Month, Day,
// Hour (1–24: hour 1 is 00:01–01:00, local standard time), Minute, the data source flags and 29
// weather fields, 35 fields in all. glarecam reads LOCATION (city, state, country, source, WMO,
// latitude, longitude, time zone in hours from UTC, elevation), the records per hour of DATA
// PERIODS, and of each record its date and field 18, "Direct Normal Illuminance" (lx: the mean
// over the hour ending at the record's time; missing when >= 999900, written 999999).
//
// What it accepts: one record per hour (DATA PERIODS' records per hour 1; sub-hourly files are
// refused), 30 to 35 fields per record (EnergyPlus still reads records without the last five
// fields), every hour of 1 January to 31 December in order, keyed by month, day and hour (the
// Year column is ignored: a typical year takes each month from another year). 29 February, when
// a leap-year file has it, is checked like any day and then dropped: the year is 365 days, and a
// date of 29 February is read as 28 February. A UTF-8 byte-order mark, CRLF line ends and empty
// lines after the last record are accepted.
//
// How it fails: kBadInput naming the file, the line and the field ("weather.epw:12: field 18
// \"Direct Normal Illuminance\": 1.2e6 lx is out of range [0, 200000]") for a header line out of
// place, a malformed or out-of-range LOCATION, a record with too few or too many fields, a
// non-numeric date or illuminance, a missing, duplicated or out-of-order hour, the missing-value
// code or an out-of-range value in the illuminance field.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/error.h"
#include "core/time.h"
#include "sun/solar_position.h"

namespace glarecam::sun {

// Records of the 365-day year: 1 January hour 1 to 31 December hour 24.
inline constexpr std::size_t kEpwHoursPerYear = 365 * 24;
// Field numbers (1-based, as the data dictionary counts a record's fields).
inline constexpr int kEpwDirectNormalIlluminanceField = 18;
inline constexpr int kEpwFieldsPerRecord = 35;
// EnergyPlus's WeatherManager reads records that end after Aerosol Optical Depth (field 30): the
// unit test of EnergyPlus pull request 9796 feeds it such a line.
inline constexpr int kEpwMinFieldsPerRecord = 30;
// The data dictionary's missing-value code of the illuminance fields, and the value from which
// it calls a value missing ("will be missing if >= 999900"). Both refused; the message says
// "missing" for 999900 to 999999, "out of range" above.
inline constexpr double kEpwMissingIlluminanceLx = 999'999;
inline constexpr double kEpwMissingIlluminanceFromLx = 999'900;
// The largest direct normal illuminance glarecam believes: the sun outside the atmosphere gives
// 127.5 klx × 1.034 ≈ 132 klx at perihelion (IES RP-21, sun/clear_sky.h). 200 klx leaves every
// luminous-efficacy model room and still refuses a corrupted value or one in other units.
inline constexpr double kEpwMaxDirectNormalIlluminanceLx = 200'000;
// A year of hourly records is about 1.5 MB; a sub-hourly file (refused) is at most 60 times that.
inline constexpr std::uintmax_t kMaxEpwFileBytes = 128u << 20;
// Beyond this distance between the file's location and the site, the sun the file saw may not
// be the site's: the caller warns (weatherSiteWarning()).
inline constexpr double kWeatherSiteWarningKm = 50;
// The Earth's mean radius R1 = (2a + b) / 3 of GRS 80 (IUGG; Moritz, "Geodetic Reference System
// 1980", J. Geodesy 74, 2000), km: a sphere whose great circles are within 0.5 % of the
// ellipsoid's geodesics.
inline constexpr double kEarthMeanRadiusKm = 6371.0088;

// The LOCATION header line.
struct EpwLocation {
  std::string city;            // as written ("San.Francisco.Intl.AP", "AMSTERDAM")
  std::string state_province;  // "-" or empty when none
  std::string country;         // usually ISO 3166 alpha-3
  std::string source;          // "IWEC Data", "SRC-TMYx", "TMY3"
  std::string wmo;             // the station's WMO number, as text ("062400")
  double latitude_deg = 0;     // north positive, [-90, 90]
  double longitude_deg = 0;    // east positive, [-180, 180]
  double utc_offset_h = 0;     // the file's local standard time minus UTC, [-12, 14]
  double elevation_m = 0;      // [-1000, 9999.9)
};

struct EpwWeather {
  std::filesystem::path path;  // as given to readEpw, or parseEpw's `file`
  EpwLocation location;
  // kEpwHoursPerYear values, lx, each the mean over the hour ending at its record's time: index
  // (day of the 365-day year − 1) · 24 + (hour − 1) (epwHourIndex()).
  std::vector<double> direct_normal_illuminance_lx;
};

// Reads an EPW file (at most kMaxEpwFileBytes); errors as above, and readTextFile()'s.
Result<EpwWeather> readEpw(const std::filesystem::path& path);
// The same for the file's text; `file` names it in messages and becomes `path`.
Result<EpwWeather> parseEpw(std::string_view text, const std::string& file);

// The index of the record of `month` (1–12), `day` and `hour` (1–24, EPW's hour ending) in
// direct_normal_illuminance_lx; nullopt for no such record (an invalid date, 29 February).
std::optional<std::size_t> epwHourIndex(int month, int day, int hour);

// The direct normal illuminance at an instant of local standard time (the file's time zone):
// `local_standard_hour` hours (0–24) after midnight starting `month`/`day`. Each record is the
// mean over the hour ending at its time, so it belongs to the middle of that hour: hour 13's
// value is the illuminance at 12:30, and between two midpoints the illuminance is linear. The
// year wraps around: from 23:30 on 31 December to 00:30 on 1 January it is interpolated between
// those two records of the same file (a typical year's ends are one climate's). 29 February is
// 28 February. The value is never negative (a mean of non-negative values); it is whatever the
// file says whether or not the sun is up (near sunrise an hour's mean is not zero although the
// sun was below the horizon for part of it): whether the sun is up is the caller's question.
// An hour beyond 0–24 runs on into the following or preceding days. NaN for an invalid date, a
// non-finite hour, or a weather without a full year.
// The linear curve keeps the hourly means only approximately: its mean over an hour is
// (v[i−1] + 6 v[i] + v[i+1]) / 8.
double directNormalIlluminanceLx(const EpwWeather& weather, int month, int day,
                                 double local_standard_hour);
// The same at an instant in UTC: local standard time is UTC + the file's utc_offset_h (the file
// keeps no daylight saving time), whatever the year.
double directNormalIlluminanceLx(const EpwWeather& weather, UtcTime utc);

// The great-circle distance between two points on a sphere of kEarthMeanRadiusKm, km (Vincenty's
// formula for the sphere: exact to rounding from coincident points to the antipodes).
double greatCircleDistanceKm(double latitude_a_deg, double longitude_a_deg, double latitude_b_deg,
                             double longitude_b_deg);
// Between the file's location and a site.
double distanceKm(const EpwLocation& location, const SiteLocation& site);
// The warning for a file farther than kWeatherSiteWarningKm from the site ("weather.epw: the
// weather file's station AMSTERDAM, NLD (52.30°, 4.77°) is 212 km from the site (52.0°, 7.8°),
// more than 50 km: its sun is another place's"), nullopt when it is nearer.
std::optional<std::string> weatherSiteWarning(const EpwWeather& weather, const SiteLocation& site);

// A valid EPW file (for tests and their fixtures) of `location` and one record per value, in
// order from 1 January hour 1 in a non-leap year (2001), at most kEpwHoursPerYear: fewer values
// end the file early (readEpw refuses it). Each value is written in its shortest exact form, a
// NaN as the missing-value code 999999. The other fields are plausible constants (20 °C, dew point
// 10 °C, 52 %, 101325 Pa, calm, a clear sky, unlimited ceiling) or their missing-value codes
// (every radiation, the other illuminances, visibility, precipitation, snow); commas and line
// breaks in the location's names become spaces.
std::string formatEpw(const EpwLocation& location,
                      std::span<const double> direct_normal_illuminance_lx);

}  // namespace glarecam::sun
