#include "daemon/storage/retention_scheduler.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <string>

#include "daemon/journal_sink.h"
#include "daemon/storage/retention.h"

namespace glarecam::daemon {

RetentionScheduler::RetentionScheduler(const DaemonClock& clock, const OutputConfig& output,
                                       std::optional<double> longitude_deg)
    : clock_(clock) {
  configure(output, longitude_deg);
}

void RetentionScheduler::configure(const OutputConfig& output,
                                   std::optional<double> longitude_deg) {
  output_ = output;
  tree_ = OutputTree(output.root);
  longitude_deg_ = longitude_deg;
}

std::size_t RetentionScheduler::start(DaemonState& state) {
  ScopedLogFields fields(LogFields{{"GLARECAM_EVENT", "retention"}});
  const RetentionSummary finished = finishCutShortPrunes(tree_, clock_.utcNow());
  logDeletions(finished);
  for (const std::string& error : finished.errors) spdlog::warn("glarecamd: retention: {}", error);
  for (const RetentionDeletion& deleted : finished.deleted)
    if (deleted.kind == kDeletedResultImages) ++state.result_images_pruned;
  return finished.deleted.size() + apply(state);
}

std::size_t RetentionScheduler::apply(DaemonState& state) { return pass(state, std::nullopt); }

void RetentionScheduler::logDeletions(const RetentionSummary& summary) {
  for (const RetentionDeletion& deleted : summary.deleted) {
    ScopedLogFields deletion(LogFields{{"GLARECAM_DELETED", deleted.name},
                                       {"GLARECAM_DELETED_KIND", deleted.kind},
                                       {"GLARECAM_DELETED_BYTES", std::to_string(deleted.bytes)}});
    spdlog::info("glarecamd: retention deleted {} {} ({}): {}", deleted.kind, deleted.name,
                 formatBytes(deleted.bytes), deleted.reason);
  }
}

HealthMonitor::DiskCheck RetentionScheduler::checkDisk(HealthMonitor& health, DaemonState& state) {
  HealthMonitor::DiskCheck disk = health.checkDisk(output_.root, output_.reserve_bytes);
  if (!disk.pause_reason.empty() && disk.state && !disk.state->read_only &&
      output_.retention.max_use_bytes && pass(state, disk.state) > 0)
    disk = health.checkDisk(output_.root, output_.reserve_bytes);
  return disk;
}

std::string RetentionScheduler::policyText() const {
  const RetentionPolicy& retention = output_.retention;
  std::string policy;
  const auto add = [&policy](const std::string& part) {
    policy += (policy.empty() ? "" : ", ") + part;
  };
  if (retention.keep_stacks_days) add(fmt::format("stacks {} days", *retention.keep_stacks_days));
  if (retention.keep_results_days)
    add(fmt::format("results {} days", *retention.keep_results_days));
  if (retention.max_use_bytes) add("within " + formatBytes(*retention.max_use_bytes));
  return policy.empty() ? "off (nothing is deleted)" : policy;
}

std::size_t RetentionScheduler::pass(DaemonState& state, const std::optional<DiskState>& disk) {
  if (!output_.retention.enabled()) return 0;
  if (!clock_.clockStatus().synchronised) return 0;
  ScopedLogFields fields(LogFields{{"GLARECAM_EVENT", "retention"}});
  const RetentionSummary summary = applyRetention(tree_, output_.retention,
                                                  {.now = clock_.utcNow(),
                                                   .longitude_deg = longitude_deg_,
                                                   .disk = disk,
                                                   .reserve_bytes = output_.reserve_bytes});
  logDeletions(summary);
  recordRetention(state, summary, disk.has_value());
  if (!summary.deleted.empty()) state.retention_last_time = clock_.utcNow();
  return summary.deleted.size();
}

}  // namespace glarecam::daemon
