// Time in glarecam: an instant in UTC to the microsecond (the time every stack, sun position and
// schedule uses), the system clock's now as one, and time as text:
//   - ISO 8601 instants, "2003-10-17T19:30:30Z" or "2003-10-17T12:30:30-07:00". The sun's
//     position needs the instant in UTC; a local time read as UTC would put the sun hours off, so
//     text without a zone designator is refused rather than guessed;
//   - ISO 8601 calendar days, "2026-06-21" (a data sheet's date, a day's directory);
//   - the stack-id stamp, "20260621T101503Z": ISO 8601's basic format in whole seconds, which
//     sorts as the time it names and begins every stack's id.
// Parsers return kBadInput naming the text and what is wrong with it.
#pragma once

#include <chrono>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

#include "core/error.h"

namespace glarecam {

using UtcTime = std::chrono::sys_time<std::chrono::microseconds>;
using UtcDay = std::chrono::sys_days;

// The system clock now (whether it can be trusted is sun/clock_sync.h's question).
inline UtcTime utcNow() {
  return std::chrono::time_point_cast<std::chrono::microseconds>(std::chrono::system_clock::now());
}

// Parses YYYY-MM-DD, then "T", "t" or a space, then hh:mm[:ss[.fraction]], then "Z", "z", ±hh:mm,
// ±hhmm or ±hh. Fractions finer than a microsecond are rounded to one. Years are 4 digits, or a
// sign and 4 or 5 (proleptic Gregorian, as std::chrono). Surrounding white space is ignored.
// kBadInput naming the text for anything else: a missing zone, an invalid date (February 30), an
// hour of 24 or more, a minute or second of 60 or more (leap seconds included), an offset beyond
// ±18:00.
Result<UtcTime> parseIsoTime(std::string_view text);

// "2003-10-17T19:30:30Z", with ".5" or ".000125" when the fraction of a second is not zero
// (trailing zeros dropped): parseIsoTime(formatIsoTime(t)) == t.
std::string formatIsoTime(UtcTime utc);
// "2003-10-17T19:30:30Z": the whole seconds only (a manifest's captured_at).
std::string formatIsoSeconds(UtcTime utc);

// Parses exactly YYYY-MM-DD (4-digit year); "no such date" for February 30, "expected a date
// YYYY-MM-DD" for anything else ("2026-6-21", "2026-06-+1", trailing text).
Result<UtcDay> parseIsoDay(std::string_view text);
// The day an ISO 8601 date or date-time names by its date part: "2026-06-21" of
// "2026-06-21T10:15:03Z" (as written, whatever its zone), nullopt when it does not begin with one.
std::optional<UtcDay> isoDayOf(std::string_view text);
// "2026-06-21"; parseIsoDay(formatIsoDay(d)) == d for the years 0000 to 9999.
std::string formatIsoDay(UtcDay day);

// Days in a year, and in a month (1 to 12) of it, in the proleptic Gregorian calendar.
int daysInYear(int year);
int daysInMonth(int year, int month);

// The stack-id stamp: "20260621T101503Z", kStackStampLength characters.
inline constexpr std::size_t kStackStampLength = 16;
std::string formatStackStamp(UtcTime utc);
// The instant a stack id's leading stamp names (the rest of the id ignored), or nullopt when it
// does not begin with a valid one.
std::optional<std::chrono::sys_seconds> parseStackStamp(std::string_view id);

}  // namespace glarecam
