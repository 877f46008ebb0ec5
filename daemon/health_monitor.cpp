#include "daemon/health_monitor.h"

#include <fmt/format.h>

namespace glarecam::daemon {

void HealthMonitor::start() {
  watchdog_interval_ = notifier_.watchdogInterval();
  next_watchdog_ = clock_.now();
}

HealthMonitor::DiskCheck HealthMonitor::checkDisk(const std::filesystem::path& root,
                                                  std::uint64_t reserve_bytes) {
  next_disk_check_ = clock_.now() + kDiskCheckPeriod;
  const auto state = disk_.probe(root);
  if (!state) return {.pause_reason = state.error().message, .state = std::nullopt};
  return {.pause_reason = diskPauseReason(*state, reserve_bytes, root), .state = *state};
}

std::string HealthMonitor::clockWarning(const sun::ClockStatus& clock) {
  if (clock.synchronised) return {};
  return fmt::format("not synchronised ({}); stacks are flagged", clock.detail);
}

bool HealthMonitor::feedWatchdog(std::optional<SteadyTime> worker_busy_since,
                                 std::chrono::nanoseconds away) {
  const SteadyTime now = clock_.now();
  if (!watchdog_interval_ || now + away < next_watchdog_) return false;
  if (last_ping_ && *last_ping_ == now) return false;  // one ping per instant is enough
  next_watchdog_ = now + *watchdog_interval_ / 2;
  // A stuck worker: systemd's watchdog will restart us.
  if (worker_busy_since && now - *worker_busy_since >= kWorkerStallLimit) return false;
  notifier_.notify("WATCHDOG=1");
  last_ping_ = now;
  return true;
}

std::optional<SteadyTime> HealthMonitor::nextWatchdog() const {
  if (!watchdog_interval_) return std::nullopt;
  return next_watchdog_;
}

}  // namespace glarecam::daemon
