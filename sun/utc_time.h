// Instants as ISO 8601 text: "2003-10-17T19:30:30Z", "2003-10-17T12:30:30-07:00". The sun's
// position needs the instant in UTC; a local time read as UTC would put the sun hours off, so text
// without a zone designator is refused rather than guessed.
#pragma once

#include <chrono>
#include <string>
#include <string_view>

#include "core/error.h"
#include "core/time.h"

namespace glarecam::sun {

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

}  // namespace glarecam::sun
