// What glarecamd watches besides its schedule: the disk it writes to, the clock the sun's
// position rests on, and systemd's watchdog.
//
//   disk      free space against [output] reserve and a read-only mount, looked at every
//             kDiskCheckPeriod and before every capture (disk_space.h)
//   clock     whether the wall clock is synchronised (only a [site] needs it: α from the sun)
//   watchdog  WATCHDOG=1 at half systemd's WatchdogSec, from the event loop itself and only while
//             the stack worker is not stuck: a wedged camera or a hung disk stops the heartbeat,
//             and systemd restarts the daemon
//
// It decides nothing about capture; the daemon pauses and resumes on what it reports.
#pragma once

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include "daemon/daemon_clock.h"
#include "daemon/service_notifier.h"
#include "daemon/storage/disk_space.h"

namespace glarecam::daemon {

// How often the loop looks at the disk while nothing else wakes it.
inline constexpr std::chrono::seconds kDiskCheckPeriod{10};
// A worker job running longer than this is stuck (a hung disk): the watchdog is no longer fed.
inline constexpr std::chrono::minutes kWorkerStallLimit{15};

class HealthMonitor {
 public:
  HealthMonitor(const DaemonClock& clock, ServiceNotifier& notifier, DiskProbe& disk)
      : clock_(clock), notifier_(notifier), disk_(disk) {}

  // Reads systemd's watchdog interval (none: no heartbeat) and makes the first ping due now.
  void start();

  // The disk under `root` now: why capture must pause (empty: it may go on), and its state
  // when it could be read. The next periodic look is due kDiskCheckPeriod from now.
  struct DiskCheck {
    std::string pause_reason;
    std::optional<DiskState> state;
  };
  DiskCheck checkDisk(const std::filesystem::path& root, std::uint64_t reserve_bytes);
  SteadyTime nextDiskCheck() const { return next_disk_check_; }

  // Why the wall clock cannot be trusted ("not synchronised (...); stacks are flagged"), or empty.
  // `clock`: the rig's clock's state (rigClockStatus, simulated_rig.h).
  static std::string clockWarning(const sun::ClockStatus& clock);

  // Sends WATCHDOG=1 when a ping is due and the worker is not stuck (`worker_busy_since`: when
  // its running job started); true when it sent one. `away`: how long the loop is about to be
  // busy (a bracket, which it cannot leave to ping): a ping that would fall due meanwhile is sent
  // now, so that the cadence holds across brackets of up to half the interval.
  bool feedWatchdog(std::optional<SteadyTime> worker_busy_since,
                    std::chrono::nanoseconds away = {});
  // The next ping, while systemd asks for them.
  std::optional<SteadyTime> nextWatchdog() const;

 private:
  const DaemonClock& clock_;
  ServiceNotifier& notifier_;
  DiskProbe& disk_;
  std::optional<std::chrono::microseconds> watchdog_interval_;
  SteadyTime next_watchdog_{};
  std::optional<SteadyTime> last_ping_;
  SteadyTime next_disk_check_{};
};

}  // namespace glarecam::daemon
