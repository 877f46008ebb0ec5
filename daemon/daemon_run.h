// glarecamd as one call: the daemon (capture_daemon.h) on the machine's clock, systemd's notifier
// and the statvfs disk probe, with signals forwarded into its loop (signal_forwarder.h) — or, with
// `simulate`, on the simulated rig (simulated_rig.h) and a time-lapse clock. Runs until SIGTERM,
// the stack count or a failure. Errors: kBadInput for an invalid config (glarecamd exits 78, which
// systemd does not restart on), anything else a failure (exit 1: systemd restarts).
#pragma once

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include "core/error.h"
#include "core/time.h"
#include "daemon/simulated_rig.h"

namespace glarecam::daemon {

// The longest --interval (a week, as [schedule] interval_s) and the fastest time lapse (a day in
// under a second).
inline constexpr std::chrono::seconds kMaxDaemonInterval{7 * 86400};
inline constexpr double kMaxTimeLapse = 1e5;

struct DaemonRunOptions {
  std::optional<std::filesystem::path> config_path;  // default /etc/glarecam/glarecam.toml
  std::optional<std::filesystem::path> output_root;  // overrides [output] root
  std::optional<std::chrono::seconds> interval;      // overrides [schedule]: a fixed interval
  std::optional<std::uint64_t> max_stacks;           // stop after this many stacks
  // The simulated rig instead of a config: its camera, its clock's start and speed.
  bool simulate = false;
  std::optional<std::string> simulated_camera;
  std::optional<UtcTime> simulation_start;
  double time_lapse = kDefaultTimeLapse;

  // The first problem in words (kBadInput), or nothing.
  Status validate() const;
};

Status runDaemon(const DaemonRunOptions& options);

}  // namespace glarecam::daemon
