// The assessment criteria a glare report applies to an observer's minutes (../shared/docs/
// hazard.md, "Counting and criteria"), each with its thresholds written out:
//   - lai: Germany, LAI "Hinweise zur Messung, Beurteilung und Minderung von Lichtimmissionen",
//     Anhang 2: significant when glare lasts more than 30 minutes on any day or more than 30
//     hours in the year;
//   - ch: Swiss guidance as applied by courts: tolerable up to 30 minutes per day on any number
//     of days and 50 hours per year in total.
// Both limits are inclusive: exactly 30 minutes on a day does not exceed them.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "core/error.h"

namespace glarecam::hazard {

struct Criterion {
  std::string id;     // "lai", "ch"
  std::string title;  // what the report cites
  double max_minutes_per_day = 0;
  double max_hours_per_year = 0;
  std::string exceeded_verdict, within_verdict;  // "significant" / "not significant"
};

// The known criteria, in this order.
const std::vector<Criterion>& knownCriteria();

// "lai,ch" → those criteria; kBadInput naming `what` ("--criteria") for an unknown or repeated id.
Result<std::vector<Criterion>> parseCriteria(std::string_view list, std::string_view what);

struct Verdict {
  bool exceeded = false;
  bool day_exceeded = false, year_exceeded = false;
  std::string text;  // the criterion's verdict in words
};

Verdict assess(const Criterion& criterion, double max_minutes_per_day, double hours_per_year);

// {"title", "max_minutes_per_day", "max_hours_per_year"}.
nlohmann::json criterionJson(const Criterion& criterion);

}  // namespace glarecam::hazard
