// The settings check retention's budget gets at start: can max_use_gib hold one day of stacks?
// Retention by value frees everything of past days before it gives up (retention.h), but never
// today's stacks: a budget smaller than one day's stacks and their results pauses capture every
// afternoon. glarecamd warns at start (and after the run's first stack when the output holds none
// yet) with the estimate it rests on:
//
//   stacks a day   [schedule] interval: the day's minutes with the sun up and, the module's
//                  orientation known, α below max_alpha_deg, over the interval in wall time (a
//                  time lapse shortens it); α targets: the day's crossings (the module known),
//                  else two per target (morning and afternoon); the button: none, no check
//   bytes a stack  the newest processed stack on disk and its result (the newest stack when none
//                  is processed yet)
#pragma once

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include "core/error.h"
#include "core/time.h"
#include "daemon/daemon_config.h"
#include "daemon/storage/output_tree.h"
#include "sun/incidence_angle.h"
#include "sun/solar_position.h"

namespace glarecam::daemon {

// The step the day's sun is sampled at for the estimate.
inline constexpr std::chrono::minutes kDayBudgetStep{5};

struct DayEstimate {
  double stacks = 0;  // a day's stacks, as the schedule takes them
  std::string basis;  // "every 600 s over 14.6 h of sun", "16 α targets crossed 32 times"
};

// What the schedule takes on the solar day that begins at `day_start` (UTC, the site's mean
// midnight). `wall_per_steady`: wall seconds per steady second (1 on a real rig, the time lapse
// on the simulated one; the interval runs on the steady clock). Nullopt in button mode, or
// without a site for an interval or α targets.
std::optional<DayEstimate> estimateDayStacks(const ScheduleConfig& schedule,
                                             const std::optional<sun::SiteLocation>& site,
                                             const std::optional<sun::ModuleOrientation>& module,
                                             UtcTime day_start, double wall_per_steady);

// The bytes of the newest processed stack in the tree (by id) with its result, else of the newest
// stack; nullopt when there is none.
std::optional<std::uint64_t> newestStackBytes(const OutputTree& tree);

// The warning when `budget_bytes` cannot hold `day` stacks of `stack_bytes` each, or nullopt:
// "max_use_gib (200.0 MiB) holds about 22 stacks with their results (9.1 MiB each), fewer than
// the 36 a day the schedule takes (every 7200 s over 14.6 h of sun): capture will pause every
// day once the budget is full; raise max_use_gib, or capture less often".
std::optional<std::string> dayBudgetWarning(std::uint64_t budget_bytes, const DayEstimate& day,
                                            std::uint64_t stack_bytes);

}  // namespace glarecam::daemon
