#include "daemon/storage/day_budget.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <system_error>
#include <vector>

#include "daemon/alpha_schedule.h"
#include "daemon/storage/day_products.h"
#include "daemon/storage/disk_space.h"
#include "pipeline/process_stack.h"

namespace glarecam::daemon {

namespace fs = std::filesystem;

namespace {

constexpr std::chrono::hours kDay{24};

}  // namespace

std::optional<DayEstimate> estimateDayStacks(const ScheduleConfig& schedule,
                                             const std::optional<sun::SiteLocation>& site,
                                             const std::optional<sun::ModuleOrientation>& module,
                                             UtcTime day_start, double wall_per_steady) {
  if (schedule.mode == ScheduleMode::kButton || !site) return std::nullopt;
  if (schedule.mode == ScheduleMode::kAlphaTargets) {
    const std::size_t targets = schedule.alpha_targets_deg.size();
    if (module) {
      const auto crossings =
          alphaCrossings(*site, *module, day_start, kDay, schedule.alpha_targets_deg);
      if (crossings)
        return DayEstimate{double(crossings->size()), fmt::format("{} α targets crossed {} times",
                                                                  targets, crossings->size())};
    }
    return DayEstimate{2.0 * double(targets),
                       fmt::format("{} α targets, morning and afternoon", targets)};
  }
  // The interval: the minutes a stack may be taken, over the interval in wall time.
  int usable_steps = 0;
  for (UtcTime t = day_start; t < day_start + kDay; t += kDayBudgetStep) {
    const auto position = sun::solarPosition(t, *site);
    if (!position || position->elevation_deg <= 0) continue;
    if (module &&
        sun::incidenceAngleDeg(*module, {position->elevation_deg, position->azimuth_deg}) >=
            schedule.max_alpha_deg)
      continue;
    ++usable_steps;
  }
  const double hours = usable_steps * std::chrono::duration<double>(kDayBudgetStep).count() / 3600;
  const double interval_s =
      std::chrono::duration<double>(schedule.interval).count() * std::max(wall_per_steady, 1e-9);
  // The slots of the interval's grid within the hours: one more than the gaps between them,
  // depending on where the grid falls (the larger count: a budget is checked against the worst).
  const double slots = usable_steps > 0 ? std::floor(hours * 3600 / interval_s) + 1 : 0.0;
  return DayEstimate{slots, fmt::format("every {:.0f} s over {:.1f} h of {}", interval_s, hours,
                                        module ? "sun on the module" : "sun")};
}

std::optional<std::uint64_t> newestStackBytes(const OutputTree& tree) {
  std::error_code error;
  std::optional<fs::path> newest, newest_processed;
  for (fs::directory_iterator it(tree.stacks(), error), end; !error && it != end;
       it.increment(error)) {
    const fs::path& path = it->path();
    if (!stackDay(path.filename().string(), std::nullopt) || !it->is_directory(error)) continue;
    if (!newest || path.filename() > newest->filename()) newest = path;
    std::error_code missing;
    const bool processed =
        fs::is_regular_file(tree.results() / path.filename() / pipeline::kResultFileName, missing);
    if (processed && (!newest_processed || path.filename() > newest_processed->filename()))
      newest_processed = path;
  }
  // A stack with its result, when there is one: a stack being processed has only half its bytes.
  const std::optional<fs::path>& measured = newest_processed ? newest_processed : newest;
  if (!measured) return std::nullopt;
  return treeBytes(*measured) + treeBytes(tree.results() / measured->filename());
}

std::optional<std::string> dayBudgetWarning(std::uint64_t budget_bytes, const DayEstimate& day,
                                            std::uint64_t stack_bytes) {
  if (stack_bytes == 0 || day.stacks <= 0) return std::nullopt;
  const double fit = std::floor(double(budget_bytes) / double(stack_bytes));
  if (fit >= day.stacks) return std::nullopt;
  return fmt::format(
      "max_use_gib ({}) holds about {:.0f} stacks with their results ({} each), fewer than the "
      "{:.0f} a day the schedule takes ({}): capture will pause every day once the budget is "
      "full; raise max_use_gib, or capture less often",
      formatBytes(budget_bytes), fit, formatBytes(stack_bytes), day.stacks, day.basis);
}

}  // namespace glarecam::daemon
