// glarecamd in two calls: prepareDaemonRig() turns the command line into the daemon's options
// and clock (with `simulate`, the simulated rig (simulated_rig.h) written under --output, on a
// time-lapse clock); runDaemon() runs the daemon (capture_daemon.h) on it with systemd's notifier
// and the statvfs disk probe, signals forwarded into its loop (signal_forwarder.h), and the status
// page when [status] listen (or --status) asks for it (status_server.h), until SIGTERM, the stack
// count or a failure. Two calls because their bad inputs differ for systemd: the
// command line's exits 2, the config's 78 (which systemd does not restart on).
#pragma once

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "core/error.h"
#include "core/time.h"
#include "daemon/capture_daemon.h"
#include "daemon/hardware/simulated_rig.h"

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
  std::optional<ListenAddress> status_listen;        // overrides [status] listen
  // Override [output]: retention by space alone within this budget, and the reserve.
  std::optional<double> max_use_gib;
  std::optional<std::int64_t> reserve_mb;
  // The simulated rig instead of a config: its camera, its clock's start and speed.
  bool simulate = false;
  std::optional<std::string> simulated_camera;
  std::optional<UtcTime> simulation_start;
  double time_lapse = kDefaultTimeLapse;

  // The first problem in words (kBadInput), or nothing.
  Status validate() const;
};

// The options and clock the daemon runs on. Errors: kBadInput for bad options (exit 2), anything
// else a failure (exit 1).
struct DaemonRig {
  DaemonOptions options;
  std::unique_ptr<DaemonClock> clock;
};
Result<DaemonRig> prepareDaemonRig(const DaemonRunOptions& options);

// Runs until it stops. Errors: kBadInput for an invalid config (exit 78), anything else a failure
// (exit 1: systemd restarts).
Status runDaemon(const DaemonRig& rig);

}  // namespace glarecam::daemon
