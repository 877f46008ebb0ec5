#include "hazard/civil_time.h"

#include <chrono>
#include <cmath>

namespace glarecam::hazard {
namespace {

using std::chrono::days;
using std::chrono::hours;
using std::chrono::microseconds;
using std::chrono::sys_days;

constexpr double kDaylightSavingShiftH = 1;

// The last Sunday of `month` and the `n`th Sunday of it (n from 1).
sys_days lastSunday(std::chrono::year year, std::chrono::month month) {
  return sys_days{year / month / std::chrono::Sunday[std::chrono::last]};
}
sys_days nthSunday(std::chrono::year year, std::chrono::month month, unsigned n) {
  return sys_days{year / month / std::chrono::Sunday[n]};
}

UtcTime at(sys_days day, double hours_utc) {
  return std::chrono::time_point_cast<microseconds>(day) +
         microseconds(std::llround(hours_utc * 3600e6));
}

}  // namespace

std::string_view daylightSavingName(DaylightSaving rule) {
  switch (rule) {
    case DaylightSaving::kNone:
      return "none";
    case DaylightSaving::kEu:
      return "eu";
    case DaylightSaving::kUs:
      return "us";
  }
  return "none";
}

Result<DaylightSaving> parseDaylightSaving(std::string_view text, std::string_view what) {
  for (const DaylightSaving rule :
       {DaylightSaving::kNone, DaylightSaving::kEu, DaylightSaving::kUs})
    if (text == daylightSavingName(rule)) return rule;
  return badInput(std::string(what) + " \"" + std::string(text) +
                  "\" is not one of none, eu (the EU's rule), us (the US and Canada's)");
}

bool inDaylightSaving(DaylightSaving rule, UtcTime utc, double standard_offset_h) {
  if (rule == DaylightSaving::kNone) return false;
  // The year of the instant in local standard time: its summer is the one that counts.
  const auto local = utc + microseconds(std::llround(standard_offset_h * 3600e6));
  const std::chrono::year year =
      std::chrono::year_month_day{std::chrono::floor<days>(local)}.year();
  if (rule == DaylightSaving::kEu) {
    return utc >= at(lastSunday(year, std::chrono::March), 1) &&
           utc < at(lastSunday(year, std::chrono::October), 1);
  }
  // US: 02:00 standard on the second Sunday of March; 02:00 daylight (01:00 standard) on the
  // first Sunday of November.
  return utc >= at(nthSunday(year, std::chrono::March, 2), 2 - standard_offset_h) &&
         utc < at(nthSunday(year, std::chrono::November, 1), 1 - standard_offset_h);
}

double civilOffsetH(DaylightSaving rule, UtcTime utc, double standard_offset_h) {
  return standard_offset_h +
         (inDaylightSaving(rule, utc, standard_offset_h) ? kDaylightSavingShiftH : 0);
}

}  // namespace glarecam::hazard
