// Local civil time for a glare report (docs/hazard.md, "Times"): the hazard counts in local
// standard time (hazard.md: glare reports use it, and a day is a standard day), but a client
// reads clock times, which in most of Europe and North America are an hour later in summer.
// A rule gives the daylight-saving period of each year:
//   - eu: from 01:00 UTC on the last Sunday of March to 01:00 UTC on the last Sunday of October
//     (Directive 2000/84/EC of the European Parliament and of the Council, Articles 2 and 3);
//   - us: from 02:00 local standard time on the second Sunday of March to 02:00 local daylight
//     time on the first Sunday of November (US Energy Policy Act of 2005, section 110, in force
//     since 2007; Canada's provinces that observe daylight saving time follow it);
//   - none: standard time all year.
// Daylight saving time is standard time plus one hour under both rules.
#pragma once

#include <string>
#include <string_view>

#include "core/error.h"
#include "core/time.h"

namespace glarecam::hazard {

enum class DaylightSaving { kNone, kEu, kUs };

std::string_view daylightSavingName(DaylightSaving rule);  // "none", "eu", "us"
// "none", "eu" or "us"; kBadInput naming `what` (the option) otherwise.
Result<DaylightSaving> parseDaylightSaving(std::string_view text, std::string_view what);

// Whether the rule's daylight saving time is in force at `utc` where standard time is UTC +
// `standard_offset_h`.
bool inDaylightSaving(DaylightSaving rule, UtcTime utc, double standard_offset_h);
// The civil time's offset from UTC at `utc`: standard, or an hour more in daylight saving time.
double civilOffsetH(DaylightSaving rule, UtcTime utc, double standard_offset_h);

}  // namespace glarecam::hazard
