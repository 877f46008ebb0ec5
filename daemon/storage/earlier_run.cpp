#include "daemon/storage/earlier_run.h"

#include <spdlog/spdlog.h>

namespace glarecam::daemon {

EarlierRun EarlierRun::read(const OutputTree& tree, UtcTime now,
                            std::optional<double> longitude_deg) {
  return {.last_result = newestResult(tree.results()),
          .today = readDayProducts({.root = tree.root(), .longitude_deg = longitude_deg},
                                   solarDay(now, longitude_deg)),
          .unprocessed = tree.unprocessedStacks()};
}

void EarlierRun::recordInto(DaemonState& state) const {
  if (last_result) {
    spdlog::info("glarecamd: last result {} (from an earlier run)", last_result->stack_id);
    state.last_result = *last_result;
  }
  if (today) {
    recordDay(state, *today);
    spdlog::info("glarecamd: day {} (from an earlier run)", state.day);
  }
  if (!unprocessed.empty())
    spdlog::info("glarecamd: processing {} stacks of an earlier run", unprocessed.size());
}

}  // namespace glarecam::daemon
