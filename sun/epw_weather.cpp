#include "sun/epw_weather.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <chrono>
#include <cmath>
#include <limits>

#include "core/angles.h"
#include "core/text_file.h"
#include "core/utf8.h"

namespace glarecam::sun {
namespace {

// The header lines in their order (the data dictionary; real files write "HOLIDAYS/DAYLIGHT
// SAVINGS", the dictionary "HOLIDAYS/DAYLIGHT SAVING": both are accepted).
constexpr int kEpwHeaderLines = 8;
constexpr std::array<std::string_view, kEpwHeaderLines> kEpwHeaderKeywords = {
    "LOCATION",
    "DESIGN CONDITIONS",
    "TYPICAL/EXTREME PERIODS",
    "GROUND TEMPERATURES",
    "HOLIDAYS/DAYLIGHT SAVINGS",
    "COMMENTS 1",
    "COMMENTS 2",
    "DATA PERIODS"};
constexpr std::string_view kEpwHolidaysKeywordAsDictionary = "HOLIDAYS/DAYLIGHT SAVING";

// LOCATION's fields, the keyword first (the data dictionary's names).
constexpr std::size_t kEpwLocationFields = 10;

// Days in each month of the 365-day year, and of the 366-day calendar a leap-year file follows.
constexpr std::array<int, 12> kEpwDaysInMonth = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};

constexpr int epwDaysInMonthOfLeapYear(int month) {
  return month == 2 ? 29 : kEpwDaysInMonth[month - 1];
}

// Days before `month` (1–12) in the 365-day year, or in a leap year.
constexpr int epwDaysBefore(int month, bool leap) {
  int days = 0;
  for (int m = 1; m < month; ++m)
    days += leap ? epwDaysInMonthOfLeapYear(m) : kEpwDaysInMonth[m - 1];
  return days;
}

// A record's place in a leap year's sequence of hours (29 February included), 0-based.
constexpr int epwLeapHour(int month, int day, int hour) {
  return (epwDaysBefore(month, true) + day - 1) * 24 + hour - 1;
}

struct EpwDate {
  int month = 1;
  int day = 1;
  int hour = 1;
};

EpwDate epwDateOfLeapHour(int leap_hour) {
  int day_of_year = leap_hour / 24;
  EpwDate date;
  date.hour = leap_hour % 24 + 1;
  date.month = 1;
  while (day_of_year >= epwDaysInMonthOfLeapYear(date.month)) {
    day_of_year -= epwDaysInMonthOfLeapYear(date.month);
    ++date.month;
  }
  date.day = day_of_year + 1;
  return date;
}

// "1/3 hour 5": the month/day of the EPW header's dates, and EPW's hour ending.
std::string epwDateText(const EpwDate& date) {
  return fmt::format("{}/{} hour {}", date.month, date.day, date.hour);
}

constexpr int kEpwLeapDayFirstHour = epwLeapHour(2, 29, 1);
constexpr int kEpwLeapDayLastHour = epwLeapHour(2, 29, 24);
constexpr int kEpwLastHour = epwLeapHour(12, 31, 24);

std::string_view epwTrim(std::string_view text) {
  const auto blank = [](char c) { return c == ' ' || c == '\t' || c == '\r'; };
  while (!text.empty() && blank(text.front())) text.remove_prefix(1);
  while (!text.empty() && blank(text.back())) text.remove_suffix(1);
  return text;
}

// A name from the file as glarecam keeps it: valid UTF-8 (reports and charts refuse anything
// else; old files may be Latin-1), without control bytes.
std::string epwName(std::string_view text) {
  std::string out(epwTrim(text));
  const bool utf8 = requireUtf8(out, "name").has_value();
  for (char& c : out) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte < 0x20 || byte == 0x7f || (!utf8 && byte >= 0x80)) c = '?';
  }
  return out;
}

std::vector<std::string_view> epwSplit(std::string_view text, char separator) {
  std::vector<std::string_view> parts;
  std::size_t start = 0;
  while (true) {
    const std::size_t end = text.find(separator, start);
    if (end == std::string_view::npos) {
      parts.push_back(text.substr(start));
      return parts;
    }
    parts.push_back(text.substr(start, end - start));
    start = end + 1;
  }
}

// A number as the files write it ("52.30", "-122.3650", "+1.0", "1.2e6"); nullopt when the
// field is not one finite number.
std::optional<double> parseEpwNumber(std::string_view text) {
  text = epwTrim(text);
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  double value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || ec != std::errc() || end != text.data() + text.size() ||
      !std::isfinite(value))
    return std::nullopt;
  return value;
}

std::optional<int> parseEpwInteger(std::string_view text) {
  text = epwTrim(text);
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  int value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || ec != std::errc() || end != text.data() + text.size()) return std::nullopt;
  return value;
}

// One pass over the file's lines; every error names the file and the line.
class EpwParser {
 public:
  EpwParser(std::string_view text, const std::string& file) : file_(file) {
    if (text.starts_with("\xEF\xBB\xBF")) text.remove_prefix(3);  // a UTF-8 byte-order mark
    lines_ = epwSplit(text, '\n');
  }

  Result<EpwWeather> parse() {
    EpwWeather weather;
    weather.path = file_;
    for (int i = 0; i < kEpwHeaderLines; ++i) {
      line_ = i + 1;
      if (static_cast<std::size_t>(i) >= lines_.size() ||
          (static_cast<std::size_t>(i) + 1 == lines_.size() && epwTrim(lines_[i]).empty()))
        return fail(fmt::format(
            "the file ends in its header: an EPW file begins with {} header lines ({} ... {})",
            kEpwHeaderLines, kEpwHeaderKeywords.front(), kEpwHeaderKeywords.back()));
      GLARECAM_CHECK(checkKeyword(i));
    }
    line_ = 1;
    GLARECAM_ASSIGN(weather.location, parseLocation(lines_[0]));
    line_ = kEpwHeaderLines;
    GLARECAM_CHECK(checkDataPeriods(lines_[kEpwHeaderLines - 1]));
    weather.direct_normal_illuminance_lx.assign(kEpwHoursPerYear, 0.0);
    GLARECAM_CHECK(parseRecords(weather.direct_normal_illuminance_lx));
    return weather;
  }

 private:
  std::unexpected<Error> fail(const std::string& problem) const {
    return badInput(fmt::format("{}:{}: {}", file_, line_, problem));
  }
  std::unexpected<Error> failField(int field, std::string_view name,
                                   const std::string& problem) const {
    return fail(fmt::format("field {} \"{}\": {}", field, name, problem));
  }

  Status checkKeyword(int index) const {
    const std::string_view line = lines_[index];
    const std::string_view first = epwTrim(line.substr(0, line.find(',')));
    std::string keyword(first);
    std::ranges::transform(keyword, keyword.begin(),
                           [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
    const std::string_view expected = kEpwHeaderKeywords[index];
    if (keyword == expected ||
        (expected == kEpwHeaderKeywords[4] && keyword == kEpwHolidaysKeywordAsDictionary))
      return {};
    return fail(fmt::format(
        "expected the header line {} (line {} of an EPW file's {}: {}, ..., {}), found \"{}\"",
        expected, index + 1, kEpwHeaderLines, kEpwHeaderKeywords.front(), kEpwHeaderKeywords.back(),
        printableText(line)));
  }

  Result<EpwLocation> parseLocation(std::string_view line) const {
    const std::vector<std::string_view> fields = epwSplit(line, ',');
    if (fields.size() != kEpwLocationFields)
      return fail(fmt::format(
          "LOCATION has {} fields where it has {} (LOCATION, city, state or province, country, "
          "source, WMO, latitude, longitude, time zone, elevation)",
          fields.size(), kEpwLocationFields));
    EpwLocation location;
    location.city = epwName(fields[1]);
    location.state_province = epwName(fields[2]);
    location.country = epwName(fields[3]);
    location.source = epwName(fields[4]);
    location.wmo = epwName(fields[5]);
    // The data dictionary's ranges; UTC+13 and +14 (Tonga, Samoa, the Line Islands) are real
    // standard times beyond its ±12.
    struct Numeric {
      int field;
      std::string_view name;
      std::string_view unit;
      double min, max;
      bool max_exclusive;
      double* value;
    };
    const std::array<Numeric, 4> numerics = {{
        {7, "Latitude", "°", -90, 90, false, &location.latitude_deg},
        {8, "Longitude", "°", -180, 180, false, &location.longitude_deg},
        {9, "TimeZone", " h", -12, 14, false, &location.utc_offset_h},
        {10, "Elevation", " m", -1000, 9999.9, true, &location.elevation_m},
    }};
    for (const Numeric& n : numerics) {
      const std::string_view text = epwTrim(fields[n.field - 1]);
      const std::optional<double> value = parseEpwNumber(text);
      if (!value)
        return failField(n.field, n.name,
                         fmt::format("\"{}\" is not a number", printableText(text)));
      if (*value < n.min || *value > n.max || (n.max_exclusive && *value == n.max))
        return failField(n.field, n.name,
                         fmt::format("{}{} is out of range [{}, {}{}", printableText(text), n.unit,
                                     n.min, n.max, n.max_exclusive ? ")" : "]"));
      *n.value = *value;
    }
    return location;
  }

  Status checkDataPeriods(std::string_view line) const {
    const std::vector<std::string_view> fields = epwSplit(line, ',');
    if (fields.size() < 3)
      return fail(fmt::format(
          "DATA PERIODS has {} fields: it needs at least the number of data periods and the "
          "number of records per hour",
          fields.size()));
    constexpr std::string_view kPeriods = "Number of Data Periods";
    constexpr std::string_view kPerHour = "Number of Records per hour";
    const std::optional<int> periods = parseEpwInteger(fields[1]);
    if (!periods || *periods < 1)
      return failField(2, kPeriods,
                       fmt::format("\"{}\" is not a whole number of at least 1",
                                   printableText(epwTrim(fields[1]))));
    const std::optional<int> per_hour = parseEpwInteger(fields[2]);
    if (!per_hour || *per_hour < 1)
      return failField(3, kPerHour,
                       fmt::format("\"{}\" is not a whole number of at least 1",
                                   printableText(epwTrim(fields[2]))));
    if (*per_hour != 1)
      return failField(3, kPerHour,
                       fmt::format("{} records per hour: a sub-hourly file (glarecam reads "
                                   "hourly EPW files, 1 record per hour)",
                                   *per_hour));
    return {};
  }

  Result<int> integerField(const std::vector<std::string_view>& fields, int field,
                           std::string_view name, int min, int max) const {
    const std::string_view text = epwTrim(fields[field - 1]);
    const std::optional<int> value = parseEpwInteger(text);
    if (!value)
      return failField(field, name,
                       fmt::format("\"{}\" is not a whole number", printableText(text)));
    if (*value < min || *value > max)
      return failField(field, name, fmt::format("{} is out of range [{}, {}]", *value, min, max));
    return *value;
  }

  // "1/3 hour 4 is missing", "1/3 hour 4 to 1/5 hour 2 are missing (47 hours)": the hours from
  // `first` to `last` (leap-year places), 29 February not counted unless `leap_day_due`.
  static std::string missingText(int first, int last, bool leap_day_due) {
    int count = last - first + 1;
    if (!leap_day_due && first < kEpwLeapDayFirstHour && last >= kEpwLeapDayLastHour) count -= 24;
    if (!leap_day_due && last == kEpwLeapDayLastHour) last = epwLeapHour(2, 28, 24);
    if (first == last) return fmt::format("{} is missing", epwDateText(epwDateOfLeapHour(first)));
    return fmt::format("{} to {} are missing ({} hours)", epwDateText(epwDateOfLeapHour(first)),
                       epwDateText(epwDateOfLeapHour(last)), count);
  }

  Status parseRecords(std::vector<double>& values) {
    constexpr std::string_view kDateFields = "fields 2-4 (Month, Day, Hour)";
    int previous = -1;  // the last record's place in the leap-year sequence
    int last_record_line = kEpwHeaderLines;
    for (std::size_t index = kEpwHeaderLines; index < lines_.size(); ++index) {
      line_ = static_cast<int>(index) + 1;
      const std::string_view line = lines_[index];
      if (epwTrim(line).empty()) {
        const bool more =
            std::any_of(lines_.begin() + static_cast<std::ptrdiff_t>(index) + 1, lines_.end(),
                        [](std::string_view l) { return !epwTrim(l).empty(); });
        if (more) return fail("an empty line among the records");
        break;
      }
      last_record_line = line_;
      const std::vector<std::string_view> fields = epwSplit(line, ',');
      const int count = static_cast<int>(fields.size());
      if (count < kEpwMinFieldsPerRecord || count > kEpwFieldsPerRecord)
        return fail(fmt::format("{} fields where an EPW record has {} ({} to {} accepted)", count,
                                kEpwFieldsPerRecord, kEpwMinFieldsPerRecord, kEpwFieldsPerRecord));
      // Field 1, the year, is not read: a typical year takes each month from another year.
      int month = 0, day = 0, hour = 0;
      GLARECAM_ASSIGN(month, integerField(fields, 2, "Month", 1, 12));
      GLARECAM_ASSIGN(day, integerField(fields, 3, "Day", 1, epwDaysInMonthOfLeapYear(month)));
      GLARECAM_ASSIGN(hour, integerField(fields, 4, "Hour", 1, 24));
      GLARECAM_CHECK(integerField(fields, 5, "Minute", 0, 60));
      double illuminance_lx = 0;
      GLARECAM_ASSIGN(illuminance_lx, illuminanceField(fields));

      // The next hour in order; 29 February may be skipped, but once begun runs to its end.
      const int place = epwLeapHour(month, day, hour);
      int expected = previous + 1;
      const bool leap_day = month == 2 && day == 29;
      const bool leap_day_due = expected > kEpwLeapDayFirstHour && expected <= kEpwLeapDayLastHour;
      if (expected == kEpwLeapDayFirstHour && !leap_day) expected = epwLeapHour(3, 1, 1);
      const std::string here = epwDateText({month, day, hour});
      const std::string before =
          previous < 0 ? std::string("the header") : epwDateText(epwDateOfLeapHour(previous));
      if (place > expected)
        return fail(fmt::format("{}: {} follows {}: {}", kDateFields, here, before,
                                missingText(expected, place - 1, leap_day_due)));
      if (place < expected)
        return fail(fmt::format(
            "{}: {} follows {}: a duplicated or out-of-order record ({})", kDateFields, here,
            before,
            previous == kEpwLastHour
                ? std::string("the year is complete")
                : fmt::format("{} comes next", epwDateText(epwDateOfLeapHour(expected)))));
      previous = place;
      if (!leap_day) values[*epwHourIndex(month, day, hour)] = illuminance_lx;
    }
    line_ = last_record_line;
    if (previous < 0)
      return fail(
          fmt::format("no records after the header: an EPW file has one per hour, {} "
                      "(1/1 hour 1 to 12/31 hour 24)",
                      kEpwHoursPerYear));
    if (previous < kEpwLastHour)
      return fail(fmt::format(
          "the records end at {}: {}", epwDateText(epwDateOfLeapHour(previous)),
          missingText(previous + 1 == kEpwLeapDayFirstHour ? epwLeapHour(3, 1, 1) : previous + 1,
                      kEpwLastHour,
                      previous + 1 > kEpwLeapDayFirstHour && previous + 1 <= kEpwLeapDayLastHour)));
    return {};
  }

  Result<double> illuminanceField(const std::vector<std::string_view>& fields) const {
    constexpr int kField = kEpwDirectNormalIlluminanceField;
    constexpr std::string_view kName = "Direct Normal Illuminance";
    const std::string_view text = epwTrim(fields[kField - 1]);
    const std::optional<double> value = parseEpwNumber(text);
    if (!value)
      return failField(kField, kName, fmt::format("\"{}\" is not a number", printableText(text)));
    if (*value >= kEpwMissingIlluminanceFromLx && *value <= kEpwMissingIlluminanceLx)
      return failField(kField, kName,
                       fmt::format("{} is the missing-value code (from {} lx): glarecam needs "
                                   "every hour's illuminance",
                                   printableText(text), kEpwMissingIlluminanceFromLx));
    if (*value < 0 || *value > kEpwMaxDirectNormalIlluminanceLx)
      return failField(kField, kName,
                       fmt::format("{} lx is out of range [0, {}]", printableText(text),
                                   kEpwMaxDirectNormalIlluminanceLx));
    return *value;
  }

  std::string file_;
  std::vector<std::string_view> lines_;
  int line_ = 0;
};

}  // namespace

Result<EpwWeather> readEpw(const std::filesystem::path& path) {
  std::string text;
  GLARECAM_ASSIGN(text, readTextFile(path, kMaxEpwFileBytes, "an EPW file"));
  EpwWeather weather;
  GLARECAM_ASSIGN(weather, parseEpw(text, path.string()));
  weather.path = path;
  return weather;
}

Result<EpwWeather> parseEpw(std::string_view text, const std::string& file) {
  return EpwParser(text, file).parse();
}

std::optional<std::size_t> epwHourIndex(int month, int day, int hour) {
  if (month < 1 || month > 12 || day < 1 || day > kEpwDaysInMonth[month - 1] || hour < 1 ||
      hour > 24)
    return std::nullopt;
  return static_cast<std::size_t>((epwDaysBefore(month, false) + day - 1) * 24 + hour - 1);
}

double directNormalIlluminanceLx(const EpwWeather& weather, int month, int day,
                                 double local_standard_hour) {
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  const std::vector<double>& values = weather.direct_normal_illuminance_lx;
  if (values.size() != kEpwHoursPerYear || !std::isfinite(local_standard_hour)) return kNaN;
  if (month == 2 && day == 29) day = 28;
  const std::optional<std::size_t> first_hour = epwHourIndex(month, day, 1);
  if (!first_hour) return kNaN;
  // Hours since 00:00 on 1 January, less half an hour: record i's midpoint is at i exactly.
  const double hours = static_cast<double>(kEpwHoursPerYear);
  double position = std::fmod(static_cast<double>(*first_hour) + local_standard_hour - 0.5, hours);
  if (position < 0) position += hours;
  const double below = std::floor(position);
  const double fraction = position - below;
  const auto i0 = static_cast<std::size_t>(below) % kEpwHoursPerYear;
  const std::size_t i1 = (i0 + 1) % kEpwHoursPerYear;
  return (1.0 - fraction) * values[i0] + fraction * values[i1];
}

double directNormalIlluminanceLx(const EpwWeather& weather, UtcTime utc) {
  using namespace std::chrono;
  const auto offset =
      microseconds(static_cast<std::int64_t>(std::llround(weather.location.utc_offset_h * 3.6e9)));
  const UtcTime local = utc + offset;
  const sys_days day = floor<days>(local);
  const year_month_day date{day};
  const double hour = duration<double, std::ratio<3600>>(local - day).count();
  return directNormalIlluminanceLx(weather, static_cast<int>(static_cast<unsigned>(date.month())),
                                   static_cast<int>(static_cast<unsigned>(date.day())), hour);
}

double greatCircleDistanceKm(double latitude_a_deg, double longitude_a_deg, double latitude_b_deg,
                             double longitude_b_deg) {
  // The central angle as atan2(|a × b|, a · b) of the two unit vectors (the special case of
  // Vincenty's formula for a sphere): well conditioned from coincident points to the antipodes,
  // where the haversine's and the arc cosine's rounding grows to 1e-8 rad.
  const double phi_a = radians(latitude_a_deg);
  const double phi_b = radians(latitude_b_deg);
  const double dlambda = radians(longitude_b_deg - longitude_a_deg);
  const double cross_east = std::cos(phi_b) * std::sin(dlambda);
  const double cross_north =
      std::cos(phi_a) * std::sin(phi_b) - std::sin(phi_a) * std::cos(phi_b) * std::cos(dlambda);
  const double dot =
      std::sin(phi_a) * std::sin(phi_b) + std::cos(phi_a) * std::cos(phi_b) * std::cos(dlambda);
  return kEarthMeanRadiusKm * std::atan2(std::hypot(cross_east, cross_north), dot);
}

double distanceKm(const EpwLocation& location, const SiteLocation& site) {
  return greatCircleDistanceKm(location.latitude_deg, location.longitude_deg, site.latitude_deg,
                               site.longitude_deg);
}

std::optional<std::string> weatherSiteWarning(const EpwWeather& weather, const SiteLocation& site) {
  const double distance_km = distanceKm(weather.location, site);
  if (!(distance_km > kWeatherSiteWarningKm)) return std::nullopt;
  const EpwLocation& l = weather.location;
  return fmt::format(
      "{}: the weather file's station {}{}{} ({:.2f}°, {:.2f}°) is {:.0f} km from the site "
      "({:.4f}°, {:.4f}°), more than {:.0f} km: its sun is another place's",
      weather.path.string(), l.city, l.country.empty() ? "" : ", ", l.country, l.latitude_deg,
      l.longitude_deg, distance_km, site.latitude_deg, site.longitude_deg, kWeatherSiteWarningKm);
}

std::string formatEpw(const EpwLocation& location,
                      std::span<const double> direct_normal_illuminance_lx) {
  const auto name = [](const std::string& text) {
    std::string out = text;
    for (char& c : out)
      if (c == ',' || c == '\n' || c == '\r') c = ' ';
    return out;
  };
  std::string out = fmt::format(
      "LOCATION,{},{},{},{},{},{},{},{},{}\n", name(location.city), name(location.state_province),
      name(location.country), name(location.source), name(location.wmo), location.latitude_deg,
      location.longitude_deg, location.utc_offset_h, location.elevation_m);
  out +=
      "DESIGN CONDITIONS,0\n"
      "TYPICAL/EXTREME PERIODS,0\n"
      "GROUND TEMPERATURES,0\n"
      "HOLIDAYS/DAYLIGHT SAVINGS,No,0,0,0\n"
      "COMMENTS 1,Written by glarecam (sun::formatEpw) for tests: only Direct Normal Illuminance "
      "is data; the other fields are constants or missing-value codes\n"
      "COMMENTS 2,\n"
      // 1 January 2001 was a Monday.
      "DATA PERIODS,1,1,Data,Monday, 1/ 1,12/31\n";
  // Fields 6–17 and 19–35: the flags ("?9": source and uncertainty unknown, as EnergyPlus's own
  // tests write them), then dry bulb, dew point, relative humidity, pressure, six radiations
  // (missing), global horizontal illuminance (missing); after field 18, diffuse illuminance and
  // zenith luminance (missing), wind direction and speed (calm), total and opaque sky cover
  // (clear), visibility (missing), ceiling (77777: unlimited), present weather observation (9:
  // not made) and codes, precipitable water, aerosol optical depth, snow depth, days since
  // snowfall, albedo, liquid precipitation depth and quantity (missing).
  constexpr std::string_view kBefore =
      "?9?9?9?9E0?9?9?9?9?9?9?9?9?9?9?9?9?9*9?9?9?9,20.0,10.0,52,101325,9999,9999,9999,9999,9999,"
      "9999,999999";
  constexpr std::string_view kAfter =
      "999999,9999,0,0.0,0,0,9999,77777,9,999999999,999,.999,999,99,999,999,99";
  const std::size_t count = std::min(direct_normal_illuminance_lx.size(), kEpwHoursPerYear);
  out.reserve(out.size() + count * 160);
  std::size_t i = 0;
  for (int month = 1; month <= 12 && i < count; ++month)
    for (int day = 1; day <= kEpwDaysInMonth[month - 1] && i < count; ++day)
      for (int hour = 1; hour <= 24 && i < count; ++hour, ++i) {
        const double value = direct_normal_illuminance_lx[i];
        out += fmt::format("2001,{},{},{},60,{},", month, day, hour, kBefore);
        out += std::isnan(value) ? fmt::format("{}", kEpwMissingIlluminanceLx)
                                 : fmt::format("{}", value);
        out += fmt::format(",{}\n", kAfter);
      }
  return out;
}

}  // namespace glarecam::sun
