#include "daemon/bracket_watchdog.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace glarecam::daemon {

bool BracketWatchdog::feed(std::optional<SteadyTime> worker_busy_since) {
  return health_.feedWatchdog(worker_busy_since);
}

bool BracketWatchdog::feedBeforeBracket(const capture::CaptureSettings& settings,
                                        std::optional<SteadyTime> worker_busy_since) {
  return health_.feedWatchdog(worker_busy_since, expectedBracket(settings));
}

std::chrono::nanoseconds BracketWatchdog::expectedBracket(
    const capture::CaptureSettings& settings) const {
  double exposures_us = 0;
  for (const double exposure_us : settings.exposures_us.value_or(std::vector<double>{}))
    exposures_us += exposure_us;
  const std::chrono::nanoseconds exposures(std::llround(exposures_us * 1e3));
  if (!last_bracket_) return exposures_us > 0 ? exposures : kUnknownBracket;
  // A bracket can run longer than the last one (an auto-bracket's re-bracket, a slower
  // transfer): half as long again.
  const auto last = std::chrono::duration_cast<std::chrono::nanoseconds>(*last_bracket_ * 1.5);
  return std::max(exposures, last);
}

}  // namespace glarecam::daemon
