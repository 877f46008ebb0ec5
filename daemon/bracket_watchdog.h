// systemd's watchdog as the capture loop feeds it: at every step of the loop, and before each
// bracket, which the loop cannot leave to ping. HealthMonitor keeps the cadence (a ping at half
// WatchdogSec, none for a stuck worker); this class foresees how long a bracket will keep the loop
// away, so that a ping which would fall due during it is sent before it starts.
//
// The estimate: the last good bracket's length and half as much again (an auto-bracket's
// re-bracket, a slower transfer), at least the bracket's fixed exposures. Before the first good
// bracket an auto-bracket has no exposures to add up and counts as long (kUnknownBracket): a ping
// always goes before it. A failed bracket says nothing of the length and is not recorded. So
// brackets of up to half the watchdog interval that run no longer than the estimate keep the
// cadence; a longer one, or a wedged camera, lets the heartbeat lapse and systemd restarts the
// daemon, as it should.
//
// Nothing here fails: feeding reports whether a ping was sent, for the daemon's count.
#pragma once

#include <chrono>
#include <optional>

#include "capture/bracketer.h"
#include "daemon/daemon_clock.h"
#include "daemon/health_monitor.h"

namespace glarecam::daemon {

// Longer than any watchdog interval: a bracket of unknown length gets a ping before it.
inline constexpr std::chrono::nanoseconds kUnknownBracket = std::chrono::hours(24);

class BracketWatchdog {
 public:
  explicit BracketWatchdog(HealthMonitor& health) : health_(health) {}

  // Between brackets: WATCHDOG=1 when one is due and the worker is not stuck
  // (`worker_busy_since`: StackWorker::busySince()). True when a ping was sent.
  bool feed(std::optional<SteadyTime> worker_busy_since);
  // Before a bracket of `settings`: also when a ping would fall due before its expected end.
  bool feedBeforeBracket(const capture::CaptureSettings& settings,
                         std::optional<SteadyTime> worker_busy_since);

  // A bracket that succeeded, and how long it kept the loop.
  void recordBracket(std::chrono::nanoseconds length) { last_bracket_ = length; }

  // How long a bracket of `settings` will keep the loop, as the estimate above.
  std::chrono::nanoseconds expectedBracket(const capture::CaptureSettings& settings) const;

 private:
  HealthMonitor& health_;
  std::optional<std::chrono::nanoseconds> last_bracket_;  // none before the first good one
};

}  // namespace glarecam::daemon
