#include "hazard/criteria.h"

#include <algorithm>

#include "core/spelling.h"

namespace glarecam::hazard {

const std::vector<Criterion>& knownCriteria() {
  static const std::vector<Criterion> criteria{
      {.id = "lai",
       .title = "LAI, Hinweise zur Messung, Beurteilung und Minderung von Lichtimmissionen, "
                "Anhang 2 (Germany)",
       .max_minutes_per_day = 30,
       .max_hours_per_year = 30,
       .exceeded_verdict = "significant",
       .within_verdict = "not significant"},
      {.id = "ch",
       .title = "Swiss practice (courts): 30 minutes per day, 50 hours per year",
       .max_minutes_per_day = 30,
       .max_hours_per_year = 50,
       .exceeded_verdict = "not tolerable",
       .within_verdict = "tolerable"},
  };
  return criteria;
}

Result<std::vector<Criterion>> parseCriteria(std::string_view list, std::string_view what) {
  const std::string where(what);
  std::vector<std::string> ids;
  for (const Criterion& criterion : knownCriteria()) ids.push_back(criterion.id);
  std::vector<Criterion> chosen;
  std::size_t start = 0;
  while (start <= list.size()) {
    const std::size_t comma = std::min(list.find(',', start), list.size());
    std::string item(list.substr(start, comma - start));
    start = comma + 1;
    item.erase(0, item.find_first_not_of(" \t"));
    item.erase(item.find_last_not_of(" \t") + 1);
    const auto known = std::find_if(knownCriteria().begin(), knownCriteria().end(),
                                    [&](const Criterion& c) { return c.id == item; });
    if (known == knownCriteria().end()) {
      const std::optional<std::string> suggestion = closestSpelling(item, ids);
      return badInput(
          where + ": unknown criterion \"" + item + "\"" +
          (suggestion ? " (did you mean " + *suggestion + "?)" : " (criteria: lai, ch)"));
    }
    if (std::any_of(chosen.begin(), chosen.end(), [&](const Criterion& c) { return c.id == item; }))
      return badInput(where + ": criterion \"" + item + "\" is given twice");
    chosen.push_back(*known);
  }
  return chosen;
}

Verdict assess(const Criterion& criterion, double max_minutes_per_day, double hours_per_year) {
  Verdict verdict;
  verdict.day_exceeded = max_minutes_per_day > criterion.max_minutes_per_day;
  verdict.year_exceeded = hours_per_year > criterion.max_hours_per_year;
  verdict.exceeded = verdict.day_exceeded || verdict.year_exceeded;
  verdict.text = verdict.exceeded ? criterion.exceeded_verdict : criterion.within_verdict;
  return verdict;
}

nlohmann::json criterionJson(const Criterion& criterion) {
  return {{"title", criterion.title},
          {"max_minutes_per_day", criterion.max_minutes_per_day},
          {"max_hours_per_year", criterion.max_hours_per_year}};
}

}  // namespace glarecam::hazard
