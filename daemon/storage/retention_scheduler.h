// When glarecamd applies [output] retention (retention.h), and what each pass leaves in the
// journal and the status. A pass runs:
//
//   at start             before the status recalls the earlier run (earlier_run.h), so that the
//                        page never shows what the pass has just deleted; first it finishes a
//                        prune of a result's images that a power cut interrupted (whatever the
//                        policy and the clock: result.json already says "pruned")
//   after every stack    finished without an error: one more that may go, one more for the budget
//   below the reserve    when the disk check finds less than the reserve free on a writable disk
//                        and a space budget (max_use_gib) is set: the oldest stacks that may go are
//                        freed, and the disk is looked at again
//
// and never while the clock is not synchronised: ages are told by the clock, and one that ran
// ahead would delete a season. Each deletion is logged with its journal fields
// (GLARECAM_EVENT=retention, GLARECAM_DELETED, GLARECAM_DELETED_KIND, GLARECAM_DELETED_BYTES);
// each pass is recorded in DaemonState (recordRetention: the counts, the shortfall) with the time
// of the last that deleted. Nothing here fails: a deletion that fails is logged and its entry left
// as it was.
#pragma once

#include <cstddef>
#include <optional>
#include <string>

#include "daemon/daemon_clock.h"
#include "daemon/daemon_config.h"
#include "daemon/health_monitor.h"
#include "daemon/status/daemon_status.h"
#include "daemon/storage/disk_space.h"
#include "daemon/storage/output_tree.h"

namespace glarecam::daemon {

class RetentionScheduler {
 public:
  // `output`: the tree's root, its reserve and the policy; `longitude_deg`: the site's, whose
  // solar days retention counts (none: UTC days).
  RetentionScheduler(const DaemonClock& clock, const OutputConfig& output,
                     std::optional<double> longitude_deg);

  // The same after a reload.
  void configure(const OutputConfig& output, std::optional<double> longitude_deg);

  // At start: a prune cut short finished, then apply().
  std::size_t start(DaemonState& state);
  // After every stack: the age rules and the budget, without looking at the disk. How many
  // entries it deleted.
  std::size_t apply(DaemonState& state);

  // The disk under the output root now (HealthMonitor::checkDisk); below the reserve, retention
  // frees what it may first and the disk is looked at again (see above).
  HealthMonitor::DiskCheck checkDisk(HealthMonitor& health, DaemonState& state);

  // The policy in the status page's words: "stacks 7 days, results 30 days, within 40.0 GiB", or
  // "off (nothing is deleted)".
  std::string policyText() const;

 private:
  // One pass; `disk` for the reserve rule (none: the disk not looked at).
  std::size_t pass(DaemonState& state, const std::optional<DiskState>& disk);
  // Logs each deletion with its journal fields.
  static void logDeletions(const RetentionSummary& summary);

  const DaemonClock& clock_;
  OutputConfig output_;
  OutputTree tree_;
  std::optional<double> longitude_deg_;
};

}  // namespace glarecam::daemon
