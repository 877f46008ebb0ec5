// What glarecamd reads from the rig's config beyond the rig itself (rig/rig_config.h): how to
// capture ([capture]), when ([schedule]), where to write and how much disk to leave free
// ([output]), what to do when something fails ([faults]) and where the status page listens
// ([status]). Every key has a default, so a rig
// config without these sections runs the daemon with them; every key is documented in
// firmware-config/glarecam.toml and docs/operator.md. readConfig() reads the whole file, the rig's
// sections and these, with "FILE:LINE: problem" errors.
#pragma once

#include <array>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "capture/capture_config.h"
#include "core/error.h"
#include "daemon/status/listen_address.h"
#include "daemon/storage/retention.h"
#include "pipeline/limit_curve.h"
#include "rig/rig_config.h"

namespace glarecam::daemon {

// Reads a preset: one "Feature=Value" a line, '#' comments, blank lines; the features joined as
// arv_device_set_features_from_string() takes them. kBadInput naming FILE:LINE for anything else.
Result<std::string> readGenicamPreset(const std::filesystem::path& path);

enum class ScheduleMode {
  kInterval,      // a stack every interval
  kAlphaTargets,  // a stack when α crosses each target as the sun moves (needs [site])
  kButton,        // only on the operator's button (and SIGUSR1)
};

// [schedule]. Whatever the mode, SIGUSR1 takes a stack now, and so does the button when
// `button` is on and the rig has one.
// [output] module when the config names none: the sheets say so; the stacks record no module.
inline constexpr std::string_view kUnnamedModule = "unnamed module";

struct ScheduleConfig {
  ScheduleMode mode = ScheduleMode::kInterval;
  std::chrono::seconds interval{600};
  std::vector<double> alpha_targets_deg;  // default 5, 10, ... 80 (the paper's sweep)
  bool button = true;
  // The limit curve of the method ends at 80° (method.md): a stack beyond it has no glare limit.
  // Interval stacks are taken only below this α; the α targets, the button and SIGUSR1 are not
  // held back.
  double max_alpha_deg = pipeline::kMaxLimitAlphaDeg;
};

// The bounds of [output] reserve_mb and max_use_gib (and of glarecamd's --reserve-mb and
// --max-use-gib).
inline constexpr std::int64_t kMaxReserveMb = std::int64_t{1} << 30;  // a petabyte
inline constexpr double kBytesPerGib = 1024.0 * 1024.0 * 1024.0;
inline constexpr double kMinMaxUseGib = 1.0 / 1024;  // 1 MiB: the smallest budget (tests, a tmpfs)
inline constexpr double kMaxMaxUseGib = 1 << 20;     // a pebibyte

// [output]: OUTPUT/stacks/<id>/, OUTPUT/results/<id>/, OUTPUT/days/<YYYY-MM-DD>/.
struct OutputConfig {
  std::filesystem::path root = "/var/lib/glarecam";
  std::uint64_t reserve_bytes = 1024ull << 20;       // capture pauses below this much free space
  std::string module = std::string(kUnnamedModule);  // the data sheets' and stacks' module name
  unsigned processing_threads = 1;  // the worker's: the camera keeps the other cores
  RetentionPolicy retention;        // keep_stacks_days, keep_results_days, max_use_gib
};

enum class InclinometerFaultPolicy {
  kContinue,  // capture on, the stack's α marked unknown
  kPause,     // no stack until the inclinometer reads again
};

// [faults].
struct FaultConfig {
  InclinometerFaultPolicy inclinometer = InclinometerFaultPolicy::kContinue;
  // A tilt outside [min, max] is implausible (a loose sensor, a module blown over): a fault.
  double min_tilt_deg = 0.0;
  double max_tilt_deg = 90.0;
  // The camera is reopened after a failure with exponential backoff from `camera_backoff`
  // doubling up to `camera_backoff_max`; after `camera_max_failures` failures in a row the daemon
  // exits with status 1 and leaves the restart to systemd.
  int camera_max_failures = 8;
  std::chrono::seconds camera_backoff{2};
  std::chrono::seconds camera_backoff_max{120};
};

// [status]: the operator's status page (status_server.h), off unless `listen` is set.
struct StatusConfig {
  std::optional<ListenAddress> listen{};
};

// The paper's sweep: 5° to 80° in steps of 5°.
std::vector<double> defaultAlphaTargetsDeg();

// The daemon's sections together.
struct DaemonConfig {
  capture::CaptureConfig capture;  // [capture]
  ScheduleConfig schedule{.alpha_targets_deg = defaultAlphaTargetsDeg()};
  OutputConfig output;
  FaultConfig faults;
  StatusConfig status;
};

// The sections of a config file the daemon's reader reads.
inline constexpr std::array<std::string_view, 5> kDaemonSections{"capture", "faults", "output",
                                                                 "schedule", "status"};

// A whole glarecam.toml: the rig (rig/rig_config.h) and what glarecamd does with it.
struct Config {
  rig::RigConfig rig;
  DaemonConfig daemon;
};

// Reads the config file at `path`: a section that neither the rig's reader nor the daemon's knows
// is an error, and so is any key or value either finds wrong (kBadInput "FILE:LINE: problem").
Result<Config> readConfig(const std::filesystem::path& path);
// The rig's part of it, the whole file validated: for the commands that use only the rig.
Result<rig::RigConfig> readRigConfig(const std::filesystem::path& path);

}  // namespace glarecam::daemon
