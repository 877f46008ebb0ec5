// What a glarecamd that starts again finds of the run before it, read back from the output tree
// once at start, for the status to show until this run has its own:
//
//   last result   the newest result on disk (results/<id>/result.json): the last stack
//                 processed, its brief and its Figure-9 picture
//   today         when it starts during a day, that day's products as the earlier run left them
//                 (days/<today>/: the day's stack count and whether it has a data sheet); a day
//                 is the site's mean solar day, as day_products.h counts days
//   unprocessed   the stacks the earlier run left without a result or a .failed note, by name:
//                 the worker processes them first (catch-up)
//
// It is read after retention's pass at start (retention_scheduler.h), so that it never names what
// that pass deleted. Reading never fails: what cannot be read is not recalled, and the status page
// says "none yet" as on a first start. The counters of written, processed and failed stacks are
// this run's and start at nought.
#pragma once

#include <filesystem>
#include <optional>
#include <vector>

#include "core/time.h"
#include "daemon/status/daemon_status.h"
#include "daemon/status/result_brief.h"
#include "daemon/storage/day_products.h"
#include "daemon/storage/output_tree.h"

namespace glarecam::daemon {

struct EarlierRun {
  std::optional<LastResult> last_result{};
  std::optional<DaySummary> today{};
  std::vector<std::filesystem::path> unprocessed{};

  // Reads `tree` at `now`; `longitude_deg`: the site's, whose solar day today is (none: UTC).
  static EarlierRun read(const OutputTree& tree, UtcTime now, std::optional<double> longitude_deg);

  // Into `state` (its last result, the day's line, count and sheet), logged ("glarecamd: last
  // result … (from an earlier run)", the day, how many stacks are to be processed).
  void recordInto(DaemonState& state) const;
};

}  // namespace glarecam::daemon
