// UTC to the microsecond (utcNow() is the system clock's now at that resolution), and time as
// text: ISO 8601 instants with their zones, fractions and separators, calendar days, and the
// stack-id stamp; invalid text refused naming the problem, and formatting that round-trips.
#include "core/time.h"

#include <gtest/gtest.h>

#include <chrono>
#include <string>
#include <type_traits>

namespace glarecam {
namespace {

TEST(Time, UtcIsCountedInMicroseconds) {
  EXPECT_TRUE((std::is_same_v<UtcTime::duration, std::chrono::microseconds>));
  EXPECT_TRUE((std::is_same_v<UtcTime::clock, std::chrono::system_clock>));
}

TEST(Time, UtcNowIsTheSystemClocksNowTruncatedToTheMicrosecond) {
  const auto before = std::chrono::system_clock::now();
  const UtcTime now = utcNow();
  const auto after = std::chrono::system_clock::now();
  EXPECT_LE(before - std::chrono::microseconds(1), now);
  // Truncated, never rounded up past the system clock's reading.
  EXPECT_LE(now, after);
}

TEST(IsoTime, ParsesZonesFractionsAndSeparators) {
  using namespace std::chrono;
  const UtcTime expected = sys_days{2003y / 10 / 17} + 19h + 30min + 30s;
  const char* same_instant[] = {
      "2003-10-17T19:30:30Z",     "2003-10-17T12:30:30-07:00", "2003-10-17T12:30:30-0700",
      "2003-10-17T12:30:30-07",   "2003-10-18T01:00:30+05:30", "2003-10-18T01:00:30+0530",
      "2003-10-17 19:30:30Z",     "2003-10-17t19:30:30z",      "  2003-10-17T19:30:30Z\n",
      "2003-10-17T19:30:30.000Z", "2003-10-17T19:30:30+00:00", "2003-10-17T19:30:30-00:00",
  };
  for (const char* text : same_instant) {
    const auto parsed = parseIsoTime(text);
    ASSERT_TRUE(parsed) << text << ": " << parsed.error().message;
    EXPECT_EQ(*parsed, expected) << text;
  }
  EXPECT_EQ(*parseIsoTime("2003-10-17T19:30Z"), expected - 30s);
  EXPECT_EQ(*parseIsoTime("2003-10-17T19:30:30.5Z"), expected + 500ms);
  EXPECT_EQ(*parseIsoTime("2003-10-17T19:30:30,25Z"), expected + 250ms);
  EXPECT_EQ(*parseIsoTime("2003-10-17T19:30:30.000125Z"), expected + 125us);
  EXPECT_EQ(*parseIsoTime("2003-10-17T19:30:30.0000004Z"), expected);       // rounded down
  EXPECT_EQ(*parseIsoTime("2003-10-17T19:30:30.9999996Z"), expected + 1s);  // rounded up
  EXPECT_EQ(*parseIsoTime("2024-02-29T00:00:00Z"), UtcTime{sys_days{2024y / 2 / 29}});
  EXPECT_EQ(*parseIsoTime("1969-12-31T23:59:59.5Z"), UtcTime{-500ms});
  EXPECT_EQ(*parseIsoTime("-0500-03-01T00:00:00Z"), UtcTime{sys_days{year{-500} / 3 / 1}});
}

TEST(IsoTime, RefusesTextWithoutZoneOrWithInvalidFields) {
  const auto expectBad = [](const std::string& text, const std::string& fragment) {
    const auto parsed = parseIsoTime(text);
    ASSERT_FALSE(parsed) << text;
    EXPECT_EQ(parsed.error().code, ErrorCode::kBadInput);
    EXPECT_NE(parsed.error().message.find("\"" + text + "\""), std::string::npos)
        << parsed.error().message;
    EXPECT_NE(parsed.error().message.find(fragment), std::string::npos) << parsed.error().message;
  };
  expectBad("2003-10-17T19:30:30", "no time zone; add \"Z\" for UTC or the offset");
  expectBad("2003-10-17 19:30", "no time zone");
  expectBad("2003-02-30T12:00:00Z", "no such date");
  expectBad("2023-02-29T12:00:00Z", "no such date");
  expectBad("2003-13-01T12:00:00Z", "no such date");
  expectBad("2003-10-17T25:00:00Z", "hour 25");
  expectBad("2003-10-17T24:00:00Z", "hour 24");
  expectBad("2003-10-17T12:60:00Z", "minute 60");
  expectBad("2003-10-17T23:59:60Z", "leap seconds");
  expectBad("2003-10-17T12:00:00+19:00", "beyond ±18:00");
  expectBad("2003-10-17T12:00:00+05:75", "beyond ±18:00");
  expectBad("2003-10-17T12:00:00 UTC", "no time zone");
  expectBad("2003-10-17T12:00:00Zjunk", "unexpected text");
  expectBad("2003-10-17T12:00:00.Z", "fraction");
  // ISO 8601 would read this as 12:30:30; a fraction after the minutes is refused, not misread.
  expectBad("2003-10-17T12:30.5Z", "after the seconds only");
  expectBad("2003-10-17", "no time of day");
  expectBad("03-10-17T12:00:00Z", "4-digit year");
  expectBad("20031017T120000Z", "expected ISO 8601");
  expectBad("", "4-digit year");
  expectBad("yesterday", "expected ISO 8601");
}

TEST(IsoTime, FormatsAndRoundTrips) {
  using namespace std::chrono;
  const UtcTime instant = sys_days{2003y / 10 / 17} + 19h + 30min + 30s;
  EXPECT_EQ(formatIsoTime(instant), "2003-10-17T19:30:30Z");
  EXPECT_EQ(formatIsoTime(instant + 500ms), "2003-10-17T19:30:30.5Z");
  EXPECT_EQ(formatIsoTime(instant + 125us), "2003-10-17T19:30:30.000125Z");
  EXPECT_EQ(formatIsoTime(UtcTime{-1us}), "1969-12-31T23:59:59.999999Z");
  EXPECT_EQ(formatIsoTime(UtcTime{sys_days{year{-500} / 3 / 1}}), "-0500-03-01T00:00:00Z");
  EXPECT_EQ(formatIsoTime(UtcTime{sys_days{year{12000} / 1 / 2}}), "+12000-01-02T00:00:00Z");
  for (const UtcTime t : {instant, instant + 123457us, UtcTime{-1us},
                          UtcTime{sys_days{year{-1999} / 12 / 31} + 23h + 1s}}) {
    const auto parsed = parseIsoTime(formatIsoTime(t));
    ASSERT_TRUE(parsed) << formatIsoTime(t) << ": " << parsed.error().message;
    EXPECT_EQ(*parsed, t);
  }
}

TEST(IsoDay, ParsesExactlyTheCalendarDay) {
  using namespace std::chrono;
  EXPECT_EQ(parseIsoDay("2026-06-21").value(), UtcDay{2026y / 6 / 21});
  EXPECT_EQ(parseIsoDay("2024-02-29").value(), UtcDay{2024y / 2 / 29});
  EXPECT_EQ(parseIsoDay("0000-01-01").value(), UtcDay{year{0} / 1 / 1});
  const auto expectBad = [](const std::string& text, const std::string& message) {
    const auto parsed = parseIsoDay(text);
    ASSERT_FALSE(parsed) << text;
    EXPECT_EQ(parsed.error().code, ErrorCode::kBadInput);
    EXPECT_EQ(parsed.error().message, "\"" + text + "\": " + message);
  };
  expectBad("2026-02-30", "no such date");
  expectBad("2026-13-01", "no such date");
  expectBad("2026-06-00", "no such date");
  // sscanf("%4d-%2u-%2u") took these; they are not dates.
  expectBad("2026-06-+1", "expected a date YYYY-MM-DD");
  expectBad("2026-6-21", "expected a date YYYY-MM-DD");
  expectBad("2026-06- 1", "expected a date YYYY-MM-DD");
  expectBad("2026-06-21x", "expected a date YYYY-MM-DD");
  expectBad("2026-06-21T00:00:00Z", "expected a date YYYY-MM-DD");
  expectBad("", "expected a date YYYY-MM-DD");
  expectBad("+2026-06-21", "expected a date YYYY-MM-DD");
}

TEST(IsoDay, FormatsAndRoundTrips) {
  using namespace std::chrono;
  EXPECT_EQ(formatIsoDay(UtcDay{2026y / 6 / 21}), "2026-06-21");
  for (const UtcDay day : {UtcDay{0000y / 1 / 1}, UtcDay{1970y / 1 / 1}, UtcDay{9999y / 12 / 31}})
    EXPECT_EQ(parseIsoDay(formatIsoDay(day)).value(), day);
}

TEST(Calendar, DaysInTheYearAndTheMonth) {
  EXPECT_EQ(daysInYear(2027), 365);
  EXPECT_EQ(daysInYear(2028), 366);
  EXPECT_EQ(daysInYear(2100), 365);  // a century is not a leap year
  EXPECT_EQ(daysInYear(2000), 366);  // unless it divides by 400
  EXPECT_EQ(daysInMonth(2027, 2), 28);
  EXPECT_EQ(daysInMonth(2028, 2), 29);
  EXPECT_EQ(daysInMonth(2100, 2), 28);
  EXPECT_EQ(daysInMonth(2026, 1), 31);
  EXPECT_EQ(daysInMonth(2026, 4), 30);
  EXPECT_EQ(daysInMonth(2026, 12), 31);
  int year_days = 0;
  for (int m = 1; m <= 12; ++m) year_days += daysInMonth(2028, m);
  EXPECT_EQ(year_days, daysInYear(2028));
}

TEST(IsoDay, OfADateTimeIsItsDatePart) {
  using namespace std::chrono;
  EXPECT_EQ(isoDayOf("2026-06-21T23:15:03-05:00"), UtcDay{2026y / 6 / 21});
  EXPECT_EQ(isoDayOf("2026-06-21 10:00"), UtcDay{2026y / 6 / 21});
  EXPECT_EQ(isoDayOf("2026-06-21"), UtcDay{2026y / 6 / 21});
  EXPECT_FALSE(isoDayOf("2026-06-21X"));
  EXPECT_FALSE(isoDayOf("2026-06-+1T00:00:00Z"));
  EXPECT_FALSE(isoDayOf("2026-02-30T00:00:00Z"));
  EXPECT_FALSE(isoDayOf("21.06.2026"));
}

TEST(StackStamp, FormatsWholeSecondsAndReadsTheIdsLeadingStamp) {
  using namespace std::chrono;
  const UtcTime time = sys_days{2026y / 6 / 21} + 10h + 15min + 3s + 999ms;
  EXPECT_EQ(formatStackStamp(time), "20260621T101503Z");
  EXPECT_EQ(formatIsoSeconds(time), "2026-06-21T10:15:03Z");
  EXPECT_EQ(parseStackStamp("20260621T101503Z-a40.00"), floor<seconds>(time));
  EXPECT_EQ(parseStackStamp("20260621T101503Z"), floor<seconds>(time));
  for (const char* bad :
       {"20260621T101503", "20260621T101503X", "20260230T101503Z", "20260621T241503Z",
        "20260621T106003Z", "2026062lT101503Z", "20260621T10+503Z", "zz-not-a-stack", ""})
    EXPECT_FALSE(parseStackStamp(bad)) << bad;
  // The stamp sorts as the time it names.
  EXPECT_LT(formatStackStamp(time), formatStackStamp(time + 1s));
}

}  // namespace
}  // namespace glarecam
