#include "sun/epw_weather.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "core/time.h"
#include "support/test_support.h"

namespace glarecam::sun {
namespace {

using testing::TempDir;
using testing::testDataDir;

EpwLocation epwTestLocation() {
  return {.city = "Test.Station",
          .state_province = "-",
          .country = "NLD",
          .source = "glarecam test",
          .wmo = "062400",
          .latitude_deg = 52.3,
          .longitude_deg = 4.77,
          .utc_offset_h = 1.0,
          .elevation_m = -2.0};
}

// A year of distinct values, none a whole number of lux (so the writer's shortest form is
// exercised), from 0.25 lx to about 120 klx.
std::vector<double> epwTestYear() {
  std::vector<double> values(kEpwHoursPerYear);
  for (std::size_t i = 0; i < values.size(); ++i)
    values[i] = static_cast<double>((i * 7919) % 120'000) + 0.25;
  return values;
}

std::string epwTestText() { return formatEpw(epwTestLocation(), epwTestYear()); }

std::vector<std::string> epwLines(const std::string& text) {
  std::vector<std::string> lines;
  std::size_t start = 0;
  while (start < text.size()) {
    const std::size_t end = text.find('\n', start);
    lines.push_back(text.substr(start, end - start));
    if (end == std::string::npos) break;
    start = end + 1;
  }
  return lines;
}

std::string epwJoin(const std::vector<std::string>& lines) {
  std::string text;
  for (const std::string& line : lines) text += line + "\n";
  return text;
}

// The file's line `number` (1-based) of formatEpw's year with field `field` (1-based) replaced.
std::string epwWithField(int number, int field, const std::string& value) {
  std::vector<std::string> lines = epwLines(epwTestText());
  std::string& line = lines[number - 1];
  std::size_t start = 0;
  for (int f = 1; f < field; ++f) start = line.find(',', start) + 1;
  const std::size_t end = line.find(',', start);
  line.replace(start, end == std::string::npos ? std::string::npos : end - start, value);
  return epwJoin(lines);
}

std::string epwWithLine(int number, const std::string& content) {
  std::vector<std::string> lines = epwLines(epwTestText());
  lines[number - 1] = content;
  return epwJoin(lines);
}

// The line of formatEpw's record of `month`/`day` `hour`.
int epwLineOf(int month, int day, int hour) {
  return 9 + static_cast<int>(*epwHourIndex(month, day, hour));
}

std::string epwError(const std::string& text) {
  const Result<EpwWeather> weather = parseEpw(text, "weather.epw");
  if (weather) return "(no error)";
  EXPECT_EQ(weather.error().code, ErrorCode::kBadInput) << weather.error().message;
  return weather.error().message;
}

// ---- reading ----------------------------------------------------------------------------------

TEST(EpwWeather, FormatEpwRoundTripsEveryValueAndTheLocation) {
  const std::vector<double> values = epwTestYear();
  const auto weather = parseEpw(epwTestText(), "weather.epw");
  ASSERT_TRUE(weather) << weather.error().message;
  EXPECT_EQ(weather->path, "weather.epw");
  const EpwLocation& l = weather->location;
  EXPECT_EQ(l.city, "Test.Station");
  EXPECT_EQ(l.state_province, "-");
  EXPECT_EQ(l.country, "NLD");
  EXPECT_EQ(l.source, "glarecam test");
  EXPECT_EQ(l.wmo, "062400");
  EXPECT_EQ(l.latitude_deg, 52.3);
  EXPECT_EQ(l.longitude_deg, 4.77);
  EXPECT_EQ(l.utc_offset_h, 1.0);
  EXPECT_EQ(l.elevation_m, -2.0);
  EXPECT_EQ(weather->direct_normal_illuminance_lx, values);  // the shortest form is exact
}

TEST(EpwWeather, FormatEpwWritesThirtyFiveFieldsAndTheMissingCodeForNaN) {
  std::vector<double> values(kEpwHoursPerYear, 1000.0);
  values[5] = std::nan("");
  const std::vector<std::string> lines = epwLines(formatEpw(epwTestLocation(), values));
  ASSERT_EQ(lines.size(), 8 + kEpwHoursPerYear);
  EXPECT_EQ(lines[0], "LOCATION,Test.Station,-,NLD,glarecam test,062400,52.3,4.77,1,-2");
  for (const std::string& line : {lines[8], lines[13], lines.back()})
    EXPECT_EQ(std::count(line.begin(), line.end(), ','), kEpwFieldsPerRecord - 1) << line;
  EXPECT_TRUE(lines[13].starts_with("2001,1,1,6,60,")) << lines[13];
  EXPECT_EQ(epwError(epwJoin(lines)),
            "weather.epw:14: field 18 \"Direct Normal Illuminance\": 999999 is the missing-value "
            "code (from 999900 lx): glarecam needs every hour's illuminance");
  // Names cannot break the line into fields.
  EpwLocation location = epwTestLocation();
  location.city = "Den Haag, Zuid-Holland";
  const auto weather =
      parseEpw(formatEpw(location, std::vector<double>(kEpwHoursPerYear, 0.0)), "weather.epw");
  ASSERT_TRUE(weather) << weather.error().message;
  EXPECT_EQ(weather->location.city, "Den Haag  Zuid-Holland");
}

TEST(EpwWeather, ReadEpwReadsAFileAndKeepsItsPath) {
  TempDir dir;
  testing::writeText(dir / "site.epw", epwTestText());
  const auto weather = readEpw(dir / "site.epw");
  ASSERT_TRUE(weather) << weather.error().message;
  EXPECT_EQ(weather->path, dir / "site.epw");
  EXPECT_EQ(weather->direct_normal_illuminance_lx, epwTestYear());
  const auto missing = readEpw(dir / "absent.epw");
  ASSERT_FALSE(missing);
  EXPECT_EQ(missing.error().code, ErrorCode::kBadInput);
  EXPECT_NE(missing.error().message.find("absent.epw"), std::string::npos);
}

// tests/data/weather/freiburg-two-days.epw: a header as climate.onebuilding.org's TMYx files
// write it (ASHRAE design conditions, typical and extreme periods, three depths of ground
// temperatures, quoted comments holding commas), CRLF line ends, and the 48 records of 1 and 2
// January from 2009 with every field filled; the test appends the rest of the year from 2001
// (formatEpw's), so the file mixes years as a typical year does.
TEST(EpwWeather, ARealFormatFileReadsItsHeaderAndRecords) {
  const std::string fixture = testing::readText(testDataDir() / "weather/freiburg-two-days.epw");
  EXPECT_EQ(epwError(fixture),
            "weather.epw:56: the records end at 1/2 hour 24: 1/3 hour 1 to 12/31 hour 24 are "
            "missing (8712 hours)");
  const std::vector<std::string> year = epwLines(epwTestText());
  std::string text = fixture;
  for (std::size_t i = 8 + 48; i < year.size(); ++i) text += year[i] + "\n";
  const auto weather = parseEpw(text, "freiburg.epw");
  ASSERT_TRUE(weather) << weather.error().message;
  const EpwLocation& l = weather->location;
  EXPECT_EQ(l.city, "Freiburg.im.Breisgau");
  EXPECT_EQ(l.state_province, "BW");
  EXPECT_EQ(l.country, "DEU");
  EXPECT_EQ(l.source, "SRC-TMYx");
  EXPECT_EQ(l.wmo, "108030");
  EXPECT_EQ(l.latitude_deg, 48.023);
  EXPECT_EQ(l.longitude_deg, 7.834);
  EXPECT_EQ(l.utc_offset_h, 1.0);
  EXPECT_EQ(l.elevation_m, 237.0);
  const std::vector<double>& v = weather->direct_normal_illuminance_lx;
  EXPECT_EQ(v[*epwHourIndex(1, 1, 12)], 0.0);  // the overcast first day
  EXPECT_EQ(v[*epwHourIndex(1, 2, 9)], 2100.0);
  EXPECT_EQ(v[*epwHourIndex(1, 2, 13)], 66800.0);
  EXPECT_EQ(v[*epwHourIndex(1, 3, 1)], epwTestYear()[48]);
  EXPECT_EQ(directNormalIlluminanceLx(*weather, 1, 2, 12.5), 66800.0);
  EXPECT_EQ(directNormalIlluminanceLx(*weather, 1, 2, 12.0), (63100.0 + 66800.0) / 2);
}

TEST(EpwWeather, AcceptsAByteOrderMarkTrailingEmptyLinesAndTheDictionarysSpellings) {
  EXPECT_TRUE(parseEpw("\xEF\xBB\xBF" + epwTestText(), "weather.epw"));
  EXPECT_TRUE(parseEpw(epwTestText() + "\n\r\n  \n", "weather.epw"));
  EXPECT_TRUE(parseEpw(epwWithLine(5, "HOLIDAYS/DAYLIGHT SAVING,No,0,0,0"), "weather.epw"));
  std::string lower = epwTestText();
  lower.replace(0, 8, "location");
  EXPECT_TRUE(parseEpw(lower, "weather.epw"));
}

TEST(EpwWeather, RecordsOfThirtyToThirtyFiveFieldsAreRead) {
  // EnergyPlus reads records that end after field 30 (Aerosol Optical Depth).
  std::vector<std::string> lines = epwLines(epwTestText());
  for (std::size_t i = 8; i < lines.size(); i += 2) {
    std::string& line = lines[i];
    for (int drop = 0; drop < 5; ++drop) line.erase(line.rfind(','));
  }
  const auto weather = parseEpw(epwJoin(lines), "weather.epw");
  ASSERT_TRUE(weather) << weather.error().message;
  EXPECT_EQ(weather->direct_normal_illuminance_lx, epwTestYear());
}

TEST(EpwWeather, ALeapYearsTwentyNinthOfFebruaryIsCheckedAndDropped) {
  std::vector<std::string> lines = epwLines(epwTestText());
  const int after = epwLineOf(2, 28, 24);  // 1-based: insert after this line
  std::vector<std::string> leap_day;
  for (int hour = 1; hour <= 24; ++hour)
    leap_day.push_back(fmt::format(
        "2004,2,29,{},60,?9,20.0,10.0,52,101325,9999,9999,9999,9999,9999,9999,999999,{},999999,"
        "9999,0,0.0,0,0,9999,77777,9,999999999,999,.999,999,99,999,999,99",
        hour, 5000 + hour));
  std::vector<std::string> with_leap_day = lines;
  with_leap_day.insert(with_leap_day.begin() + after, leap_day.begin(), leap_day.end());
  const auto weather = parseEpw(epwJoin(with_leap_day), "weather.epw");
  ASSERT_TRUE(weather) << weather.error().message;
  EXPECT_EQ(weather->direct_normal_illuminance_lx, epwTestYear());

  // Once begun, the day runs to its end.
  std::vector<std::string> partial = lines;
  partial.insert(partial.begin() + after, leap_day.begin(), leap_day.begin() + 5);
  EXPECT_EQ(epwError(epwJoin(partial)),
            fmt::format("weather.epw:{}: fields 2-4 (Month, Day, Hour): 3/1 hour 1 follows 2/29 "
                        "hour 5: 2/29 hour 6 to 2/29 hour 24 are missing (19 hours)",
                        after + 6));
  // A gap across it counts the hours of a 365-day year.
  std::vector<std::string> gap = lines;
  gap.erase(gap.begin() + epwLineOf(2, 28, 10) - 1, gap.begin() + epwLineOf(3, 1, 3) - 1);
  EXPECT_EQ(epwError(epwJoin(gap)),
            fmt::format("weather.epw:{}: fields 2-4 (Month, Day, Hour): 3/1 hour 3 follows 2/28 "
                        "hour 9: 2/28 hour 10 to 3/1 hour 2 are missing (17 hours)",
                        epwLineOf(2, 28, 10)));
  std::vector<std::string> to_march = lines;
  to_march.erase(to_march.begin() + epwLineOf(2, 28, 10) - 1,
                 to_march.begin() + epwLineOf(3, 1, 1) - 1);
  EXPECT_EQ(epwError(epwJoin(to_march)),
            fmt::format("weather.epw:{}: fields 2-4 (Month, Day, Hour): 3/1 hour 1 follows 2/28 "
                        "hour 9: 2/28 hour 10 to 2/28 hour 24 are missing (15 hours)",
                        epwLineOf(2, 28, 10)));
}

// ---- bad files: each names the file, the line and the field -----------------------------------

TEST(EpwWeather, AHeaderLineOutOfPlaceOrAShortHeaderIsRefused) {
  EXPECT_EQ(epwError(epwWithLine(3, "GROUND TEMPERATURES,0")),
            "weather.epw:3: expected the header line TYPICAL/EXTREME PERIODS (line 3 of an EPW "
            "file's 8: LOCATION, ..., DATA PERIODS), found \"GROUND TEMPERATURES,0\"");
  std::vector<std::string> lines = epwLines(epwTestText());
  lines.erase(lines.begin() + 1);  // no DESIGN CONDITIONS: the records begin at line 8
  EXPECT_EQ(epwError(epwJoin(lines)),
            "weather.epw:2: expected the header line DESIGN CONDITIONS (line 2 of an EPW file's "
            "8: LOCATION, ..., DATA PERIODS), found \"TYPICAL/EXTREME PERIODS,0\"");
  lines = epwLines(epwTestText());
  lines.resize(5);
  EXPECT_EQ(epwError(epwJoin(lines)),
            "weather.epw:6: the file ends in its header: an EPW file begins with 8 header lines "
            "(LOCATION ... DATA PERIODS)");
  EXPECT_EQ(epwError(""),
            "weather.epw:1: the file ends in its header: an EPW file begins with 8 header lines "
            "(LOCATION ... DATA PERIODS)");
  lines = epwLines(epwTestText());
  lines.resize(8);
  EXPECT_EQ(epwError(epwJoin(lines)),
            "weather.epw:8: no records after the header: an EPW file has one per hour, 8760 (1/1 "
            "hour 1 to 12/31 hour 24)");
}

TEST(EpwWeather, AMalformedOrOutOfRangeLocationIsRefused) {
  EXPECT_EQ(epwError(epwWithLine(1, "LOCATION,Test,-,NLD,src,062400,52.3,4.77,1.0")),
            "weather.epw:1: LOCATION has 9 fields where it has 10 (LOCATION, city, state or "
            "province, country, source, WMO, latitude, longitude, time zone, elevation)");
  EXPECT_EQ(epwError(epwWithField(1, 7, "52N")),
            "weather.epw:1: field 7 \"Latitude\": \"52N\" is not a number");
  EXPECT_EQ(epwError(epwWithField(1, 7, "95.0")),
            "weather.epw:1: field 7 \"Latitude\": 95.0° is out of range [-90, 90]");
  EXPECT_EQ(epwError(epwWithField(1, 8, "-180.5")),
            "weather.epw:1: field 8 \"Longitude\": -180.5° is out of range [-180, 180]");
  EXPECT_EQ(epwError(epwWithField(1, 9, "15")),
            "weather.epw:1: field 9 \"TimeZone\": 15 h is out of range [-12, 14]");
  EXPECT_EQ(epwError(epwWithField(1, 9, "")),
            "weather.epw:1: field 9 \"TimeZone\": \"\" is not a number");
  EXPECT_EQ(epwError(epwWithField(1, 10, "9999.9")),
            "weather.epw:1: field 10 \"Elevation\": 9999.9 m is out of range [-1000, 9999.9)");
  EXPECT_TRUE(parseEpw(epwWithField(1, 9, "+13.0"), "weather.epw"));  // Tonga
}

TEST(EpwWeather, ASubHourlyOrMalformedDataPeriodsIsRefused) {
  EXPECT_EQ(epwError(epwWithField(8, 3, "4")),
            "weather.epw:8: field 3 \"Number of Records per hour\": 4 records per hour: a "
            "sub-hourly file (glarecam reads hourly EPW files, 1 record per hour)");
  EXPECT_EQ(epwError(epwWithField(8, 3, "one")),
            "weather.epw:8: field 3 \"Number of Records per hour\": \"one\" is not a whole "
            "number of at least 1");
  EXPECT_EQ(epwError(epwWithField(8, 2, "0")),
            "weather.epw:8: field 2 \"Number of Data Periods\": \"0\" is not a whole number of at "
            "least 1");
  EXPECT_EQ(epwError(epwWithLine(8, "DATA PERIODS,1")),
            "weather.epw:8: DATA PERIODS has 2 fields: it needs at least the number of data "
            "periods and the number of records per hour");
}

TEST(EpwWeather, ARecordWithTooFewOrTooManyFieldsIsRefused) {
  const int line = epwLineOf(3, 2, 7);
  std::vector<std::string> lines = epwLines(epwTestText());
  lines[line - 1] += ",0";
  EXPECT_EQ(epwError(epwJoin(lines)),
            fmt::format("weather.epw:{}: 36 fields where an EPW record has 35 (30 to 35 accepted)",
                        line));
  lines = epwLines(epwTestText());
  for (int drop = 0; drop < 6; ++drop) lines[line - 1].erase(lines[line - 1].rfind(','));
  EXPECT_EQ(epwError(epwJoin(lines)),
            fmt::format("weather.epw:{}: 29 fields where an EPW record has 35 (30 to 35 accepted)",
                        line));
  EXPECT_EQ(
      epwError(epwWithLine(line, "2001;3;2;7;60")),
      fmt::format("weather.epw:{}: 1 fields where an EPW record has 35 (30 to 35 accepted)", line));
}

TEST(EpwWeather, ANonNumericOrOutOfRangeDateIsRefused) {
  const int line = epwLineOf(4, 30, 5);
  const auto expect = [&](int field, const std::string& value, const std::string& message) {
    EXPECT_EQ(epwError(epwWithField(line, field, value)),
              fmt::format("weather.epw:{}: {}", line, message));
  };
  expect(2, "Apr", "field 2 \"Month\": \"Apr\" is not a whole number");
  expect(2, "13", "field 2 \"Month\": 13 is out of range [1, 12]");
  expect(3, "31", "field 3 \"Day\": 31 is out of range [1, 30]");
  expect(3, "4.5", "field 3 \"Day\": \"4.5\" is not a whole number");
  expect(4, "0", "field 4 \"Hour\": 0 is out of range [1, 24]");
  expect(4, "25", "field 4 \"Hour\": 25 is out of range [1, 24]");
  expect(5, "61", "field 5 \"Minute\": 61 is out of range [0, 60]");
  const int february = epwLineOf(2, 28, 5);
  EXPECT_EQ(epwError(epwWithField(february, 3, "30")),
            fmt::format("weather.epw:{}: field 3 \"Day\": 30 is out of range [1, 29]", february));
  // The year is not read: a typical year's months come from different years.
  EXPECT_TRUE(parseEpw(epwWithField(line, 1, "1987"), "weather.epw"));
  EXPECT_TRUE(parseEpw(epwWithField(line, 5, "0"), "weather.epw"));
}

TEST(EpwWeather, AMissingNonNumericOrOutOfRangeIlluminanceIsRefused) {
  const int line = epwLineOf(7, 14, 13);
  const auto expect = [&](const std::string& value, const std::string& problem) {
    EXPECT_EQ(
        epwError(epwWithField(line, 18, value)),
        fmt::format("weather.epw:{}: field 18 \"Direct Normal Illuminance\": {}", line, problem));
  };
  expect("1.2e6", "1.2e6 lx is out of range [0, 200000]");
  expect("200001", "200001 lx is out of range [0, 200000]");
  expect("1000000", "1000000 lx is out of range [0, 200000]");
  expect("-1", "-1 lx is out of range [0, 200000]");
  expect("999999",
         "999999 is the missing-value code (from 999900 lx): glarecam needs every hour's "
         "illuminance");
  expect("999900",
         "999900 is the missing-value code (from 999900 lx): glarecam needs every hour's "
         "illuminance");
  expect("bright", "\"bright\" is not a number");
  expect("", "\"\" is not a number");
  expect("nan", "\"nan\" is not a number");
  expect("inf", "\"inf\" is not a number");
  expect("85000lx", "\"85000lx\" is not a number");
  EXPECT_TRUE(parseEpw(epwWithField(line, 18, "200000"), "weather.epw"));
  EXPECT_TRUE(parseEpw(epwWithField(line, 18, " +85000.5 "), "weather.epw"));
}

TEST(EpwWeather, AMissingDuplicatedOrOutOfOrderHourIsRefused) {
  const std::string text = epwTestText();
  const int line = epwLineOf(1, 3, 4);
  std::vector<std::string> lines = epwLines(text);
  lines.erase(lines.begin() + line - 1);
  EXPECT_EQ(epwError(epwJoin(lines)),
            fmt::format("weather.epw:{}: fields 2-4 (Month, Day, Hour): 1/3 hour 5 follows 1/3 "
                        "hour 3: 1/3 hour 4 is missing",
                        line));

  lines = epwLines(text);
  lines.erase(lines.begin() + epwLineOf(1, 3, 1) - 1, lines.begin() + epwLineOf(1, 4, 1) - 1);
  EXPECT_EQ(epwError(epwJoin(lines)),
            fmt::format("weather.epw:{}: fields 2-4 (Month, Day, Hour): 1/4 hour 1 follows 1/2 "
                        "hour 24: 1/3 hour 1 to 1/3 hour 24 are missing (24 hours)",
                        epwLineOf(1, 3, 1)));

  lines = epwLines(text);
  lines.insert(lines.begin() + line, lines[line - 1]);
  EXPECT_EQ(epwError(epwJoin(lines)),
            fmt::format("weather.epw:{}: fields 2-4 (Month, Day, Hour): 1/3 hour 4 follows 1/3 "
                        "hour 4: a duplicated or out-of-order record (1/3 hour 5 comes next)",
                        line + 1));

  lines = epwLines(text);
  std::swap(lines[line - 1], lines[line]);
  EXPECT_EQ(epwError(epwJoin(lines)),
            fmt::format("weather.epw:{}: fields 2-4 (Month, Day, Hour): 1/3 hour 5 follows 1/3 "
                        "hour 3: 1/3 hour 4 is missing",
                        line));
  // The same two records in order but the later one first in the month.
  lines = epwLines(text);
  lines[line] = lines[epwLineOf(1, 3, 2) - 1];
  EXPECT_EQ(epwError(epwJoin(lines)),
            fmt::format("weather.epw:{}: fields 2-4 (Month, Day, Hour): 1/3 hour 2 follows 1/3 "
                        "hour 4: a duplicated or out-of-order record (1/3 hour 5 comes next)",
                        line + 1));

  lines = epwLines(text);
  lines.erase(lines.begin() + 8);
  EXPECT_EQ(epwError(epwJoin(lines)),
            "weather.epw:9: fields 2-4 (Month, Day, Hour): 1/1 hour 2 follows the header: 1/1 "
            "hour 1 is missing");
}

TEST(EpwWeather, AFileThatEndsEarlyOrRunsOnIsRefused) {
  std::vector<std::string> lines = epwLines(epwTestText());
  lines.resize(lines.size() - 24);
  EXPECT_EQ(epwError(epwJoin(lines)),
            fmt::format("weather.epw:{}: the records end at 12/30 hour 24: 12/31 hour 1 to 12/31 "
                        "hour 24 are missing (24 hours)",
                        8 + kEpwHoursPerYear - 24));
  lines = epwLines(epwTestText());
  lines.push_back(lines[8]);
  EXPECT_EQ(epwError(epwJoin(lines)),
            fmt::format("weather.epw:{}: fields 2-4 (Month, Day, Hour): 1/1 hour 1 follows 12/31 "
                        "hour 24: a duplicated or out-of-order record (the year is complete)",
                        9 + kEpwHoursPerYear));
  lines = epwLines(epwTestText());
  lines[99] = "";
  EXPECT_EQ(epwError(epwJoin(lines)), "weather.epw:100: an empty line among the records");
  // formatEpw's short years end early the same way.
  EXPECT_EQ(epwError(formatEpw(epwTestLocation(), std::vector<double>(10, 0.0))),
            "weather.epw:18: the records end at 1/1 hour 10: 1/1 hour 11 to 12/31 hour 24 are "
            "missing (8750 hours)");
}

// ---- interpolation ----------------------------------------------------------------------------

TEST(EpwWeather, EachRecordHoldsAtItsHoursMidpointAndIsLinearBetween) {
  const auto weather = parseEpw(epwTestText(), "weather.epw");
  ASSERT_TRUE(weather);
  const std::vector<double> v = epwTestYear();
  for (const auto [month, day, hour] :
       {std::array{1, 1, 1}, std::array{1, 1, 13}, std::array{3, 1, 1}, std::array{6, 21, 12},
        std::array{12, 31, 24}}) {
    const std::size_t i = *epwHourIndex(month, day, hour);
    // Record `hour` is the mean over the hour ending at `hour`: its midpoint is hour − 0.5.
    EXPECT_EQ(directNormalIlluminanceLx(*weather, month, day, hour - 0.5), v[i]);
    if (i + 1 < v.size()) {
      // Quarter hours are exact in binary: the interpolation is exact to rounding.
      EXPECT_DOUBLE_EQ(directNormalIlluminanceLx(*weather, month, day, hour - 0.25),
                       0.75 * v[i] + 0.25 * v[i + 1]);
      EXPECT_DOUBLE_EQ(directNormalIlluminanceLx(*weather, month, day, hour),
                       0.5 * v[i] + 0.5 * v[i + 1]);
    }
  }
  // An hour beyond 24 runs on into the next day.
  EXPECT_EQ(directNormalIlluminanceLx(*weather, 1, 1, 24.5), v[*epwHourIndex(1, 2, 1)]);
  EXPECT_EQ(directNormalIlluminanceLx(*weather, 1, 2, -0.5), v[*epwHourIndex(1, 1, 24)]);
}

TEST(EpwWeather, TheYearWrapsAroundFromTheThirtyFirstOfDecemberToTheFirstOfJanuary) {
  const auto weather = parseEpw(epwTestText(), "weather.epw");
  ASSERT_TRUE(weather);
  const std::vector<double> v = epwTestYear();
  const double last = v.back();    // 31 December hour 24: 23:00–24:00, at 23:30
  const double first = v.front();  // 1 January hour 1: 00:00–01:00, at 00:30
  EXPECT_DOUBLE_EQ(directNormalIlluminanceLx(*weather, 12, 31, 23.75), 0.75 * last + 0.25 * first);
  EXPECT_DOUBLE_EQ(directNormalIlluminanceLx(*weather, 12, 31, 24.0), 0.5 * last + 0.5 * first);
  EXPECT_DOUBLE_EQ(directNormalIlluminanceLx(*weather, 1, 1, 0.0), 0.5 * last + 0.5 * first);
  EXPECT_DOUBLE_EQ(directNormalIlluminanceLx(*weather, 1, 1, 0.25), 0.25 * last + 0.75 * first);
}

TEST(EpwWeather, TheTwentyNinthOfFebruaryIsTheTwentyEighth) {
  const auto weather = parseEpw(epwTestText(), "weather.epw");
  ASSERT_TRUE(weather);
  for (double hour : {0.0, 0.5, 6.25, 12.5, 23.9, 24.0})
    EXPECT_EQ(directNormalIlluminanceLx(*weather, 2, 29, hour),
              directNormalIlluminanceLx(*weather, 2, 28, hour))
        << hour;
  // Through UTC: 11:30Z on 29 February 2024 is 12:30 in the file's UTC+1, hour 13's midpoint.
  const UtcTime utc = std::chrono::sys_days{std::chrono::year{2024} / 2 / 29} +
                      std::chrono::hours{11} + std::chrono::minutes{30};
  EXPECT_EQ(directNormalIlluminanceLx(*weather, utc), epwTestYear()[*epwHourIndex(2, 28, 13)]);
}

TEST(EpwWeather, AnInstantInUtcIsReadInTheFilesStandardTime) {
  EpwLocation location = epwTestLocation();
  location.utc_offset_h = -5;  // New York's standard time
  const auto weather = parseEpw(formatEpw(location, epwTestYear()), "weather.epw");
  ASSERT_TRUE(weather);
  const std::vector<double> v = epwTestYear();
  // 03:00Z on 1 January 2026 is 22:00 on 31 December: midway between hour 22 (21:30) and hour
  // 23 (22:30) of 31 December, whatever the year.
  const UtcTime utc =
      std::chrono::sys_days{std::chrono::year{2026} / 1 / 1} + std::chrono::hours{3};
  EXPECT_DOUBLE_EQ(directNormalIlluminanceLx(*weather, utc),
                   0.5 * v[*epwHourIndex(12, 31, 22)] + 0.5 * v[*epwHourIndex(12, 31, 23)]);
  // Summer: 17:30Z on 21 June 2026 is 12:30 EST (13:30 EDT: the file keeps no daylight saving).
  const UtcTime june = std::chrono::sys_days{std::chrono::year{2026} / 6 / 21} +
                       std::chrono::hours{17} + std::chrono::minutes{30};
  EXPECT_EQ(directNormalIlluminanceLx(*weather, june), v[*epwHourIndex(6, 21, 13)]);
  // A half-hour zone (India, UTC+5:30).
  location.utc_offset_h = 5.5;
  const auto india = parseEpw(formatEpw(location, epwTestYear()), "weather.epw");
  ASSERT_TRUE(india);
  EXPECT_EQ(
      directNormalIlluminanceLx(*india, june - std::chrono::hours{10} - std::chrono::minutes{30}),
      v[*epwHourIndex(6, 21, 13)]);  // 07:00Z + 5:30 = 12:30
}

TEST(EpwWeather, InterpolatedValuesAreNeverNegativeAndBadQueriesAreNaN) {
  std::vector<double> values(kEpwHoursPerYear, 0.0);
  for (std::size_t i = 0; i < values.size(); ++i)
    if (i % 24 >= 7 && i % 24 <= 16) values[i] = 1000.0 * static_cast<double>(i % 24 - 6);
  const auto weather = parseEpw(formatEpw(epwTestLocation(), values), "weather.epw");
  ASSERT_TRUE(weather);
  for (int step = 0; step < 2000; ++step) {
    const double hour = step * 0.0123;
    EXPECT_GE(directNormalIlluminanceLx(*weather, 5, 17, hour), 0.0) << hour;
  }
  EXPECT_EQ(directNormalIlluminanceLx(*weather, 5, 17, 3.0), 0.0);  // night: both records 0
  EXPECT_TRUE(std::isnan(directNormalIlluminanceLx(*weather, 13, 1, 12.0)));
  EXPECT_TRUE(std::isnan(directNormalIlluminanceLx(*weather, 4, 31, 12.0)));
  EXPECT_TRUE(std::isnan(directNormalIlluminanceLx(*weather, 4, 1, std::nan(""))));
  EXPECT_TRUE(std::isnan(directNormalIlluminanceLx(EpwWeather{}, 4, 1, 12.0)));
  EXPECT_EQ(epwHourIndex(2, 29, 1), std::nullopt);
  EXPECT_EQ(epwHourIndex(1, 1, 0), std::nullopt);
  EXPECT_EQ(epwHourIndex(12, 31, 24), kEpwHoursPerYear - 1);
}

// ---- distance ---------------------------------------------------------------------------------

TEST(EpwWeather, DistanceIsTheGreatCircleOnTheMeanSphere) {
  const double degree_km = kEarthMeanRadiusKm * std::numbers::pi / 180;  // 111.195 km
  EXPECT_NEAR(greatCircleDistanceKm(0, 0, 1, 0), degree_km, 1e-9);
  EXPECT_NEAR(greatCircleDistanceKm(52, 4, 53, 4), degree_km, 1e-9);  // along a meridian
  EXPECT_NEAR(greatCircleDistanceKm(0, 0, 0, 90), kEarthMeanRadiusKm * std::numbers::pi / 2, 1e-9);
  EXPECT_NEAR(greatCircleDistanceKm(10, 20, -10, -160), kEarthMeanRadiusKm * std::numbers::pi,
              1e-6);                                                         // antipodes
  EXPECT_NEAR(greatCircleDistanceKm(0, 179.5, 0, -179.5), degree_km, 1e-9);  // across 180°
  // At 60° a degree of longitude is cos 60° as long, to second order in the small angle.
  EXPECT_NEAR(greatCircleDistanceKm(60, 10, 60, 10.1), 0.1 * degree_km * 0.5, 1e-3);
  SiteLocation site;
  site.latitude_deg = 52.3;
  site.longitude_deg = 4.77;
  EXPECT_EQ(distanceKm(epwTestLocation(), site), 0.0);
}

TEST(EpwWeather, AFileFartherThanFiftyKilometresFromTheSiteIsWarnedAbout) {
  const auto weather = parseEpw(epwTestText(), "weather.epw");
  ASSERT_TRUE(weather);
  SiteLocation site;
  site.latitude_deg = 52.3 + 0.44;  // 48.9 km north
  site.longitude_deg = 4.77;
  EXPECT_EQ(weatherSiteWarning(*weather, site), std::nullopt);
  site.latitude_deg = 52.3 + 0.46;  // 51.2 km north
  EXPECT_EQ(weatherSiteWarning(*weather, site),
            "weather.epw: the weather file's station Test.Station, NLD (52.30°, 4.77°) is 51 km "
            "from the site (52.7600°, 4.7700°), more than 50 km: its sun is another place's");
}

}  // namespace
}  // namespace glarecam::sun
